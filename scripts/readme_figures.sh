#!/usr/bin/env bash
# Remakes the README's scenario figures and tables: the paper's hydrograph on the coarse grid
# (scenes/maeno2008_coarse.toml, about 10 minutes on one core), then copies the run's figures to
# docs/figures/maeno2008_coarse/ and writes its cost and stage report to benchmarks/results/.
# The benchmark figures of the README come from the scripts named beside them in benchmarks/.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PY:-python3}
OUT=${OUT:-out/maeno2008_coarse}
"$PY" -m vofdem run scenes/maeno2008_coarse.toml --out "$OUT" --no-animation --no-progress
rm -rf docs/figures/maeno2008_coarse
mkdir -p docs/figures/maeno2008_coarse
cp "$OUT"/figures/*.png "$OUT/stage_table.md" docs/figures/maeno2008_coarse/
"$PY" benchmarks/maeno2008_realtime.py --from-run "$OUT" --out benchmarks/results/maeno2008_coarse_realtime.md
