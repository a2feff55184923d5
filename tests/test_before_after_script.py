"""benchmarks/maeno2008_before_after.py at a tiny size: the candidate variant takes its settings."""
import pytest

from script_loader import load_script


def test_the_candidate_variant_at_a_tiny_size(tmp_path, capsys):
    ba = load_script("benchmarks/maeno2008_before_after.py")
    out = ba.main(["--end-time", "0.05", "--scenes", "maeno2008", "--variants", "after", "candidate",
                   "--candidate", "numerics.viscous_scheme=implicit", "numerics.turbulence_step_limit=false",
                   "--out", str(tmp_path / "ba.md")])
    text = out.read_text()
    assert ("after = the scene files as they are; candidate = the scene files with "
            "numerics.viscous_scheme=implicit, numerics.turbulence_step_limit=false.") in text
    assert "before =" not in text
    assert "| maeno2008 | after |" in text and "| maeno2008 | candidate |" in text
    with pytest.raises(SystemExit):
        ba.main(["--variants", "after", "candidate", "--out", str(tmp_path / "x.md")])
    assert "goes with --variants" in capsys.readouterr().err
