"""The README as a user reads it: its length, its figure on the first screen, its Python example run as
it stands.
"""
from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"

LINK = re.compile(r"!?\[([^\]]*)\]\(([^)\s]+)\)")


def test_readme_is_short_with_its_figure_on_the_first_screen():
    lines = README.read_text(encoding="utf-8").splitlines()
    assert len(lines) <= 200
    figure = [i for i, line in enumerate(lines) if line.startswith("![")]
    assert figure and figure[0] < 40, "the fragility figure within the first 40 lines"
    path = LINK.search(lines[figure[0]]).group(2)
    assert (ROOT / path).is_file() and "fragility" in path


def python_example() -> str:
    text = README.read_text(encoding="utf-8")
    section = text.split("## From Python", 1)[1]
    return re.search(r"```python\n(.*?)```", section, re.S).group(1)


def test_the_python_example_runs(tmp_path):
    code = python_example()
    assert 15 <= len(code.splitlines()) <= 30
    out = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    first = out.stdout.splitlines()[0]
    assert re.match(r"80 stones, the furthest moved \d+\.\d{3} m; \d+ cells of water after \d+ flow steps", first)
    assert "fluid" in out.stdout.splitlines()[1]


@pytest.mark.parametrize("name", ["LICENSE", "CHANGELOG.md", "CITATION.cff"])
def test_the_house_files_exist(name):
    assert (ROOT / name).is_file() and (ROOT / name).stat().st_size > 200
