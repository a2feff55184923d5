"""Runs a notebook of notebooks/ from top to bottom for the tests of the notebooks, in the kernel of the
vofdem this test imports, and gathers what its cells showed."""
from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import nbformat
from nbclient import NotebookClient

import vofdem

ROOT = Path(__file__).resolve().parents[1]


@dataclass
class NotebookRun:
    """What the notebook's code cells showed: their outputs, the printed text, the markdown and the count
    of figures."""

    outputs: list
    text: str
    markdown: str
    images: int


def run_notebook(name: str, tmp_path: Path, monkeypatch, **env: str) -> NotebookRun:
    """Runs notebooks/<name> with the environment variables env (VOFDEM_NOTEBOOK_* sizes), the kernel's
    working folder tmp_path; fails on any cell that raised."""
    for key, value in env.items():
        monkeypatch.setenv(key, value)
    # the kernel imports the same vofdem as this test (installed, or the source tree with its _core)
    package_root = str(Path(vofdem.__file__).resolve().parents[1])
    monkeypatch.setenv("PYTHONPATH", package_root + os.pathsep + os.environ.get("PYTHONPATH", ""))
    nb = nbformat.read(ROOT / "notebooks" / name, as_version=4)
    NotebookClient(nb, timeout=600, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}).execute()
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])]
    assert not [o for o in outputs if o.output_type == "error"]
    return NotebookRun(outputs=outputs,
                       text="".join(o.get("text", "") for o in outputs),
                       markdown="".join(o.get("data", {}).get("text/markdown", "") for o in outputs),
                       images=sum("image/png" in o.get("data", {}) for o in outputs))
