#!/usr/bin/env bash
# Installs the C++ library to a temporary prefix (cmake --install) and builds and runs the example
# program of examples/cpp against the installed vofdem::vofdem target, without Python. The library is
# the one of the optimised C++ test build (scripts/test_cpp.sh), brought up to date here: after
# make test-cpp nothing is compiled again.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/cpp_builds.sh
JOBS=${JOBS:-2}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cpp_configure "$CPP_RELEASE_DIR" "${CPP_RELEASE_ARGS[@]}"
cmake --build "$CPP_RELEASE_DIR" --target vofdem -j "$JOBS" >/dev/null
cmake --install "$CPP_RELEASE_DIR" --prefix "$work/prefix" >/dev/null
cmake -S examples/cpp -B "$work/example" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/example" -j "$JOBS" >/dev/null
"$work/example/stones_into_pool"
