"""studies/ensemble_pair.py: two small ensembles' tables paired by member, its counts by hand."""
import csv

from script_loader import load_script

ep = load_script("studies/ensemble_pair.py")
FIELDS = ["member", "seed", "status", "first_removal_lps", "first_discharge_lps", "stage1_lps", "stage1_stones",
          "stages", "removed", "cpu_seconds"]


def _write(d, rows):
    d.mkdir()
    with open(d / "ensemble.csv", "w", newline="") as f:
        w = csv.DictWriter(f, FIELDS)
        w.writeheader()
        for r in rows:
            w.writerow(dict(zip(FIELDS, r)))
    return d


def test_members_are_paired_and_counted(tmp_path):
    before = _write(tmp_path / "b", [
        ("seed0", 0, "completed", 10.0625, 10.0625, 10.0625, 14, 1, 14, 30.0),  # lost stones at the release
        ("seed1", 1, "completed", 18.75, 10.0625, "", "", 0, 1, 31.0),
        ("seed2", 2, "completed", "", 10.0625, "", "", 0, 0, 29.0),
        ("seed3", 3, "failed", "", 10.0625, "", "", 0, 0, 1.0)])  # not completed: left out
    after = _write(tmp_path / "a", [
        ("seed2", 2, "completed", 20.0, 10.0625, 20.0, 3, 2, 5, 28.0),
        ("seed0", 0, "completed", 15.0, 10.0625, 15.0, 6, 1, 6, 30.0),
        ("seed1", 1, "completed", 10.0625, 10.0625, "", "", 0, 1, 30.0)])
    text = ep.main([str(before), str(after), "--title", "T", "--preamble", "what changed",
                    "--out", str(tmp_path / "t.md")])
    lines = text.splitlines()
    assert lines[0] == "# T" and "what changed" in text and (tmp_path / "t.md").read_text() == text
    assert "| lost a stone at the release (the first discharge) | 1 | 1 |" in lines
    assert "| had a first stage | 1 | 2 |" in lines
    # before: 10.06, none, none -> the median is beyond the end; after: 15, 20, none -> 20
    assert "| first stage's median [l/s] (none: beyond the run's end) | not reached | 20.00 |" in lines
    assert "| failed in two stages or more | 0 | 1 |" in lines and "| stones removed in all | 15 | 12 |" in lines
    rows = [ln for ln in lines if ln.startswith("| seed")]
    assert rows == ["| seed0 | 10.06 / 15.00 | 10.06: 14 / 15.00: 6 | 14 / 6 |",
                    "| seed1 | 18.75 / 10.06 | - / - | 1 / 1 |",
                    "| seed2 | - / 20.00 | - / 20.00: 3 | 0 / 5 |"]
