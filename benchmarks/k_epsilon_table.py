"""Runs the k-epsilon step benchmark and writes benchmarks/results/k_epsilon.md.

usage: python3 benchmarks/k_epsilon_table.py BUILD_DIR   (a build configured with -DVOFDEM_BENCHMARKS=ON)
"""
import os
import platform
import sys

from google_bench import medians, write_results

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "..", "build-dev")
    exe = os.path.join(build, "bench_k_epsilon")
    context, rows = medians(exe, 5, 0.3)
    stages = ["setup", "wall functions", "production", "transport", "eddy viscosity", "checks"]
    lines = ["# k-epsilon step cost", "",
             "Google Benchmark `benchmarks/cpp/bench_k_epsilon.cpp`, median of 5 repetitions (CPU time), "
             f"{context.get('num_cpus')} CPUs shared with other jobs, {platform.machine()}. "
             "Scene: a flume on the paper's graded mesh (2.5 cm x 1 cm cells, 0.5 cm rows at the bed, "
             "30 rows), sheared divergence-free flow, a porous mound (n = 0.41), a solid block, "
             "air in the upper third (not solved). `nx/sweeps` in the name.", "",
             "| benchmark | cells | ns per cell and step | " + " | ".join(f"{s} %" for s in stages) + " |",
             "|---|---|---|" + "---|" * len(stages)]
    for b in rows:
        name = b["run_name"]
        cells = b.get("ncell", "")
        cells = f"{cells:.0f}" if cells != "" else ""
        shares = " | ".join(f"{b[s]:.0f}" if s in b else "" for s in stages)
        lines.append(f"| {name} | {cells} | {b['ns_per_cell']:.0f} | {shares} |")
    lines += ["", "Stage shares are of the model's own StageProfile time. `BM_KEpsilonStableDt` is the cost "
              "of `stable_dt()` alone. The load of the shared machine makes single figures vary by about "
              "+-30 %."]
    write_results("k_epsilon.md", lines)


if __name__ == "__main__":
    main()
