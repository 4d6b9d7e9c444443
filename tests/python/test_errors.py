# Errors raise mbgen's exceptions (ValueError subclasses) with the command's messages: FILE:LINE:COLUMN for a model.
import subprocess

import numpy as np
import pytest

import mbgen
from conftest import MDOF2

MODEL = MDOF2 / "mdof2.mdl"


def malformed(tmp_path):
    path = tmp_path / "bad.mdl"
    # line 3, column 22: `estimat` is no role
    path.write_text('model bad\n\nparam m = 1.0 "kg"  estimat in [0, 10]\n')
    return path


def test_malformed_model_names_line_and_column(tmp_path):
    path = malformed(tmp_path)
    with pytest.raises(mbgen.ModelError) as caught:
        mbgen.load_model(path)
    text = str(caught.value)
    assert text.startswith(f"{path}:3:21: error: ")  # the line and column of `estimat`
    assert "found `estimat`" in text
    assert isinstance(caught.value, ValueError) and isinstance(caught.value, mbgen.Error)


def test_malformed_model_message_is_the_commands(tmp_path, mbgen_command):
    path = malformed(tmp_path)
    with pytest.raises(mbgen.ModelError) as caught:
        mbgen.load_model(path)
    run = subprocess.run([mbgen_command, "export", str(path)], capture_output=True, text=True)
    assert run.returncode == 1
    assert run.stderr.rstrip("\n") == str(caught.value)


def test_bad_set_value_is_a_usage_error():
    with pytest.raises(mbgen.UsageError, match=r"mbgen: --set: m1=abc: the value must be a decimal number"):
        mbgen.load_model(MODEL, set={"m1": "abc"})
    with pytest.raises(mbgen.UsageError, match="--set"):
        mbgen.load_model(MODEL, set={"m1": float("inf")})


def test_role_refusals():
    with pytest.raises(mbgen.UsageError, match=r"--fix: `c12` is not estimated"):
        mbgen.load_model(MODEL, fix=["c12"])
    with pytest.raises(mbgen.UsageError, match=r"--free: the model has no parameter `nope`"):
        mbgen.load_model(MODEL, free=["nope"])


def test_unknown_parameter_in_params():
    model = mbgen.load_model(MODEL)
    with pytest.raises(mbgen.UsageError, match=r"the model has no parameter `mass`"):
        model.matrices(params={"mass": 1.0})
    with pytest.raises(mbgen.UsageError, match="finite"):
        model.frf([10.0], params={"m1": float("nan")})


def test_singular_dynamics_name_the_model():
    model = mbgen.load_model(MODEL)
    with pytest.raises(mbgen.ModelError, match=str(MODEL)):
        model.state_space(params={"m1": 0.0})


def test_simulate_checks_its_arrays():
    model = mbgen.load_model(MODEL)
    with pytest.raises(mbgen.UsageError, match="uniformly spaced"):
        model.simulate([0.0, 0.1, 0.3], np.zeros(3))
    with pytest.raises(mbgen.UsageError, match="3 samples x 1 inputs"):
        model.simulate([0.0, 0.1, 0.2], np.zeros((2, 1)))


def test_missing_data_file(tmp_path):
    with pytest.raises(mbgen.DataError, match=str(tmp_path / "none.csv")):
        mbgen.read_data(tmp_path / "none.csv")


def test_method_refusing_the_data():
    with pytest.raises(mbgen.FitError, match=r"time_F1.csv: error: --method frf-output-error needs FRF data"):
        mbgen.fit(MODEL, MDOF2 / "data" / "time_F1.csv", method="frf-output-error")
    with pytest.raises(mbgen.UsageError, match="--method"):
        mbgen.fit(MODEL, MDOF2 / "data" / "frf_F1.csv", method="guess")
