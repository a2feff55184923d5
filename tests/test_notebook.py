"""notebooks/maeno2008.ipynb runs from top to bottom (a short run of the scenario) and shows its results."""
from notebook_util import run_notebook


def test_notebook_runs_and_shows_the_stage_table_and_figures(tmp_path, monkeypatch):
    run = run_notebook("maeno2008.ipynb", tmp_path, monkeypatch, VOFDEM_NOTEBOOK_END_TIME="6",
                       VOFDEM_NOTEBOOK_OUT=str(tmp_path / "out"))
    assert "| event | this run" in run.markdown and "| stage | seconds |" in run.markdown
    assert run.images >= 5
    assert (tmp_path / "out" / "run.h5").exists()


def test_ensembles_notebook_runs_a_tiny_ensemble_on_dask(tmp_path, monkeypatch):
    run = run_notebook("ensembles.ipynb", tmp_path, monkeypatch, VOFDEM_NOTEBOOK_SEEDS="0-1",
                       VOFDEM_NOTEBOOK_END_TIME="4", VOFDEM_NOTEBOOK_WORKERS="2",
                       VOFDEM_NOTEBOOK_OUT=str(tmp_path / "out"))
    assert "**stones.friction_stone=0.5**: 2 completed members" in run.markdown
    assert "| stage 2 |" in run.markdown and run.images == 1
    assert (tmp_path / "out" / "stones.friction_stone=0.577" / "seed1" / "outcome.json").exists()
