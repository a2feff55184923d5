"""benchmarks/resume_cost.py at a tiny size: a killed quick member resumed with its weir packed again and
from its checkpoint's stones, to the same bits."""
import re

import pytest
from script_loader import load_script


@pytest.mark.slow
def test_both_resumes_end_with_the_same_bits(tmp_path):
    script = load_script("benchmarks/resume_cost.py")
    out = script.main(["--scene", "maeno2008", "--quick", "--end-time", "3", "--kill-at", "3",
                       "--out", str(tmp_path / "r.md")])
    text = out.read_text()
    assert "hold the same datasets bit for bit" in text
    cpu = {m.group(1): float(m.group(2)) for m in re.finditer(r"^\| (packed|checkpoint) \| [^|]+ \| ([\d.]+) \|", text, re.M)}
    assert cpu.keys() == {"packed", "checkpoint"} and min(cpu.values()) > 0.0
    assert re.search(r"its checkpoint holds \d+ of its 7 snapshots", text)
    with pytest.raises(ValueError, match="kill-at"):
        script.main(["--kill-at", "1"])
