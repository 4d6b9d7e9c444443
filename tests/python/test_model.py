# mbgen.load_model and Model: the numbers of examples/mdof2/mdof2.mdl against the matrices written out by hand from
# the model file (two masses on beams k11, c11 and k22, c22 to the wall, joined by the helix k12, c12).
import json

import numpy as np
import pytest

import mbgen
from conftest import MDOF2

MODEL = MDOF2 / "mdof2.mdl"
NOMINAL = dict(m1=1.39, m2=1.09, k11=1.38e6, k22=0.24e6, k12=0.12e6, c11=13.42, c22=0.47, c12=0.0)


def by_hand(p):
    M = np.diag([p["m1"], p["m2"]])
    K = np.array([[p["k11"] + p["k12"], -p["k12"]], [-p["k12"], p["k22"] + p["k12"]]])
    C = np.array([[p["c11"] + p["c12"], -p["c12"]], [-p["c12"], p["c22"] + p["c12"]]])
    B = np.array([[1.0], [0.0]])  # F1 acts on mass1
    Cd = np.eye(2)  # d1, d2: the displacements of mass1 and mass2
    return M, C, K, B, Cd


@pytest.fixture(scope="module")
def model():
    return mbgen.load_model(MODEL)


def test_parameters(model):
    p = model.parameters
    assert list(p) == ["m1", "m2", "k11", "k22", "k12", "c11", "c22", "c12"]
    assert p["m1"] == {"value": 1.39, "role": "estimate", "bounds": (0.0, 100.0), "unit": "kg"}
    assert p["k11"]["bounds"] == (0.0, 1e9) and p["k11"]["unit"] == "N/m"
    assert p["c12"]["role"] == "fixed"
    assert model.inputs == ["F1"] and model.outputs == ["d1", "d2"]
    assert model.coordinates == ["mass1.x", "mass2.x"]


def test_matrices_by_hand(model):
    M, C, K, B, Cd = by_hand(NOMINAL)
    m = model.matrices()
    np.testing.assert_allclose(m["M"], M, rtol=1e-15)
    np.testing.assert_allclose(m["K"], K, rtol=1e-15)
    np.testing.assert_allclose(m["C"], C, rtol=1e-15)
    np.testing.assert_array_equal(m["B"], B)
    np.testing.assert_array_equal(m["Cd"], Cd)
    np.testing.assert_array_equal(m["Cv"], np.zeros((2, 2)))
    np.testing.assert_array_equal(m["Ca"], np.zeros((2, 2)))


def test_matrices_as_export(model, mbgen_command):
    import subprocess

    out = subprocess.run([mbgen_command, "export", str(MODEL), "--what", "matrices"], check=True,
                         capture_output=True, text=True).stdout
    exported = json.loads(out)
    m = model.matrices()
    for name in ["M", "C", "K", "B", "Cd", "Cv", "Ca"]:
        np.testing.assert_array_equal(m[name], np.array(exported[name]), err_msg=name)


def test_params_and_set_override_values(model):
    p = dict(NOMINAL, m1=2.0, k12=1.0e5)
    M, C, K, _, _ = by_hand(p)
    m = model.matrices(params={"m1": 2.0, "k12": 1.0e5})
    np.testing.assert_allclose(m["M"], M, rtol=1e-15)
    np.testing.assert_allclose(m["K"], K, rtol=1e-15)
    # set= derives the model at the value (as --set): the model's own value changes
    assert mbgen.load_model(MODEL, set={"m1": 2.0}).parameters["m1"]["value"] == 2.0
    np.testing.assert_allclose(mbgen.load_model(MODEL, set={"m1": 2.0}).matrices()["M"], M, rtol=1e-15)


def test_roles(model):
    fixed = mbgen.load_model(MODEL, fix={"m1": 1.262}, free=["c12"])
    assert fixed.parameters["m1"]["role"] == "known" and fixed.parameters["m1"]["value"] == 1.262
    assert fixed.parameters["c12"]["role"] == "estimate"
    assert mbgen.load_model(MODEL, fix=["m2"]).parameters["m2"]["role"] == "known"


def test_frf_by_hand(model):
    f = np.array([10.0, 50.0, 89.7, 123.4, 400.0])
    H = model.frf(f)
    assert H.shape == (5, 2, 1) and H.dtype == np.complex128
    M, C, K, B, Cd = by_hand(NOMINAL)
    for k, fk in enumerate(f):
        w = 2 * np.pi * fk
        expected = Cd @ np.linalg.solve(K - w**2 * M + 1j * w * C, B)
        np.testing.assert_allclose(H[k], expected, rtol=1e-10)


def test_frf_at_params(model):
    truth = dict(NOMINAL, m1=1.262, m2=1.022, k11=1.3e6)
    M, C, K, B, Cd = by_hand(truth)
    w = 2 * np.pi * 77.0
    H = model.frf([77.0], params={"m1": 1.262, "m2": 1.022, "k11": 1.3e6})
    np.testing.assert_allclose(H[0], Cd @ np.linalg.solve(K - w**2 * M + 1j * w * C, B), rtol=1e-10)


def test_state_space_by_hand(model):
    M, C, K, B, Cd = by_hand(NOMINAL)
    Mi = np.linalg.inv(M)
    ss = model.state_space()
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [-Mi @ K, -Mi @ C]])
    np.testing.assert_allclose(ss["A"], A, rtol=1e-13, atol=1e-9)
    np.testing.assert_allclose(ss["B"], np.vstack([np.zeros((2, 1)), Mi @ B]), rtol=1e-13)
    np.testing.assert_allclose(ss["C"], np.hstack([Cd, np.zeros((2, 2))]), rtol=1e-13)
    np.testing.assert_array_equal(ss["D"], np.zeros((2, 1)))


def test_modes_by_hand(model):
    modes = model.modes()
    M, C, K, _, _ = by_hand(NOMINAL)
    Mi = np.linalg.inv(M)
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [-Mi @ K, -Mi @ C]])
    lam = np.linalg.eigvals(A)
    lam = lam[lam.imag > 0]
    f = np.sort(np.abs(lam)) / (2 * np.pi)
    np.testing.assert_allclose(modes["f_hz"], f, rtol=1e-10)
    # the undamped frequencies the model's README quotes for these values: 89.72 and 166.29 Hz
    np.testing.assert_allclose(modes["f_hz"], [89.72, 166.29], atol=0.01)
    assert np.all(modes["zeta"] > 0) and np.all(modes["zeta"] < 0.01)
    assert modes["shapes"].shape == (2, 2)
    # each shape solves (K + lambda C + lambda^2 M) v = 0
    for k in range(2):
        s, v = modes["eigenvalues"][k], modes["shapes"][:, k]
        assert np.linalg.norm((K + s * C + s**2 * M) @ v) < 1e-8 * np.linalg.norm(K) * np.linalg.norm(v)


def test_simulate_reproduces_the_record():
    # The record of examples/mdof2 (40 dB output noise) simulated at its truth's values from its own force.
    data = mbgen.read_data(MDOF2 / "data" / "time_F1.csv")
    truth = json.loads((MDOF2 / "data" / "time_F1.truth.json").read_text())["parameters"]
    channels = data["channels"]
    u = data["values"][:, channels.index("F1")]
    y = mbgen.load_model(MDOF2 / "mdof2.mdl").simulate(data["t"], u, params=truth)
    assert y.shape == (len(data["t"]), 2)
    for o, name in enumerate(["d1", "d2"]):
        measured = data["values"][:, channels.index(name)]
        nrmse = np.linalg.norm(y[:, o] - measured) / np.linalg.norm(measured)
        assert nrmse < 0.03, (name, nrmse)  # the noise alone is 0.01


def test_simulate_static_limit(model):
    # A step held long with heavy damping settles at K^-1 B.
    t = np.arange(0, 2.0, 1e-4)
    u = np.ones((len(t), 1))
    params = {"c11": 5000.0, "c22": 3000.0}
    y = model.simulate(t, u, params=params)
    _, _, K, B, Cd = by_hand(NOMINAL)
    np.testing.assert_allclose(y[-1], (Cd @ np.linalg.solve(K, B))[:, 0], rtol=1e-6)
