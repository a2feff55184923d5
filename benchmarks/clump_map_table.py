"""Runs the clump mapping benchmark and writes benchmarks/results/clump_map.md.

usage: python3 benchmarks/clump_map_table.py BUILD_DIR   (a build configured with -DVOFDEM_BENCHMARKS=ON)
"""
import os
import platform
import sys

from google_bench import medians, write_results

HERE = os.path.dirname(os.path.abspath(__file__))


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "..", "build", "cpp-release")
    exe = os.path.join(build, "bench_clump_map")
    env = dict(os.environ, OMP_NUM_THREADS="1")
    context, rows = medians(exe, 5, 0.3, env)
    # cpu_time is per call; items_per_second counts stones per second of CPU time
    per_stone = {b["run_name"]: 1e9 / b["items_per_second"] for b in rows}
    base = per_stone["BM_MapSpheres"]
    lines = ["# Solid fraction of clumps against spheres", "",
             "Google Benchmark `benchmarks/cpp/bench_clump_map.cpp`, median of 5 repetitions (CPU time), "
             f"{context.get('num_cpus')} CPUs shared with other jobs, {platform.machine()}. "
             "300 stones of d_eq = 4.8 cm at random places and orientations in the lower 0.5 m of the "
             "paper's grid (2.5 cm x 1.0 cm cells, 0.5 cm rows up to 2 cm) across a 0.3 m flume; one call "
             "maps them all (`PorosityMapper::map_spheres` for spheres of d_eq, `map_clumps` for the "
             "library shapes 1 : 0.8 : 0.6). Time per stone includes the per-call work on every cell.", "",
             "| case | sub-spheres | ns per stone | against spheres |", "|---|---|---|---|"]
    for b in rows:
        name = b["run_name"]
        k = b.get("spheres", 1)
        lines.append(f"| {name} | {k:.0f} | {per_stone[name]:.0f} | {per_stone[name] / base:.2f} |")
    lines += ["", "The ratio is measured in one run. The load of the shared machine makes single figures "
              "vary by about +-30 %; the ratios less."]
    write_results("clump_map.md", lines)


if __name__ == "__main__":
    main()
