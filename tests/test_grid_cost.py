"""benchmarks/grid_cost.py and benchmarks/step_limits_grid.py: the grids by hand, the limits' shares and
the aims by hand, and tiny runs (the quick scene on the draft grid and the paper's) whose tables hold what
they say; the k-epsilon scheme 'alternating_lines' from a scene."""
import pytest
from script_loader import load_script

grid_cost = load_script("benchmarks/grid_cost.py")
step_limits = load_script("benchmarks/step_limits_grid.py")


def test_the_grids_are_the_papers_divided_by_the_factor():
    assert grid_cost.grid_settings(1) == ["grid.dx=0.025", "grid.dz=0.01", "grid.dz_bed=0.005",
                                          "grid.bed_layer_height=0.005"]
    assert grid_cost.grid_settings(4) == ["grid.dx=0.00625", "grid.dz=0.0025", "grid.dz_bed=0.00125",
                                          "grid.bed_layer_height=0.00125"]


def _result(factor, steps, cpu, limits, cells=100):
    return dict(factor=factor, dx=0.025 / factor, dz=0.01 / factor, nx=10, nz=cells // 10, cells=cells, seconds=1.0,
                steps=steps, cpu=cpu, stages={"flow / pressure": (cpu / 2, steps)}, limits=limits,
                iterations=3 * steps, solves=steps, loads=dict(fx=1.0, fz=-2.0, largest=1.0), level=0.3, nut_mean=1e-3)


def test_limit_shares_and_the_aims_by_hand():
    r = _result(1, 100, 1.0, {"advective": 25, "turbulence": 75})
    assert grid_cost.limit_shares(r) == "turbulence 75.0 %, advective 25.0 %"
    assert grid_cost.per_solve(r) == 3.0
    # twice as fine: 4 x the cells at 2 x the steps and the same cost per cell-step is 8 x the CPU (met);
    # four times as fine at 16 x 8 = 128 x the CPU is not
    fine, finer = _result(2, 200, 8.0, {"advective": 200}, 400), _result(4, 800, 128.0, {"viscous": 800}, 1600)
    text = grid_cost.report([r, fine, finer], "t", "n")
    assert "Grid 2 times as fine: CPU 8.0 times the first grid's (aim: at most 9): met." in text
    assert "Grid 4 times as fine: CPU 128.0 times the first grid's (aim: at most 70): NOT met." in text
    assert "| 1.25 | 10 x 40 = 400 | 200 | 2.00 | 8 | 8.00 | 100.000 | 3.00 |" in text  # 8 s / (400 x 200)


def test_a_tiny_run_of_both_scripts(tmp_path):
    out = grid_cost.main(["--small", "--factors", "1", "2", "--seconds", "0.05", "--out", str(tmp_path / "c.md")])
    text = out.read_text()
    rows = [line for line in text.splitlines() if line.startswith("| 5 |") or line.startswith("| 2.5 |")]
    assert len(rows) == 2, text  # the draft grid (5 cm) and the paper's (2.5 cm)
    steps = [int(r.split("|")[3]) for r in rows]
    assert all(s > 0 for s in steps)
    assert float(rows[1].split("|")[8]) > 0.0  # CG iterations per pressure solve
    assert "flow / pressure" in text and "k-epsilon / k-eps transport" in text
    out = step_limits.main(["--small", "--factors", "1", "2", "--seconds-per-grid", "0.05", "0.02",
                            "--set", "numerics.turbulence_scheme=alternating_lines", "--out", str(tmp_path / "s.md")])
    text = out.read_text()
    assert "numerics.turbulence_scheme=alternating_lines" in text and "| 5 x 2 |" in text and "| 2.5 x 1 |" in text
    with pytest.raises(ValueError, match="one per grid"):
        step_limits.main(["--small", "--seconds-per-grid", "0.1"])
    with pytest.raises(ValueError, match="seconds"):
        grid_cost.main(["--small", "--seconds", "0"])


def test_the_alternating_lines_from_a_scene():
    from vofdem import _core
    from vofdem.builder import flow_params
    from vofdem.ensemble import with_settings
    scene = with_settings(grid_cost.load_scene(grid_cost.ROOT / "scenes" / "maeno2008_consistent.toml"),
                          ["numerics.turbulence_scheme=alternating_lines"])
    assert flow_params(scene).turbulence_time_scheme == _core.KEpsilonTimeScheme.ALTERNATING_LINES
    with pytest.raises(ValueError, match="turbulence_scheme"):
        with_settings(scene, ["numerics.turbulence_scheme=alternating"])
