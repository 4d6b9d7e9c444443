# mbgen.fit, mbgen.modal, mbgen.diagnose: the commands' results on the mdof2 example, the truth recovered, and the
# same JSON as the command writes.
import json
import subprocess

import pytest

import mbgen
from conftest import MDOF2

MODEL = MDOF2 / "mdof2.mdl"
FRF = MDOF2 / "data" / "frf_F1.csv"
TRUTH = json.loads((MDOF2 / "data" / "frf_F1.truth.json").read_text())


@pytest.fixture(scope="module")
def fitted():
    return mbgen.fit(MODEL, FRF)


def test_fit_recovers_the_truth(fitted):
    assert fitted["schema"] == "mbgen-fit/1"
    assert fitted["method"] == "frf-output-error"
    assert fitted["fit"]["converged"]
    estimated = fitted["parameters"]
    assert set(estimated) == {"m1", "m2", "k11", "k22", "k12", "c11", "c22"}  # c12 is fixed
    for name, entry in estimated.items():
        truth = TRUTH["parameters"][name]
        # 40 dB data: within 1 % of the truth, and the priors were 3 to 10 % off it
        assert entry["value"] == pytest.approx(truth, rel=0.01), name
        assert abs(entry["prior"] - truth) > 0.02 * truth, name
        assert abs(entry["value"] - truth) < 5 * entry["std"] + 1e-3 * truth, name
    f = sorted(m["f_hz"] for m in fitted["modes"])
    assert f == pytest.approx([94.06, 169.13], abs=0.05)


def test_fit_json_is_the_commands(fitted, mbgen_command, tmp_path):
    out = tmp_path / "fit.json"
    subprocess.run([mbgen_command, "fit", str(MODEL), "--data", str(FRF), "--json", str(out)], check=True,
                   capture_output=True)
    assert json.loads(out.read_text()) == fitted


def test_fit_given_a_model_with_roles():
    # --fix through the Python arguments: the masses known at the truth, the rest estimated.
    masses = {"m1": TRUTH["parameters"]["m1"], "m2": TRUTH["parameters"]["m2"]}
    model = mbgen.load_model(MODEL, fix=masses)
    result = mbgen.fit(model, [FRF], starts=4, seed=3)
    assert set(result["parameters"]) == {"k11", "k22", "k12", "c11", "c22"}
    assert result["fit"]["seed"] == 3 and result["fit"]["starts"] == 4
    assert result["parameters"]["k11"]["value"] == pytest.approx(TRUTH["parameters"]["k11"], rel=0.01)


def test_modal_finds_the_modes():
    result = mbgen.modal(FRF, band=(50, 250), model=MODEL)
    assert result["schema"] == "mbgen-modal/1"
    f = sorted(m["f_hz"] for m in result["modes"])
    assert f == pytest.approx([94.06, 169.13], abs=0.1)


def test_modal_json_is_the_commands(mbgen_command, tmp_path):
    out = tmp_path / "modal.json"
    subprocess.run([mbgen_command, "modal", "--data", str(FRF), "--band", "50:250", "--json", str(out)], check=True,
                   capture_output=True)
    assert json.loads(out.read_text()) == mbgen.modal([FRF], band="50:250")


@pytest.fixture(scope="module")
def diagnosed():
    return mbgen.diagnose(MODEL, FRF)


def test_diagnose_keeps_the_nominal_model(diagnosed):
    # The data were made from the nominal model itself (frf_F1.truth.json: no hidden effect).
    assert diagnosed["schema"] == "mbgen-diagnosis/1"
    assert diagnosed["verdict"] == "no_extension_justified"
    assert diagnosed["selected"] == []


def test_diagnose_json_is_the_commands(diagnosed, mbgen_command, tmp_path):
    out = tmp_path / "diagnosis.json"
    subprocess.run([mbgen_command, "diagnose", str(MODEL), "--data", str(FRF), "--json", str(out)], check=True,
                   capture_output=True)
    assert json.loads(out.read_text()) == diagnosed


def test_diagnose_with_a_method_start_is_the_commands(diagnosed, mbgen_command, tmp_path):
    # --method: the direct estimate is one more start of the nominal fit; the JSON names it, the verdict stays.
    started = mbgen.diagnose(MODEL, FRF, method="direct")
    assert started["start_method"] == "direct"
    assert "start_method" not in diagnosed
    assert started["verdict"] == diagnosed["verdict"]
    out = tmp_path / "diagnosis.json"
    subprocess.run([mbgen_command, "diagnose", str(MODEL), "--data", str(FRF), "--method", "direct", "--json",
                    str(out)], check=True, capture_output=True)
    assert json.loads(out.read_text()) == started


def test_arx_two_stage_with_the_masses_fixed():
    # The case: arx-two-stage needs M known; fix= makes the masses known without editing the model.
    record = MDOF2 / "data" / "time_F1.csv"
    truth = json.loads((MDOF2 / "data" / "time_F1.truth.json").read_text())["parameters"]
    with pytest.raises(mbgen.FitError, match=r"needs the mass matrix known .* \(--fix NAME=VALUE\)"):
        mbgen.fit(MODEL, record, method="arx-two-stage")
    result = mbgen.fit(MODEL, record, method="arx-two-stage", fix={"m1": truth["m1"], "m2": truth["m2"]})
    assert result["method"] == "arx-two-stage"
    assert set(result["parameters"]) == {"k11", "k22", "k12", "c11", "c22"}
    for k in ["k11", "k22", "k12"]:  # the stiffnesses from the record; its dampings are the method's weak side
        assert result["parameters"][k]["value"] == pytest.approx(truth[k], rel=0.03), k


def test_calls_from_threads(fitted):
    # The interpreter lock is released during a fit; the calls still run one at a time (GiNaC is not thread-safe)
    # and give the results of a call alone.
    import threading

    results = [None] * 4

    def work(k):
        results[k] = mbgen.fit(MODEL, FRF) if k % 2 == 0 else mbgen.load_model(MODEL).parameters

    threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert results[0] == fitted and results[2] == fitted
    assert results[1] == results[3] == mbgen.load_model(MODEL).parameters


def test_fit_with_validation_data_is_the_commands(mbgen_command, tmp_path):
    # A record fitted, the example's FRF of the same truth scored: residual tests of the record, fit % per channel.
    record = MDOF2 / "data" / "time_F1.csv"
    result = mbgen.fit(MODEL, record, starts=2, validate=[FRF], residual_lags=30)
    out = tmp_path / "fit.json"
    subprocess.run([mbgen_command, "fit", str(MODEL), "--data", str(record), "--starts", "2", "--validate", str(FRF),
                    "--residual-lags", "30", "--json", str(out)], check=True, capture_output=True)
    assert json.loads(out.read_text()) == result
    assert result["residual_tests"]["max_lag"] == 30
    assert [c["output"] for c in result["residual_tests"]["channels"]] == ["d1", "d2"]
    [scored] = result["validation"]
    assert scored["kind"] == "frf"
    assert scored["fit_percent"]["d1/F1"] > 95 and scored["fit_percent"]["d2/F1"] > 95
    with pytest.raises(ValueError, match="--residual-lags"):
        mbgen.fit(MODEL, record, residual_lags=0)
