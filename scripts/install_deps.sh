#!/usr/bin/env bash
# Installs what the project needs and is missing on a Debian 12 machine: the system packages from
# Debian's apt (Eigen, GoogleTest, Google Benchmark, ParaView), then the Python package with its test extras
# and documentation extras from PyPI. Safe to run again: it installs only what is missing and rebuilds incrementally.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PY:-python3}

# paraview + python3-paraview: pvbatch, for the tests that read the output with ParaView's own readers
# (about 220 MB to download and 1.3 GB installed with --no-install-recommends; 2 minutes here); xvfb and
# xauth: an X display for its renderer without a screen (scripts/paraview_figure.sh)
APT_PACKAGES="libeigen3-dev libgtest-dev libgmock-dev libbenchmark-dev ninja-build paraview python3-paraview xvfb xauth"
missing=""
for p in $APT_PACKAGES; do
  dpkg -s "$p" >/dev/null 2>&1 || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "installing system packages:$missing"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends $missing
fi

EXTRAS=${1:-test}
# the test install (make test, CI) also installs what the documentation site needs (make docs)
PIP_EXTRAS=$EXTRAS; [ "$EXTRAS" = "test" ] && PIP_EXTRAS="test,docs"
# the test install (make test, CI) builds the extension with warnings as errors; a user's install does not
WERROR=OFF; [ "$EXTRAS" = "test" ] && WERROR=ON
# the package is rebuilt only when a file it is built from changed since this script last installed it
# into this Python (the stamp keeps the hash of those files, the interpreter and the options)
stamp=build/install-${EXTRAS}.stamp
key=$( { "$PY" -c 'import sys; print(sys.executable, sys.version)'; echo "$PIP_EXTRAS $WERROR"
         find CMakeLists.txt pyproject.toml cpp python -type f \( -name '*.cpp' -o -name '*.h' -o -name '*.py' \
           -o -name '*.pyi' -o -name '*.txt' -o -name '*.toml' -o -name '*.typed' \) -print0 | sort -z | xargs -0 sha256sum
       } | sha256sum | cut -d' ' -f1)
if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$key" ] && (cd / && "$PY" -c 'import vofdem' 2>/dev/null); then
  echo "vofdem is installed from these sources already (${stamp}); not rebuilt"
  exit 0
fi
"$PY" -m pip install --quiet --disable-pip-version-check -C cmake.define.VOFDEM_WERROR=$WERROR ".[${PIP_EXTRAS}]"
mkdir -p build && echo "$key" > "$stamp"
