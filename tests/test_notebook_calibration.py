"""notebooks/calibration.ipynb runs from top to bottom (small heaps, one pull per direction) and shows its results."""
from notebook_util import run_notebook


def test_calibration_notebook_runs_and_shows_heaps_and_pulls(tmp_path, monkeypatch):
    run = run_notebook("calibration.ipynb", tmp_path, monkeypatch, VOFDEM_NOTEBOOK_STONES="60")
    assert run.markdown.count("| vertical | 1 |") == 2 and "4.75" in run.markdown
    assert "submerged, mu_r = 0.5" in run.text
    assert run.images == 3
