"""What the scripts that run a C++ benchmark share (clump_map_table.py, k_epsilon_table.py,
pressure_solver_table.py): the benchmark's medians over repetitions from Google Benchmark's JSON, and the
results file written into benchmarks/results/ and printed."""
from __future__ import annotations

import json
import subprocess
from pathlib import Path

RESULTS = Path(__file__).resolve().parent / "results"


def medians(exe, repetitions: int, min_time: float, env=None) -> tuple[dict, list[dict]]:
    """Runs the benchmark executable exe (min_time [s] per benchmark, repetitions times); returns its
    context and the median row of each benchmark."""
    out = subprocess.run([str(exe), "--benchmark_format=json", f"--benchmark_repetitions={repetitions}",
                          "--benchmark_report_aggregates_only=true", f"--benchmark_min_time={min_time}"],
                         check=True, capture_output=True, text=True, env=env).stdout
    data = json.loads(out)
    return data["context"], [b for b in data["benchmarks"] if b.get("aggregate_name") == "median"]


def write_results(name: str, lines: list[str]) -> Path:
    """Writes the lines to benchmarks/results/<name> and prints them."""
    RESULTS.mkdir(parents=True, exist_ok=True)
    path = RESULTS / name
    path.write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return path
