"""studies/release_stability.py at a tiny size: a 8 cm weir of 3 cm spheres across a 10 cm flume, one seed, a
1 s spin-up and 0.5 s after the release; the tables' structure and their numbers against the member's own
outcome and packing, the needed angle against a hand value, the options' ranges."""
import json
import math
import re

import pytest

import vofdem
from script_loader import load_script

rs = load_script("studies/release_stability.py")


def tiny_scene(path, ramp_duration=None):
    """The spheres' small test scene (tests/test_sphere_scenes.py) with the consistent coupling and a held
    spin-up of 1 s (and a ramp of ramp_duration [s] if given); written as TOML to path."""
    d = vofdem.Scene.maeno2008().to_dict()
    d["name"] = "release_tiny"
    d["stones"].update(shape="sphere", diameter=0.03, drag_model="bed")
    d["flume"].update(width=0.1, length=1.6, height=0.2)
    d["weir"].update(height=0.08, crest_length=0.06, toe_x=0.5)
    d["hydrograph"].update(discharge_start_lps=1.0, discharge_end_lps=2.0, spin_up_duration=1.0,
                           hold_stones_during_spin_up=True)
    if ramp_duration is not None:
        d["hydrograph"]["ramp_duration"] = ramp_duration
    d["grid"].update(dx=0.02)
    d["output"].update(snapshot_interval=0.25, figures=False, animation=False)
    path.write_text(vofdem.Scene.from_dict(d).validate().to_toml(), encoding="utf-8")
    return path


def test_tiny_study_writes_tables_from_its_own_run(tmp_path):
    scene = tiny_scene(tmp_path / "tiny.toml")
    out, res, fig = tmp_path / "ens", tmp_path / "r.md", tmp_path / "f.png"
    rs.main(["--scene", str(scene), "--seeds", "0", "--mu-r", "0", "--clump-mu-r", "", "--after", "0.5",
             "--window", "0.5", "--out", str(out), "--results", str(res), "--figure", str(fig)])
    text = res.read_text()
    # no machine path in a committed page: neither the run's own directory nor any absolute one
    assert fig.stat().st_size > 0 and str(tmp_path) not in text and not re.search(r"/(work|tmp|root|home)/", text)
    lines = text.splitlines()
    assert "## Per configuration" in lines and "## Per member" in lines
    assert "## Through the hydrograph" not in lines  # the members stop before the ramp's end
    # the heap angle of spheres at mu_r = 0 comes from benchmarks/results/sphere_calibration.md
    conf = [ln for ln in lines if ln.startswith("| spheres, mu_r = 0 | 20.1 |")]
    member = [ln for ln in lines if ln.startswith("| spheres, mu_r = 0 | 0 |")]
    assert len(conf) == 1 and len(member) == 1
    cells = [c.strip() for c in member[0].strip("|").split("|")]
    assert cells[2] == "completed"
    mdir = out / "spheres_mu_r=0" / "seed0"
    outcome = json.loads((mdir / "outcome.json").read_text())
    packing = json.loads((mdir / rs.PACKING_FILE).read_text())
    lost_release, lost_end = int(cells[3]), int(cells[5])
    assert lost_end == outcome["removed"] and 0 <= lost_release <= lost_end
    assert int(cells[6]) > 0  # surface stones of the downstream slope found in the held weir
    assert cells[10] == f"{packing['porosity']:.3f}" and 0.2 < packing["porosity"] < 0.8
    assert float(cells[11]) == pytest.approx(outcome["simulated_seconds"], abs=0.05)
    assert float(cells[11]) == pytest.approx(1.5, abs=0.05)  # the spin-up and 0.5 s after the release
    assert cells[12] == f"{outcome['cpu_seconds']:.0f}"
    # the angle needed is the slope's plus the resultant's tilt: finite, above the slope
    assert 27.0 < float(cells[9]) < 90.0
    # more packings on a page of their own: seed 1 (not run: --no-run), seed 0 from the page above
    res2 = tmp_path / "r2.md"
    rs.main(["--scene", str(scene), "--seeds", "1", "--mu-r", "0", "--clump-mu-r", "", "--after", "0.5",
             "--window", "0.5", "--out", str(out), "--results", str(res2), "--figure", str(fig), "--no-run",
             "--earlier", str(res)])
    text2 = res2.read_text()
    lines2 = text2.splitlines()
    # the earlier member's row as it was, but for its status; the run's summary counts it
    assert member[0].replace("| completed |", f"| {rs.EARLIER} |") in lines2
    assert [ln for ln in lines2 if ln.startswith("| spheres, mu_r = 0 | 1 | not run |")]
    summary = [c.strip() for c in [ln for ln in lines2 if ln.startswith("| spheres, mu_r = 0 | 20.1 |")][0].split("|")]
    n = lost_release
    assert summary[3] == "1 of 2" and summary[4] == f"{n} [{n}-{n}], sum {n}"
    assert "spheres, mu_r = 0 seed 0." in text2
    assert re.search(r"--earlier \S*/r\.md --results \S*/r2\.md --figure \S*/f\.png --out \S*/ens`", text2)
    assert str(tmp_path) not in text2 and not re.search(r"/(work|tmp|root|home)/", text2)
    # the page's own command line reruns it: no empty option value left bare
    assert "--mu-r '0' --clump-mu-r ''" in text2


def test_members_through_the_whole_ramp_get_the_verdicts_tables(tmp_path):
    """--after reaching the ramp's end adds the verdict's tables of the members run: events, shares, crest."""
    scene = tiny_scene(tmp_path / "tiny.toml", ramp_duration=0.5)
    out, res, fig = tmp_path / "ens", tmp_path / "r.md", tmp_path / "f.png"
    args = ["--scene", str(scene), "--seeds", "0", "--mu-r", "0", "--clump-mu-r", "", "--window", "0.5", "--out",
            str(out), "--results", str(res), "--figure", str(fig)]
    rs.main(args + ["--after", "0.5"])
    text = res.read_text()
    head, whole = text.split("## Through the hydrograph")
    outcome = json.loads((out / "spheres_mu_r=0" / "seed0" / "outcome.json").read_text())
    assert "**spheres, mu_r = 0** (sphere" in whole and "1 of 1 members completed" in whole
    first = [ln for ln in whole.splitlines() if ln.startswith("| first removal")]
    happened = 0 if outcome["first_removal_lps"] is None else 1
    assert len(first) == 1 and f"| {happened} of 1 (" in first[0]
    # the experiment's and the paper's model's second stage beside the run's
    assert re.search(r"\| stage 2 \| .* \| 16\.5 \| 17\.1 \|", whole)


def test_an_earlier_pages_member_row_reads_back_as_written():
    cfg = rs.Config("clump", 0.0)
    row = {"config": cfg.label, "seed": 2, "status": "completed", "cpu": 954.0, "removed": 3, "porosity": 0.501,
           "stones": 900, "lost_release": 1, "lost_end": 3, "stage_release": True, "stage_stones": 2,
           "simulated": 30.0, "surface": 88, "load_x": 0.42, "load_x_max": 0.61, "load_z": -0.12, "phi_needed": 47.5,
           "lost_where": {"upstream slope": 0, "crest": 0, "shoulder": 0, "downstream slope": 1}}
    args = rs.argparse.Namespace(seeds="2", after=10.0, window=2.0, no_run=False, out=rs.ROOT / "out" / "x",
                                 figure=rs.ROOT / "docs" / "f.png", earlier=None)
    base = vofdem.load_scene(rs.ROOT / "scenes" / "maeno2008_spheres_rolling_consistent.toml")
    summary = rs.config_rows([cfg], [row], {})
    page = rs.results_md(args, base, [cfg], [row], summary, "cmd")
    lines = [ln for ln in page.split("## Per member")[1].splitlines() if ln.startswith("| clumps")]
    # the per-member row, then where its lost stone lay (a table of its own, the regions in analysis' order)
    assert lines[1] == "| clumps, mu_r = 0 | 2 | 0 | 0 | 0 | 1 |" and "| crest | shoulder | downstream slope |" in page
    assert rs.earlier_rows_of(page, [cfg], []) == [rs.parsed_member([c.strip() for c in lines[0].strip("|").split("|")])]
    back = rs.parsed_member([c.strip() for c in lines[0].strip("|").split("|")])
    assert back == {**{k: row[k] for k in back if k != "status"}, "status": rs.EARLIER}
    no_stage = rs.parsed_member([c.strip() for c in lines[0].replace("yes (2)", "no").strip("|").split("|")])
    assert no_stage["stage_release"] is False and no_stage["stage_stones"] == 0


def test_needed_angle_by_hand():
    # 27 deg slope, a horizontal load of 0.4 W': 27 + atan(0.4) = 48.80 deg (the 46-51 deg hand estimate)
    assert rs.needed_angle(27.0, 0.4, 0.0) == pytest.approx(27.0 + math.degrees(math.atan(0.4)))
    assert rs.needed_angle(27.0, 0.4, 0.0) == pytest.approx(48.80, abs=0.01)
    assert rs.needed_angle(27.0, 0.0, 0.5) == pytest.approx(27.0)  # lift alone does not tilt the resultant


def test_options_are_checked():
    with pytest.raises(ValueError, match="--mu-r.*allowed range"):
        rs.parse_mu("0,3", "--mu-r")
    with pytest.raises(ValueError, match="--after"):
        rs.main(["--after", "0"])
    with pytest.raises(ValueError, match="--earlier: .*no such file"):
        rs.main(["--earlier", "studies/results/no_such_page.md"])
    assert rs.parse_mu("", "--clump-mu-r") == []


def test_clump_configuration_takes_the_clump_calibrations_step():
    base = vofdem.load_scene(rs.ROOT / "scenes" / "maeno2008_spheres_rolling_consistent.toml")
    s = rs.Config("clump", 0.0).scene(base)
    n, n0 = s.numerics, base.numerics
    assert s.stones.shape == "clump" and s.stones.rolling_friction == s.stones.rolling_friction_wall == 0.0
    assert n.dem_dt < n0.dem_dt  # the clumps' stable step is shorter than the spheres'
    assert n.dem_dt * n.dem_contact_steps == pytest.approx(n0.dem_dt * n0.dem_contact_steps)  # same stiffness
    sph = rs.Config("sphere", 0.4).scene(base)
    assert sph.stones.rolling_friction == sph.stones.rolling_friction_wall == 0.4
    assert sph.numerics.dem_dt == n0.dem_dt  # 32 steps per contact already
