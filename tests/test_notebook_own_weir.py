"""notebooks/own_weir.ipynb runs from top to bottom at a tiny size: an outline with an armour zone, sieve curves,
a CSV flood, the scene written and checked, packed, a quick run and an until-failure run."""
from notebook_util import run_notebook


def test_the_own_weir_notebook_runs_and_shows_each_step(tmp_path, monkeypatch):
    run = run_notebook("own_weir.ipynb", tmp_path, monkeypatch, VOFDEM_NOTEBOOK_END_TIME="3",
                       VOFDEM_NOTEBOOK_OUT=str(tmp_path / "out"))
    assert "refused: hydrograph CSV" in run.text and "line 3, column 2 (discharge_lps)" in run.text
    assert "**armour**" in run.markdown and "**core**" in run.markdown and "| stage | start [s] |" in run.markdown
    assert "# Until failure: my_weir_quick_until_failure" in run.markdown and "Critical discharge" in run.markdown
    assert run.images >= 4
    assert (tmp_path / "out" / "my_weir.toml").exists() and (tmp_path / "out" / "quick" / "run.h5").exists()
