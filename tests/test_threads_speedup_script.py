"""benchmarks/threads_speedup.py: Amdahl's law by hand, the speed-up taken over the repeats on free cores
only, and a tiny run whose two thread counts end in the same bits."""
import sys

import pytest
from script_loader import ROOT, load_script

script = load_script("benchmarks/threads_speedup.py")


def _run(wall, cores, steps=100):
    return dict(wall=wall, cpu=wall, steps=steps, free_cores=cores, stages={}, hash="h", load=(0.0, 0.0))


def test_amdahl_with_the_serial_fraction_measured_at_two_threads():
    f, s8 = script.amdahl(1.6, 8)
    assert f == pytest.approx(0.25)  # 2 / 1.6 - 1
    assert s8 == pytest.approx(1.0 / (0.25 + 0.75 / 8))
    assert script.amdahl(2.0, 8) == pytest.approx((0.0, 8.0))


def test_the_speed_up_is_taken_over_the_repeats_on_free_cores():
    # repeat 1 on free cores (1.5 times), repeat 2 with a core held (two threads 10 times slower)
    res = {"runs": {1: [_run(1.5, 2.0), _run(1.5, 2.0)], 2: [_run(1.0, 1.9), _run(15.0, 1.0)]}}
    s = script.speedups(res)
    assert s["free"]["count"] == 1 and s["free"]["best"] == pytest.approx(1.5)
    assert s["all"]["best"] == pytest.approx(1.5) and s["all"]["median"] == pytest.approx(1.5 / 8.0)
    res["runs"][2][0]["free_cores"] = 1.2
    assert script.speedups(res)["free"] is None


@pytest.mark.skipif(not script._core.built_with_openmp(), reason="built without OpenMP: one thread only")
def test_a_tiny_run_ends_in_the_same_bits_on_both_thread_counts(tmp_path, monkeypatch):
    # the free-core probe's processes import the script by its name
    monkeypatch.syspath_prepend(str(ROOT / "benchmarks"))
    monkeypatch.setitem(sys.modules, "threads_speedup", script)
    before = script._core.thread_min_cells()
    script._core.set_thread_min_cells(1)  # the draft grid's loops split too
    try:
        out = script.main(["--fidelity", "draft", "--seconds", "0.05", "--repeats", "1", "--wait", "0",
                           "--out", str(tmp_path / "t.md")])
    finally:
        script._core.set_thread_min_cells(before)
    text = out.read_text()
    assert "End states: the same bits" in text and "the same step counts" in text
    assert "| 1 | 1 |" in text and "| 2 | 1 |" in text
    with pytest.raises(ValueError, match="seconds"):
        script.main(["--seconds", "0"])
