#!/usr/bin/env bash
# Builds and runs the C++ tests twice: an optimised build, and one under AddressSanitizer and
# UndefinedBehaviorSanitizer (any report fails the run). --fast: the optimised build alone.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/cpp_builds.sh
JOBS=${JOBS:-$(nproc)}
run() {
  local dir=$1; shift
  cpp_configure "$dir" "$@"
  cmake --build "$dir" -j "$JOBS"
  # two tests at a time, each on one thread (the same bits as on any count: the Threads suite checks two
  # threads, alone); a team of threads per test would wait at every loop for the core the other test holds
  (cd "$dir" && OMP_NUM_THREADS=1 ctest --output-on-failure -j "$JOBS")
}
run "$CPP_RELEASE_DIR" "${CPP_RELEASE_ARGS[@]}"
[ "${1:-}" = "--fast" ] && exit 0  # the sanitizer build only in the full run
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  run "$CPP_SANITIZE_DIR" "${CPP_SANITIZE_ARGS[@]}"
