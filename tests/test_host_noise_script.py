"""benchmarks/host_noise.py at a tiny size: both kernels alone and in pairs, the page's tables, and its options'
ranges."""
import re

import pytest
from script_loader import load_script


def test_a_tiny_run(tmp_path):
    script = load_script("benchmarks/host_noise.py")
    text = script.main(["--repeats", "1", "--megabytes", "1", "--out", str(tmp_path / "h.md")]).read_text()
    rows = re.findall(r"^\| (compute|memory) \| 1 \| ([\d.e-]+) \| ([\d.e-]+), ([\d.e-]+) \| ([\d.]+) \|$", text, re.M)
    assert [r[0] for r in rows] == ["compute", "memory"]
    for _, alone, a, b, ratio in rows:
        assert min(float(alone), float(a), float(b)) > 0.0
        assert float(ratio) == pytest.approx(max(float(a), float(b)) / float(alone), rel=0.01, abs=0.006)
    assert re.search(r"^\| memory \| [\d.e-]+ - [\d.e-]+ \| 1\.00 \| ", text, re.M)  # one run alone: no spread


def test_refuses_options_out_of_range():
    script = load_script("benchmarks/host_noise.py")
    with pytest.raises(ValueError, match=r"--repeats must be in \[1, 100\]"):
        script.main(["--repeats", "0"])
    with pytest.raises(ValueError, match=r"--megabytes must be in \[1, 4096\]"):
        script.main(["--megabytes", "5000"])
