#!/usr/bin/env bash
# The ParaView screenshot of the docs (docs/figures/paraview.png): runs the quick scene and renders its
# last snapshot with examples/paraview_view.py in pvbatch. Debian's ParaView renders through X, so
# without a display it runs under xvfb-run (scripts/install_deps.sh installs paraview and xvfb).
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PY:-python3}
OUT=${OUT:-out}
"$PY" -m vofdem run maeno2008 --quick --no-figures --no-animation --no-progress --out "$OUT/maeno2008_quick"
RUN=(pvbatch examples/paraview_view.py "$OUT/maeno2008_quick" --png docs/figures/paraview.png)
if [ -n "${DISPLAY:-}" ]; then "${RUN[@]}"; exit; fi
# a display picked by xvfb-run -a is now and then taken by another job before pvbatch connects: retry
for attempt in 1 2 3; do
  xvfb-run -a -s "-screen 0 1920x1080x24" "${RUN[@]}" && exit 0
  echo "pvbatch under xvfb-run failed (attempt $attempt of 3)" >&2
done
exit 1
