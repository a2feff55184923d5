#!/usr/bin/env bash
# Remakes the README's scenario figures and tables: the whole Maeno 2008 scenario on the paper's grid
# and hydrograph (scenes/maeno2008.toml, a few minutes on one core), then copies the run's figures and
# stage table to docs/figures/maeno2008/ and writes its cost report to benchmarks/results/.
# The benchmark figures of the README come from the scripts named beside them in benchmarks/.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PY:-python3}
OUT=${OUT:-out/maeno2008}
"$PY" -m vofdem run scenes/maeno2008.toml --out "$OUT" --no-animation --no-progress
rm -rf docs/figures/maeno2008
mkdir -p docs/figures/maeno2008
cp "$OUT"/figures/*.png "$OUT/stage_table.md" docs/figures/maeno2008/
"$PY" benchmarks/maeno2008_realtime.py --from-run "$OUT" --out benchmarks/results/maeno2008_full_realtime.md
