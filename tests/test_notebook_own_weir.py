"""notebooks/own_weir.ipynb runs from top to bottom at a tiny size: an outline with an armour zone, sieve curves,
a CSV flood, the scene written and checked, packed, a quick run and an until-failure run."""
import os
from pathlib import Path

import nbformat
from nbclient import NotebookClient

import vofdem

ROOT = Path(__file__).resolve().parents[1]


def test_the_own_weir_notebook_runs_and_shows_each_step(tmp_path, monkeypatch):
    monkeypatch.setenv("VOFDEM_NOTEBOOK_END_TIME", "3")
    monkeypatch.setenv("VOFDEM_NOTEBOOK_OUT", str(tmp_path / "out"))
    monkeypatch.setenv("PYTHONPATH", str(Path(vofdem.__file__).resolve().parents[1]) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    nb = nbformat.read(ROOT / "notebooks" / "own_weir.ipynb", as_version=4)
    NotebookClient(nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}).execute()
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])]
    assert not [o for o in outputs if o.output_type == "error"]
    text = "".join(o.get("text", "") for o in outputs)
    markdown = "".join(o.get("data", {}).get("text/markdown", "") for o in outputs)
    assert "refused: hydrograph CSV" in text and "line 3, column 2 (discharge_lps)" in text
    assert "**armour**" in markdown and "**core**" in markdown and "| stage | start [s] |" in markdown
    assert "# Until failure: my_weir_quick_until_failure" in markdown and "Critical discharge" in markdown
    assert sum("image/png" in o.get("data", {}) for o in outputs) >= 4
    assert (tmp_path / "out" / "my_weir.toml").exists() and (tmp_path / "out" / "quick" / "run.h5").exists()
