"""CSV loaders: columns, units in the header, and every bad input named by file, line, column."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pytest

from dryfriction.records.data import SeriesData, StaticData, SteadyData, read_csv

EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "data"


def write(tmp_path: Path, text: str, name: str = "d.csv") -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


def test_hand_written_files_with_unit_headers(tmp_path: Path) -> None:
    st = read_csv(write(tmp_path, "# my lab, run 7\nT_w [min], mu_s , note\n0.5,0.61,a\n"
                        "2,0.63,b\n\n10,0.65,c\n"))
    assert isinstance(st, StaticData) and st.sigma is None
    assert st.t_w.tolist() == [30.0, 120.0, 600.0]  # minutes -> s by hand
    assert st.mu_s.tolist() == [0.61, 0.63, 0.65]
    sd = read_csv(write(tmp_path, "mu_d,V[um/s],sigma_mu_d\n0.5,3,0.01\n0.49,30,0.02\n"))
    assert isinstance(sd, SteadyData)
    assert sd.V == pytest.approx([3e-6, 3e-5], rel=1e-15)
    assert sd.sigma.tolist() == [0.01, 0.02]
    se = read_csv(write(tmp_path, "t[ms],v_load[mm/min],mu\n0,6,0.6\n500,6,0.6\n1000,0,0.61\n"))
    assert isinstance(se, SeriesData)
    assert se.t.tolist() == [0.0, 0.5, 1.0]
    assert se.v_load == pytest.approx([1e-4, 1e-4, 0.0], rel=1e-15)  # 6 mm/min = 0.1 mm/s
    dur, vel = se.segments()
    assert dur.tolist() == [1.0, 0.5] and vel.tolist() == pytest.approx([1e-4, 0.0])


def test_examples_are_labelled_synthetic_and_load() -> None:
    files = sorted(EXAMPLES.glob("synthetic_*.csv"))
    assert len(files) == 4
    for f in files:
        assert f.read_text().startswith("# SYNTHETIC data")
        assert len(read_csv(f)) >= 12


def test_example_script_reproduces_the_shipped_files(tmp_path: Path,
                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    spec = importlib.util.spec_from_file_location("make_synthetic",
                                                  EXAMPLES / "make_synthetic.py")
    mod = importlib.util.module_from_spec(spec)  # type: ignore[arg-type]
    spec.loader.exec_module(mod)  # type: ignore[union-attr]
    monkeypatch.setattr(mod, "HERE", tmp_path)
    mod.main()
    for f in EXAMPLES.glob("synthetic_*.csv"):
        assert (tmp_path / f.name).read_text() == f.read_text()


@pytest.mark.parametrize(("text", "match"), [
    ("t_w,mu\n1,0.5\n", r"missing columns.*t_w, mu_s"),
    ("t_w,mu_s\n1,0.5\n2,abc\n", r"line 3, column 2 \(mu_s\): 'abc' is not a number"),
    ("# c\nt_w,mu_s\n1,nan\n", r"line 3, column 2 \(mu_s\): NaN"),
    ("t_w,mu_s\n-1,0.5\n", r"line 2, column 1 \(t_w\): negative waiting time"),
    ("V,mu_d\n1e-6,0.5\n-1e-6,0.5\n", r"line 3, column 1 \(V\): sliding velocity -1e-6"),
    ("V,mu_d\n0,0.5\n", r"line 2, column 1 \(V\).*> 0"),
    ("t,v_load,mu\n0,1e-6,0.6\n1,-1e-6,0.6\n", r"line 3, column 2 \(v_load\): negative"),
    ("t,v_load,mu\n0,1e-6,0.6\n0,1e-6,0.6\n", r"line 3, column 1 \(t\).*does not increase"),
    ("t_w,mu_s\n1,\n", r"line 2, column 2 \(mu_s\): empty cell"),
    ("t_w,mu_s\n1,0.5,3\n", r"line 2: 3 cells, the header has 2"),
    ("t_w[fortnight],mu_s\n1,0.5\n", r"line 1, column 1.*unknown time unit"),
    ("V[m/fortnight],mu_d\n1,0.5\n", r"unknown velocity unit"),
    ("t_w,mu_s[N]\n1,0.5\n", r"dimensionless"),
    ("t_w,mu_s,sigma_mu_s\n1,0.5,0\n", r"column 3 \(sigma_mu_s\): uncertainty 0 must be > 0"),
    ("t_w,mu_s\n1,inf\n", r"not finite"),
    ("# only a comment\n", r"empty file"),
    ("t_w,mu_s\n", r"no data rows"),
    ("t_w,mu_s,V,mu_d\n1,0.5,1,0.5\n", r"one kind of data per file"),
])
def test_bad_files_name_file_line_and_column(tmp_path: Path, text: str, match: str) -> None:
    p = write(tmp_path, text, "bad.csv")
    with pytest.raises(ValueError, match=match) as exc:
        read_csv(p)
    assert str(p) in str(exc.value)


def test_in_memory_data_sets_are_checked_and_frozen() -> None:
    with pytest.raises(ValueError, match=r"t_w\[1\] = -2"):
        StaticData([1.0, -2.0], [0.5, 0.6])
    with pytest.raises(ValueError, match="different lengths"):
        SteadyData([1e-6, 2e-6], [0.5])
    with pytest.raises(ValueError, match="starts with v_load = 0"):
        SeriesData([0.0, 1.0], [0.0, 1e-6], [0.6, 0.6])
    d = StaticData([1.0, 2.0], [0.5, 0.6])
    with pytest.raises(ValueError):
        d.t_w[0] = 3.0


def test_a_waiting_time_of_zero_is_read_and_a_negative_one_refused(tmp_path: Path) -> None:
    """``t_w = 0`` is a measurement (the peak on reloading at once: the steady level's
    neighbour), not bad input; a negative one is refused naming file, line and value. Mistake:
    the refusal at ``t_w <= 0`` (the zero-wait point of a slide-hold-slide series lost)."""
    st = read_csv(write(tmp_path, "t_w[s],mu_s\n0,0.583\n2.5,0.601\n40,0.622\n"))
    assert isinstance(st, StaticData) and st.t_w.tolist() == [0.0, 2.5, 40.0]
    with pytest.raises(ValueError, match=r"line 3.*negative waiting time -0\.5"):
        read_csv(write(tmp_path, "t_w[s],mu_s\n1,0.59\n-0.5,0.6\n", "neg.csv"))
