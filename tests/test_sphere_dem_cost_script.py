"""benchmarks/sphere_dem_cost.py: its tables by hand, its hash of a state and its refusals (a run packs the
Maeno weir of 3D spheres: 35 CPU-s, too long for the suite)."""
import numpy as np
import pytest

from script_loader import load_script

sdc = load_script("benchmarks/sphere_dem_cost.py")


def run(cpu, h, contacts=100.0):
    return dict(cpu=cpu, simulated=2.0, mobile=10, substeps=1000, contacts=contacts, hash=h)


def test_the_cost_table_gives_medians_ranges_ratios_and_whether_the_bits_agree():
    rows = sdc.build_table(["before", "after"], [[run(4.0, "a"), run(5.0, "a"), run(6.0, "a")],
                                                 [run(3.0, "a"), run(2.0, "a"), run(2.5, "a")]])
    # CPU medians 5 and 2.5 s over 2 s simulated: real-time factors 2.5 and 1.25; 1e9 x 5 / (10 x 1000) ns
    assert rows[2] == ("| before | 5 [4 to 6] | 2.5 [2 to 3] | 5e+05 [4e+05 to 6e+05] | "
                       "5e+04 [4e+04 to 6e+04] | 1.000 | yes |")
    assert rows[3].startswith("| after | 2.5 [2 to 3] | 1.25 [1 to 1.5] |")
    assert rows[3].endswith("| 0.500 | yes |")
    rows = sdc.build_table(["x", "y"], [[run(1.0, "a")], [run(1.0, "b")]])
    assert rows[2].endswith("| NO: a |") and rows[3].endswith("| NO: b |")


def test_the_stage_table_apportions_the_process_time_by_the_timers_shares():
    r = dict(run(2.0, "a"), coupler={"dem": 3.0, "fluid": 1.0}, dem={"contacts": 2.0, "integrate": 1.0})
    rows = sdc.stage_table(r)
    assert rows[2] == "| coupler | dem | 75.0% | |"
    # contacts: half the timed 4 s of a run of 2 CPU-s over 10 spheres x 1000 substeps: 1e5 ns
    assert rows[4] == "| DEM | contacts | 50.0% | 100000.0 |"
    # the contact stage's 1 CPU-s over 100 contacts x 1000 substeps: 1e4 ns
    assert sdc.contact_ns(r) == pytest.approx(1e4)


def test_the_hash_sees_one_bit():
    a = {"x": np.array([1.0, 2.0]), "y": np.array([3.0])}
    b = {"x": np.array([1.0, np.nextafter(2.0, 3.0)]), "y": np.array([3.0])}
    assert sdc.state_hash(a) == sdc.state_hash(dict(a)) != sdc.state_hash(b)


def test_refusals_name_the_option(tmp_path):
    with pytest.raises(ValueError, match="--segment"):
        sdc.main(["--segment", "0", "--out", str(tmp_path / "x.md")])
    with pytest.raises(ValueError, match="LABEL=DIR"):
        sdc.main(["--build", "nolabel", "--out", str(tmp_path / "x.md")])


def test_the_report_from_canned_runs(tmp_path, monkeypatch):
    seg = dict(run(2.0, "a"), simulated=10.0, flow_steps=1000, builds=10, active=711, wall_contacts=40.0,
               pairs=150.0, dt=6.25e-5, contact_steps=32.0, stable_dt=8e-5, kn=1.87e5,
               coupler={"dem": 3.0, "fluid": 1.0}, dem={"contacts": 2.0})
    prep = dict(cpu_build=35.0, cpu_spin_up=4.8, spin_up=20.0, steps_spin_up=2098)
    monkeypatch.setattr(sdc, "run_child", lambda build, args, mode: prep if mode == "prepare" else seg)
    sdc.main(["--rounds", "2", "--build", "a=x=dir", "b=", "--out", str(tmp_path / "c.md")])
    text = (tmp_path / "c.md").read_text()
    assert "- build 0: a=x\n- build 1: b\n" in text  # a label may hold '='; the directory follows the last
    assert "1000 flow steps (10.00 ms on average), 1000 DEM substeps (1.0 per flow step: the DEM step 6.25e-05 s, " \
           "32 steps per contact" in text
    assert "| b | 2 [2 to 2] | 0.2 [0.2 to 0.2] |" in text and "dir" not in text  # labels, never directories
