#!/usr/bin/env bash
# Remakes the scenario figures and tables of docs/results.md: the whole Maeno 2008 scenario on the paper's grid
# and hydrograph, once with the paper's coupling (scenes/maeno2008.toml) and once with the consistent
# coupling options (scenes/maeno2008_consistent.toml), a few minutes each on one core; copies each
# run's figures and stage table to docs/figures/<scene>/ and writes the paper scene's cost report to
# benchmarks/results/. The benchmark figures of the docs come from the scripts named beside them.
# It runs the vofdem that python3 imports: in a build in place (VOFDEM_INPLACE) give PYTHONPATH=python.
# It stops when that vofdem's Python sources differ from this tree's (an older installed one).
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PY:-python3}
OUT=${OUT:-out}
export OMP_NUM_THREADS=1
pkg=$("$PY" -c "import pathlib, vofdem; print(pathlib.Path(vofdem.__file__).resolve().parent)")
if ! diff -rq --exclude=__pycache__ --exclude='*.so' --exclude='*.pyi' python/vofdem "$pkg" > /dev/null; then
  echo "readme_figures.sh: the vofdem that $PY imports ($pkg) is not this tree's python/vofdem;" \
       "build in place and give PYTHONPATH=python, or pip install . again" >&2
  exit 1
fi
for scene in maeno2008 maeno2008_consistent; do
  "$PY" -m vofdem run "scenes/$scene.toml" --out "$OUT/$scene" --no-animation --no-progress
  rm -rf "docs/figures/$scene"
  mkdir -p "docs/figures/$scene"
  cp "$OUT/$scene"/figures/*.png "$OUT/$scene/stage_table.md" "docs/figures/$scene/"
done
"$PY" benchmarks/maeno2008_realtime.py --from-run "$OUT/maeno2008" --out benchmarks/results/maeno2008_full_realtime.md
