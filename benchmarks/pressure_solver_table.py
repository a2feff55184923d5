"""Runs the pressure solver benchmark (Google Benchmark) and writes benchmarks/results/pressure_solver.md.

Usage: python3 benchmarks/pressure_solver_table.py [path/to/bench_pressure]
(build it with -DVOFDEM_BENCHMARKS=ON; the default path is build-bench/bench_pressure).
"""
from __future__ import annotations

import os
import platform
import sys
from pathlib import Path

from google_bench import medians, write_results

ROOT = Path(__file__).resolve().parents[1]
NAMES = {0: "Eigen LDLT (direct)", 1: "multigrid CG"}


def main() -> None:
    exe = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "build-bench" / "bench_pressure"
    context, runs = medians(exe, 3, 0.5)
    rows = []
    for b in runs:
        name = b["run_name"]  # BM_PressureSetupSolve/kind:1/scale:2
        kind = int(name.split("kind:")[1].split("/")[0])
        warm = int(name.split("warm:")[1].split("/")[0])
        rows.append((int(b["cells"]), kind, warm, b["setup_ms"], b["solve_ms"], int(b["iterations"]),
                     b["us_per_cell"], b["wall_ms"]))
    rows.sort()
    lines = [
        "# Pressure solver cost",
        "",
        "Dam-break-like two-phase field (water rho = 1000 kg/m^3 / air rho = 1.2 kg/m^3 under an open top,",
        "a porous mound n = 0.4, a solid bed step), grid graded in z; setup (coefficients -> factorisation or",
        "multigrid hierarchy) + solve to a relative residual of 1e-8 from a zero guess or from the previous",
        "step's solution (source changed by 5 %), one core.",
        "Times are thread CPU times (median of 3 repetitions); the wall time of the same run is given too",
        f"(the machine may be shared). Produced by `benchmarks/pressure_solver_table.py` on {platform.machine()}"
        f" with {os.cpu_count()} logical CPUs ({context.get('date', '')}).",
        "",
        "| cells | solver | initial guess | setup ms | solve ms | iterations | us per cell | wall ms |",
        "|---:|---|---|---:|---:|---:|---:|---:|",
    ]
    for cells, kind, warm, setup, solve, its, upc, wall in rows:
        guess = "previous step" if warm else "zero"
        lines.append(f"| {cells} | {NAMES[kind]} | {guess} | {setup:.3f} | {solve:.3f} | {its} | {upc:.3f} | {wall:.3f} |")
    direct = {r[0]: r[3] + r[4] for r in rows if r[1] == 0}
    mg = {r[0]: r[3] + r[4] for r in rows if r[1] == 1 and r[2] == 0}
    lines += ["", "Speed-up of multigrid CG (zero guess) over the direct solver (setup + solve): " + ", ".join(
        f"{direct[c] / mg[c]:.1f}x at {c} cells" for c in sorted(mg) if c in direct) + "."]
    write_results("pressure_solver.md", lines)


if __name__ == "__main__":
    main()
