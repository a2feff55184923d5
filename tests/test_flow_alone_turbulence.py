"""benchmarks/flow_alone_turbulence.py at a tiny size: the scene and a variant, one table each; another packing."""
from script_loader import load_script


def test_the_scene_and_a_variant_at_a_tiny_size(tmp_path):
    fa = load_script("benchmarks/flow_alone_turbulence.py")
    out = fa.main(["--variant", "cfl1", "numerics.turbulence_cfl=1.0", "--times", "0.05", "0.1",
                   "--out", str(tmp_path / "fa.md")])
    text = out.read_text()
    assert "## scene (as it is)" in text and "## cfl1: numerics.turbulence_cfl=1.0" in text
    assert text.count("| 0.1 | ") == 2 and "depth at x = 0.488 m [m]" in text


def test_another_packing_is_named_and_changes_the_weir(tmp_path):
    fa = load_script("benchmarks/flow_alone_turbulence.py")
    text0 = fa.main(["--times", "0.05", "--out", str(tmp_path / "fa0.md")]).read_text()
    text1 = fa.main(["--seed", "1", "--times", "0.05", "--out", str(tmp_path / "fa1.md")]).read_text()
    assert "stones held, seed 0;" in text0 and "stones held, seed 1;" in text1
    row = [line for line in text1.splitlines() if line.startswith("| 0.05 | ")]
    assert len(row) == 1 and row[0] not in text0  # another weir: another eddy viscosity or level
