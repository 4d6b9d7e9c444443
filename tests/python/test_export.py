# Model.export: `mbgen export`'s content (the same code): its arrays equal to the model's own numbers (Model.matrices,
# state_space, modes, frf, computed by other calls), its JSON equal to the command's, a fit result's estimate taken.
import json
import subprocess

import numpy as np
import pytest

import mbgen
from conftest import MDOF2

MODEL = MDOF2 / "mdof2.mdl"


@pytest.fixture(scope="module")
def model():
    return mbgen.load_model(MODEL)


def command_json(mbgen_command, *args):
    run = subprocess.run([mbgen_command, "export", str(MODEL), *args], check=True, capture_output=True, text=True)
    return json.loads(run.stdout)


def test_matrices_are_the_models(model):
    exported = model.export()
    assert exported["schema"] == "mbgen-export/1" and exported["what"] == "matrices"
    direct = model.matrices()
    for name in ("M", "C", "K", "B", "Cd", "Cv", "Ca"):
        assert isinstance(exported[name], np.ndarray), name
        assert exported[name].shape == direct[name].shape, name
        assert np.array_equal(exported[name], direct[name]), name
    assert exported["coordinates"] == model.coordinates and exported["outputs"] == model.outputs
    assert exported["parameters"]["k11"] == model.parameters["k11"]["value"]


def test_state_space_modes_and_frf_are_the_models(model):
    ss, direct = model.export("state-space"), model.state_space()
    for name in "ABCD":
        assert ss[name].shape == direct[name].shape and np.array_equal(ss[name], direct[name]), name
    modes, own = model.export("modes")["modes"], model.modes()
    assert np.array_equal(modes["f_hz"], own["f_hz"]) and np.array_equal(modes["zeta"], own["zeta"])
    assert np.array_equal(modes["eigenvalues"], own["eigenvalues"])
    assert np.array_equal(modes["shapes"], own["shapes"])
    frf = model.export("frf", frf=(10, 400, 40))["frf"]
    assert frf["f_hz"][0] == 10 and frf["f_hz"][-1] == 400 and len(frf["f_hz"]) == 40
    assert frf["H"].shape == (40, 2, 1)
    assert np.allclose(frf["H"], model.frf(frf["f_hz"]), rtol=1e-14, atol=0)


def test_json_is_the_commands(model, mbgen_command):
    for what, extra in (("matrices", []), ("state-space", []), ("modes", []), ("frf", ["--frf", "5:300:7"])):
        mine = model.export(what, frf="5:300:7" if what == "frf" else None, json=True)
        assert mine == command_json(mbgen_command, "--what", what, *extra), what


def test_set_values_are_exported(mbgen_command):
    # The model's --set values (and --fix's) are those exported, as the command's --set.
    model = mbgen.load_model(MODEL, set={"k11": 1.2e6}, fix={"m1": 1.25})
    mine = model.export(json=True)
    assert mine == command_json(mbgen_command, "--set", "k11=1200000.0", "--set", "m1=1.25")
    assert mine["parameters"]["k11"] == 1.2e6 and mine["parameters"]["m1"] == 1.25


def test_at_a_fit_result(model, mbgen_command, tmp_path):
    # A fit result's values replace the model's: the matrices at them are the model's at those values.
    result = {"schema": "mbgen-fit/1", "parameters": {"k11": {"value": 1.1e6}, "m2": {"value": 0.95}}}
    path = tmp_path / "fit.json"
    path.write_text(json.dumps(result))
    at_path, at_dict = model.export(fit_result=path), model.export(fit_result=result)
    direct = model.matrices(params={"k11": 1.1e6, "m2": 0.95})
    for name in ("M", "K", "C"):
        assert np.array_equal(at_path[name], direct[name]) and np.array_equal(at_dict[name], direct[name]), name
    assert model.export(fit_result=path, json=True) == command_json(mbgen_command, "--fit-result", str(path))


def test_refusals(model, tmp_path):
    with pytest.raises(mbgen.UsageError, match="--frf: --what frf needs the grid: --frf LO:HI:N"):
        model.export("frf")
    with pytest.raises(mbgen.UsageError, match="--frf: only with --what frf"):
        model.export("modes", frf=(1, 2, 3))
    with pytest.raises(mbgen.UsageError, match="--frf: expected LO:HI:N"):
        model.export("frf", frf=(5, 1, 3))
    with pytest.raises(mbgen.UsageError, match="--what"):
        model.export("poles")
    with pytest.raises(mbgen.DataError, match="not a fit result"):
        model.export(fit_result={"schema": "mbgen-diagnosis/1"})
    with pytest.raises(mbgen.DataError, match="parameter `zz` of the fit result is not in the model"):
        model.export(fit_result={"schema": "mbgen-fit/1", "parameters": {"zz": {"value": 1}}})
    with pytest.raises(mbgen.DataError, match="cannot read the file"):
        model.export(fit_result=tmp_path / "none.json")
