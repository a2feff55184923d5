#!/usr/bin/env bash
# Builds and runs the C++ tests twice: an optimised build, and one under AddressSanitizer and
# UndefinedBehaviorSanitizer (any report fails the run). --fast: the optimised build alone.
set -euo pipefail
cd "$(dirname "$0")/.."
JOBS=${JOBS:-$(nproc)}
run() {
  local dir=$1; shift
  cmake -S . -B "$dir" -G Ninja -DVOFDEM_PYTHON=OFF -DVOFDEM_TESTS=ON -DVOFDEM_WERROR=ON "$@" >/dev/null
  cmake --build "$dir" -j "$JOBS"
  (cd "$dir" && ctest --output-on-failure -j "$JOBS")
}
run build/cpp-release -DCMAKE_BUILD_TYPE=Release
[ "${1:-}" = "--fast" ] && exit 0  # the sanitizer build only in the full run
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  run build/cpp-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVOFDEM_SANITIZE=ON
