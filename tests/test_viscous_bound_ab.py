"""benchmarks/viscous_bound_ab.py: both bounds from one state, the table of stages written."""
from script_loader import load_script


def _load():
    return load_script("benchmarks/viscous_bound_ab.py")


def test_both_bounds_run_from_one_state_and_the_table_names_every_stage(tmp_path):
    ab = _load()
    out = tmp_path / "ab.md"
    ab.main(["--scene", "maeno2008_rolling_consistent", "--start", "0.3", "--span", "0.1", "--reps", "1",
             "--out", str(out)])
    text = out.read_text()
    assert "| stage | row sums [ms per step] | energy [ms per step] | energy / row sums |" in text
    for stage in ("momentum", "pressure", "fluid step"):
        assert f"| {stage} |" in text
    assert "steps per run: row sums [" in text and "energy [" in text


def test_another_field_alternates_from_one_state(tmp_path):
    ab = _load()
    out = tmp_path / "ab.md"
    ab.main(["--scene", "maeno2008_rolling_consistent", "--start", "0.3", "--span", "0.1", "--reps", "1",
             "--param", "viscous_scheme", "--values", "IMPLICIT_VERTICAL", "IMPLICIT", "--out", str(out)])
    text = out.read_text()
    assert text.startswith("# FlowParams.viscous_scheme IMPLICIT_VERTICAL against IMPLICIT on one state")
    assert "| stage | IMPLICIT_VERTICAL [ms per step] | IMPLICIT [ms per step] | IMPLICIT / IMPLICIT_VERTICAL |" in text
    assert "| momentum |" in text and "steps per run: IMPLICIT_VERTICAL [" in text
