# mbgen.monitor and mbgen.monitor_output_only: the command's mbgen-monitor/1 and mbgen-monitor-operational/1 content
# (the same code) on short series made by the independent truth generator (scripts/truthgen), and the command's
# refusals with its messages.
import json
import subprocess
import sys

import pytest

import mbgen
from conftest import MDOF2, ROOT

MODEL = MDOF2 / "mdof2.mdl"
TRUTHGEN = ROOT / "scripts" / "truthgen" / "truthgen.py"
PYTHON = "/usr/bin/python3"  # Debian's, with numpy and scipy, as the monitor's CTest cases use


def truthgen(*args):
    subprocess.run([PYTHON, str(TRUTHGEN), *args], check=True, capture_output=True)


@pytest.fixture(scope="module")
def frf_series(tmp_path_factory):
    # Five FRF sets of mdof2's nominal truth, 40 dB noise; k11 15 % down in the last two.
    d = tmp_path_factory.mktemp("frf_series")
    files = []
    for i in range(5):
        path = d / f"set{i}.csv"
        step = ["--set", "k11=1105000"] if i >= 3 else []
        truthgen("--example", "mdof2", "--case", "nominal", "--kind", "frf", "--snr-db", "40", "--seed",
                 str(900 + i), *step, "-o", str(path))
        # Its `# set` lines (the truth's values, which mbgen would take as the model's) are left out.
        path.write_text("".join(line for line in path.read_text().splitlines(True) if not line.startswith("# set ")))
        files.append(path)
    return files


@pytest.fixture(scope="module")
def oma_series(tmp_path_factory):
    # Ten output-only records of mdof2 (20 s each) whose stiffnesses follow a temperature; k11 4 % down from set 7.
    d = tmp_path_factory.mktemp("oma_series")
    truthgen("--example", "mdof2", "--case", "nominal", "--kind", "oma", "--draw", "1", "--duration", "20",
             "--series", "10", "--temperature", "20,4,12,0.6,0.3", "--seed", "3", "--change", "k11=0.96@7",
             "-o", str(d / "s.csv"))
    return sorted(d.glob("s_*.csv"))


def command_json(mbgen_command, tmp_path, args):
    out = tmp_path / "m.json"
    subprocess.run([mbgen_command, "monitor", *map(str, args), "--json", str(out)], check=True, capture_output=True)
    return json.loads(out.read_text())


def test_monitor_is_the_commands(frf_series, mbgen_command, tmp_path):
    result = mbgen.monitor(MODEL, frf_series, baseline=3, starts=4, warm_starts=2, diagnosis=False)
    assert result["schema"] == "mbgen-monitor/1"
    assert len(result["series"]) == 5
    args = [MODEL, "--baseline", "3", "--starts", "4", "--warm-starts", "2", "--no-diagnosis"]
    for f in frf_series:
        args += ["--data", f]
    assert result == command_json(mbgen_command, tmp_path, args)
    # The 15 % stiffness step at set 3 is found there, naming k11.
    assert [c["index"] for c in result["changes"]] == [3]
    assert "k11" in result["changes"][0]["parameters"]


def test_monitor_with_a_method_start_is_the_commands(frf_series, mbgen_command, tmp_path):
    # --method: each set's fit also starts from the two-step estimate on it; the same change is found.
    result = mbgen.monitor(MODEL, frf_series, baseline=3, starts=4, warm_starts=2, diagnosis=False, method="two-step")
    assert result["start_method"] == "two-step"
    args = [MODEL, "--baseline", "3", "--starts", "4", "--warm-starts", "2", "--no-diagnosis", "--method", "two-step"]
    for f in frf_series:
        args += ["--data", f]
    assert result == command_json(mbgen_command, tmp_path, args)
    assert [c["index"] for c in result["changes"]] == [3]
    assert "k11" in result["changes"][0]["parameters"]
    with pytest.raises(mbgen.FitError, match="--method ekf needs time records"):
        mbgen.monitor(MODEL, frf_series, method="ekf")


def test_monitor_output_only_is_the_commands(oma_series, mbgen_command, tmp_path):
    result = mbgen.monitor_output_only(oma_series, baseline=5, model=MODEL)
    assert result["schema"] == "mbgen-monitor-operational/1"
    args = ["--output-only", "--baseline", "5", "--model", MODEL]
    for f in oma_series:
        args += ["--data", f]
    assert result == command_json(mbgen_command, tmp_path, args)
    # The 4 % step of k11 at set 7 is found there, and the model names k11 among what explains it.
    assert [c["index"] for c in result["changes"]] == [7]
    assert "k11" in result["changes"][0]["explanation"]["named"]
    plain = mbgen.monitor_output_only(oma_series, baseline=5, compensation=False, false_alarm=0.05)
    args = ["--output-only", "--baseline", "5", "--no-compensation", "--false-alarm", "0.05"]
    for f in oma_series:
        args += ["--data", f]
    assert plain == command_json(mbgen_command, tmp_path, args)


def test_refusals(frf_series):
    with pytest.raises(mbgen.UsageError, match=r"--data: monitoring needs more data sets than the baseline's 3"):
        mbgen.monitor(MODEL, frf_series[:3])
    with pytest.raises(mbgen.UsageError, match="--baseline"):
        mbgen.monitor(MODEL, frf_series, baseline=1)
    with pytest.raises(mbgen.UsageError, match="--set: needs --model"):
        mbgen.monitor_output_only(frf_series, set={"k11": 1e6})
    with pytest.raises(mbgen.UsageError, match="--fix, --free and --bound need --model"):
        mbgen.monitor_output_only(frf_series, fix=["k11"])
    with pytest.raises(mbgen.DataError, match="set0.csv: error: monitoring in operation needs time records"):
        mbgen.monitor_output_only(frf_series)
