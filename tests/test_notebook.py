"""notebooks/maeno2008.ipynb runs from top to bottom (a short run of the scenario) and shows its results."""
import os
from pathlib import Path

import nbformat
from nbclient import NotebookClient

import vofdem

ROOT = Path(__file__).resolve().parents[1]


def test_notebook_runs_and_shows_the_stage_table_and_figures(tmp_path, monkeypatch):
    monkeypatch.setenv("VOFDEM_NOTEBOOK_END_TIME", "6")
    monkeypatch.setenv("VOFDEM_NOTEBOOK_OUT", str(tmp_path / "out"))
    # the kernel imports the same vofdem as this test (installed, or the source tree with its _core)
    monkeypatch.setenv("PYTHONPATH", str(Path(vofdem.__file__).resolve().parents[1]) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    nb = nbformat.read(ROOT / "notebooks" / "maeno2008.ipynb", as_version=4)
    NotebookClient(nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}).execute()
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])]
    assert not [o for o in outputs if o.output_type == "error"]
    markdown = "".join(o.get("data", {}).get("text/markdown", "") for o in outputs)
    assert "| event | this run" in markdown and "| stage | seconds |" in markdown
    assert sum("image/png" in o.get("data", {}) for o in outputs) >= 5
    assert (tmp_path / "out" / "run.h5").exists()


def test_ensembles_notebook_runs_a_tiny_ensemble_on_dask(tmp_path, monkeypatch):
    monkeypatch.setenv("VOFDEM_NOTEBOOK_SEEDS", "0-1")
    monkeypatch.setenv("VOFDEM_NOTEBOOK_END_TIME", "4")
    monkeypatch.setenv("VOFDEM_NOTEBOOK_WORKERS", "2")
    monkeypatch.setenv("VOFDEM_NOTEBOOK_OUT", str(tmp_path / "out"))
    monkeypatch.setenv("PYTHONPATH", str(Path(vofdem.__file__).resolve().parents[1]) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    nb = nbformat.read(ROOT / "notebooks" / "ensembles.ipynb", as_version=4)
    NotebookClient(nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}).execute()
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])]
    assert not [o for o in outputs if o.output_type == "error"]
    markdown = "".join(o.get("data", {}).get("text/markdown", "") for o in outputs)
    assert "**stones.friction_stone=0.5**: 2 completed members" in markdown
    assert "| stage 2 |" in markdown and sum("image/png" in o.get("data", {}) for o in outputs) == 1
    assert (tmp_path / "out" / "stones.friction_stone=0.577" / "seed1" / "outcome.json").exists()
