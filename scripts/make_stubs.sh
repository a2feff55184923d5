#!/usr/bin/env bash
# Regenerates python/vofdem/_core.pyi (type stubs of the C++ extension, for editors and type checkers)
# from the built extension. Run after changing a binding; needs pybind11-stubgen (the test extra);
# tests/test_stubs.py fails while the stub and the extension disagree.
set -euo pipefail
cd "$(dirname "$0")/.."
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
python3 -m pybind11_stubgen vofdem._core -o "$out" --ignore-invalid-expressions '.*' >/dev/null
cp "$out/vofdem/_core.pyi" python/vofdem/_core.pyi
