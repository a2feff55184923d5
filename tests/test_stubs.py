"""The stub file of the extension (python/vofdem/_core.pyi, for editors and type checkers) says what the
built extension holds: pybind11-stubgen run on the imported vofdem._core (as scripts/make_stubs.sh does)
gives the same text. After changing a binding, run scripts/make_stubs.sh."""
import difflib
import subprocess
import sys
from pathlib import Path

import vofdem


def test_the_stub_file_matches_the_extension(tmp_path):
    run = subprocess.run([sys.executable, "-m", "pybind11_stubgen", "vofdem._core", "-o", str(tmp_path),
                          "--ignore-invalid-expressions", ".*"], capture_output=True, text=True)
    assert run.returncode == 0, "pybind11-stubgen (the test extra) failed:\n" + run.stderr[-2000:]
    made = (tmp_path / "vofdem" / "_core.pyi").read_text()
    kept = (Path(vofdem.__file__).parent / "_core.pyi").read_text()
    diff = list(difflib.unified_diff(kept.splitlines(), made.splitlines(), "_core.pyi (kept)", "_core.pyi (made)",
                                     lineterm="", n=1))
    assert not diff, "the stub file and the extension disagree (run scripts/make_stubs.sh):\n" + "\n".join(diff[:60])
