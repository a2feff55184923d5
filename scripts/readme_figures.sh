#!/usr/bin/env bash
# Remakes the README's scenario figures and tables: the paper's hydrograph on the coarse grid
# (scenes/maeno2008_coarse.toml, about 15 minutes on one core), then copies the destruction figure
# and the timeline to docs/figures/ and writes its real-time report to benchmarks/results/.
# The benchmark figures of the README come from the scripts named beside them in benchmarks/.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PY:-python3}
OUT=${OUT:-out/maeno2008_coarse}
"$PY" -m vofdem run scenes/maeno2008_coarse.toml --out "$OUT" --no-animation
mkdir -p docs/figures
cp "$OUT/figures/stones_velocity_stage2.png" docs/figures/maeno2008_coarse_stage2.png
cp "$OUT/figures/timeline.png" docs/figures/maeno2008_coarse_timeline.png
"$PY" benchmarks/maeno2008_realtime.py --from-run "$OUT" --out benchmarks/results/maeno2008_coarse_realtime.md
