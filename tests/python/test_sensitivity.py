# mbgen.sensitivity: the command's mbgen-sensitivity/1 content (the same code) on the mdof2 example, its modes those
# of the model, and the command's refusals with its messages.
import json
import subprocess

import pytest

import mbgen
from conftest import MDOF2

MODEL = MDOF2 / "mdof2.mdl"


def command_json(mbgen_command, tmp_path, *args):
    out = tmp_path / "s.json"
    subprocess.run([mbgen_command, "sensitivity", str(MODEL), "--json", str(out), *args], check=True,
                   capture_output=True)
    return json.loads(out.read_text())


def test_local_is_the_commands(mbgen_command, tmp_path):
    result = mbgen.sensitivity(MODEL)
    assert result["schema"] == "mbgen-sensitivity/1"
    assert result == command_json(mbgen_command, tmp_path)
    # The modes analysed are the model's (computed by Model.modes, another path).
    modes = mbgen.load_model(MODEL).modes()
    assert sorted(m["f_hz"] for m in result["modes"]) == pytest.approx(sorted(modes["f_hz"]), rel=1e-12)


def test_global_and_sweeps_are_the_commands(mbgen_command, tmp_path):
    model = mbgen.load_model(MODEL, fix={"c22": None})
    result = mbgen.sensitivity(model, global_=True, samples=64, seed=5, spread=0.1,
                               sweep={"k11": (1.0e6, 1.5e6, 5)})
    assert result == command_json(mbgen_command, tmp_path, "--fix", "c22", "--global", "--samples", "64", "--seed",
                                  "5", "--spread", "0.1", "--sweep", "k11=1000000.0:1500000.0:5")
    assert len(result["feature_maps"]) == 1
    assert mbgen.sensitivity(MODEL, sweep="k11=1e6:1.5e6:5")["feature_maps"] == result["feature_maps"]


def test_refusals():
    with pytest.raises(mbgen.UsageError, match="--samples, --seed, --spread and --bounds need --global"):
        mbgen.sensitivity(MODEL, samples=64)
    with pytest.raises(mbgen.UsageError, match="--sweep: the model has no parameter `zz`: `zz=1:2:3`"):
        mbgen.sensitivity(MODEL, sweep=["zz=1:2:3"])
    with pytest.raises(mbgen.UsageError, match="--samples"):
        mbgen.sensitivity(MODEL, global_=True, samples=4)
    with pytest.raises(mbgen.ModelError, match=r"mdof2.mdl:\d+:\d+: error: --sweep m1=-1:1:3: outside the bounds"):
        mbgen.sensitivity(MODEL, sweep={"m1": (-1, 1, 3)})
