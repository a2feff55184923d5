"""benchmarks/flow_alone_turbulence.py at a tiny size: the scene and a variant, one table each."""
from script_loader import load_script


def test_the_scene_and_a_variant_at_a_tiny_size(tmp_path):
    fa = load_script("benchmarks/flow_alone_turbulence.py")
    out = fa.main(["--variant", "cfl1", "numerics.turbulence_cfl=1.0", "--times", "0.05", "0.1",
                   "--out", str(tmp_path / "fa.md")])
    text = out.read_text()
    assert "## scene (as it is)" in text and "## cfl1: numerics.turbulence_cfl=1.0" in text
    assert text.count("| 0.1 | ") == 2 and "depth at x = 0.488 m [m]" in text
