#!/usr/bin/env bash
# Installs the C++ library to a temporary prefix (cmake --install) and builds and runs the example
# program of examples/cpp against the installed vofdem::vofdem target, without Python.
set -euo pipefail
cd "$(dirname "$0")/.."
JOBS=${JOBS:-2}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake -S . -B "$work/lib" -G Ninja -DVOFDEM_PYTHON=OFF -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/lib" -j "$JOBS" >/dev/null
cmake --install "$work/lib" --prefix "$work/prefix" >/dev/null
cmake -S examples/cpp -B "$work/example" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/example" -j "$JOBS" >/dev/null
"$work/example/stones_into_pool"
