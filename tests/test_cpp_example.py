"""The C++ library alone: install it to a temporary prefix and build and run examples/cpp against it."""
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.slow
@pytest.mark.skipif(shutil.which("cmake") is None or shutil.which("ninja") is None, reason="needs cmake and ninja")
def test_example_builds_against_the_installed_target():
    out = subprocess.run([str(ROOT / "scripts" / "test_cpp_example.sh")], capture_output=True, text=True, timeout=900)
    assert out.returncode == 0, out.stdout + out.stderr
    assert "water volume error" in out.stdout and "porosity" in out.stdout
