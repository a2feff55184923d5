"""benchmarks/kernel_smoothing_cost.py, the source of docs/coupler.md's cost of the kernel mapping: its count
of smoothed fields by hand, and the script at a tiny size."""
from script_loader import load_script

from vofdem.builder import build_simulation
from vofdem.ensemble import with_settings
from vofdem.scene import load_scene


def test_the_fields_per_step_by_hand():
    cost = load_script("benchmarks/kernel_smoothing_cost.py")
    scene = load_scene("scenes/maeno2008_rolling_consistent.toml")
    # the bed drag: solid and diameter, F, F U, F W, dp/dx, dp/dz, and the three bed-drag densities; the
    # relative-velocity resistance adds the stones' two velocity components
    sim = build_simulation(with_settings(scene, ["numerics.coupling_mapping=kernel"]))
    assert sim.params.stone_drag.name == "BED"
    rel = bool(scene.effects.relative_velocity_resistance)
    assert cost.fields_per_step(sim) == (12 if rel else 10)


def test_the_script_at_a_tiny_size(tmp_path):
    cost = load_script("benchmarks/kernel_smoothing_cost.py")
    out = cost.main(["--duration", "0.02", "--out", str(tmp_path / "cost.md")])
    text = out.read_text()
    assert "# The kernel mapping's cost: scene maeno2008_rolling_consistent" in text
    assert "| cell |" in text and "| kernel |" in text and "CPU per step, kernel / cell:" in text
