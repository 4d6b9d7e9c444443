# mbgen.read_data: the readers of `fit` and `modal` on the example data and a real UFF file, values as written.
import numpy as np
import pytest

import mbgen
from conftest import MDOF2, ROOT


def test_frf_csv():
    data = mbgen.read_data(MDOF2 / "data" / "frf_F1.csv")
    assert data["kind"] == "frf"
    assert data["channels"] == ["d1/F1", "d2/F1"]
    assert data["outputs"] == ["d1", "d2"] and data["inputs"] == ["F1", "F1"]
    f = data["f_hz"]
    assert len(f) == 1561 and f[0] == 10.0 and f[1] == 10.25 and f[-1] == 400.0
    assert data["values"].shape == (1561, 2) and data["values"].dtype == np.complex128
    # the file's first line: 10,7.4258738e-07,-2.1732918e-08,0.994395,2.0998042e-07,-4.9087627e-08,0.938299
    assert data["values"][0, 0] == complex(7.4258738e-07, -2.1732918e-08)
    assert data["values"][0, 1] == complex(2.0998042e-07, -4.9087627e-08)
    assert data["coherence"][0, 0] == 0.994395 and data["coherence"][0, 1] == 0.938299
    assert data["set"] == {}


def test_time_csv():
    data = mbgen.read_data(str(MDOF2 / "data" / "time_F1.csv"))
    assert data["kind"] == "time"
    assert set(data["channels"]) == {"F1", "d1", "d2"}
    t = data["t"]
    assert len(t) == 8192 and data["values"].shape == (8192, 3)
    # the file's times as written (six decimals): 0.000000, 0.000244, ..., 1.999756
    assert t[0] == 0.0 and t[1] == 0.000244 and t[-1] == 1.999756
    names = data["channels"]
    # its second data line: 0.000244,-10,-3.8485e-07,-1.5107e-07
    assert [data["values"][1, names.index(n)] for n in ["F1", "d1", "d2"]] == [-10.0, -3.8485e-07, -1.5107e-07]
    assert data["hold"] == "zero-order"


def test_uff58_time_history():
    # A HBM catman export (tests/data/uff/README.md): 13 samples every 5e-5 s, the last data line not full.
    data = mbgen.read_data(ROOT / "tests" / "data" / "uff" / "time-history-not-all-columns-filled.uff")
    assert data["kind"] == "time"
    assert len(data["t"]) == 13
    np.testing.assert_allclose(data["t"][1] - data["t"][0], 5e-5, rtol=1e-12)
    assert data["values"].shape == (13, 1)
    assert data["values"][0, 0] == pytest.approx(-3.81956, rel=1e-12)
    assert data["values"][12, 0] == pytest.approx(-5.84096, rel=1e-12)


def test_uff58_frf():
    data = mbgen.read_data(ROOT / "tests" / "data" / "uff" / "non_ascii_header.uff")
    assert data["kind"] == "frf"
    assert data["values"].shape == (len(data["f_hz"]), len(data["channels"]))
    assert np.all(np.diff(data["f_hz"]) > 0)


# mbgen.write_data: the inverse of read_data, by `mbgen convert`'s writers.
def test_write_data_round_trip(tmp_path):
    data = mbgen.read_data(MDOF2 / "data" / "frf_F1.csv")  # 8 significant digits, coherence
    data["set"] = {"k12": 130000.0}
    mbgen.write_data(tmp_path / "frf.uff", data)
    mbgen.write_data(tmp_path / "frf.csv", data)
    for written in ("frf.uff", "frf.csv"):
        back = mbgen.read_data(tmp_path / written)
        assert back["kind"] == "frf" and back["channels"] == data["channels"]
        # UFF 58 holds 13 significant digits, CSV the shortest text of each double: both give the values back.
        assert np.array_equal(back["f_hz"], data["f_hz"])
        assert np.array_equal(back["values"], data["values"])
        assert np.array_equal(back["coherence"], data["coherence"])
        assert back["set"] == {"k12": 130000.0}
    assert (tmp_path / "frf.uff.map").read_text().splitlines()[1:] == ["set k12=130000.0", "1:+X = d1", "1001:+X = F1",
                                                                       "2:+X = d2"]
    # Full-precision values: CSV keeps every bit, UFF 13 significant digits.
    data["values"] = data["values"] * (1 + np.pi * 1e-9)
    mbgen.write_data(tmp_path / "exact.csv", data)
    mbgen.write_data(tmp_path / "exact.uff", data)
    assert np.array_equal(mbgen.read_data(tmp_path / "exact.csv")["values"], data["values"])
    uff = mbgen.read_data(tmp_path / "exact.uff")["values"]
    assert not np.array_equal(uff, data["values"])
    np.testing.assert_allclose(uff.real, data["values"].real, rtol=5e-13, atol=0)
    np.testing.assert_allclose(uff.imag, data["values"].imag, rtol=5e-13, atol=0)


def test_write_data_time_and_refusals(tmp_path):
    data = mbgen.read_data(MDOF2 / "data" / "time_F1.csv")
    mbgen.write_data(tmp_path / "time.csv", data)
    back = mbgen.read_data(tmp_path / "time.csv")
    assert np.array_equal(back["t"], data["t"]) and np.array_equal(back["values"], data["values"])
    assert back["channels"] == data["channels"]
    with pytest.raises(mbgen.DataError, match="a time record is written as CSV only"):
        mbgen.write_data(tmp_path / "time.uff", data)
    with pytest.raises(mbgen.UsageError, match="the name says the format"):
        mbgen.write_data(tmp_path / "time.txt", data)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["time.csv"]


def test_write_data_with_model(tmp_path):
    data = mbgen.read_data(MDOF2 / "data" / "frf_F1.csv")
    mbgen.write_data(tmp_path / "frf.uff", data, model=mbgen.load_model(MDOF2 / "mdof2.mdl"))
    text = (tmp_path / "frf.uff").read_text()
    assert "\n         8    0    0    0 displacement " in text  # the model's outputs: displacements
    assert np.array_equal(mbgen.read_data(tmp_path / "frf.uff")["values"], data["values"])
