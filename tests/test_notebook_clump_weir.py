"""notebooks/clump_weir.ipynb runs from top to bottom: a small weir of clumps packed by a scene of
stones.shape = 'clump', drawn in side and plan view, run a moment with the water kept."""
import os
from pathlib import Path

import nbformat
from nbclient import NotebookClient

import vofdem

ROOT = Path(__file__).resolve().parents[1]


def test_the_clump_weir_notebook_packs_draws_and_runs(tmp_path, monkeypatch):
    monkeypatch.setenv("VOFDEM_NOTEBOOK_END_TIME", "0.2")
    monkeypatch.setenv("PYTHONPATH", str(Path(vofdem.__file__).resolve().parents[1]) + os.pathsep
                       + os.environ.get("PYTHONPATH", ""))
    nb = nbformat.read(ROOT / "notebooks" / "clump_weir.ipynb", as_version=4)
    NotebookClient(nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}).execute()
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])]
    assert not [o for o in outputs if o.output_type == "error"]
    markdown = "".join(o.get("data", {}).get("text/markdown", "") for o in outputs)
    assert "clumps** (" in markdown and "after 0.2 s: water gained" in markdown
    assert sum("image/png" in o.get("data", {}) for o in outputs) == 2
