"""notebooks/calibration.ipynb runs from top to bottom (small heaps, one pull per direction) and shows its results."""
import os
from pathlib import Path

import nbformat
from nbclient import NotebookClient

import vofdem

ROOT = Path(__file__).resolve().parents[1]


def test_calibration_notebook_runs_and_shows_heaps_and_pulls(tmp_path, monkeypatch):
    monkeypatch.setenv("VOFDEM_NOTEBOOK_STONES", "60")
    # the kernel imports the same vofdem as this test (installed, or the source tree with its _core)
    package_root = str(Path(vofdem.__file__).resolve().parents[1])
    monkeypatch.setenv("PYTHONPATH", package_root + os.pathsep + os.environ.get("PYTHONPATH", ""))
    nb = nbformat.read(ROOT / "notebooks" / "calibration.ipynb", as_version=4)
    NotebookClient(nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}).execute()
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])]
    assert not [o for o in outputs if o.output_type == "error"]
    markdown = "".join(o.get("data", {}).get("text/markdown", "") for o in outputs)
    assert markdown.count("| vertical | 1 |") == 2 and "4.75" in markdown
    text = "".join(o.get("text", "") for o in outputs)
    assert "submerged, mu_r = 0.5" in text
    assert sum("image/png" in o.get("data", {}) for o in outputs) == 3
