"""The failure's mechanism (studies/failure_mechanism.py): the median member of an ensemble by hand, a
stage's stones, places and loads on hand-made trajectories, and the script end to end on an ensemble of
the test double whose stones go at known discharges."""
import math
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest
from fake_sim import FakeSimulation
from script_loader import load_script

from vofdem.analysis import analyse
from vofdem.scene import Scene


def _mod():
    return load_script("studies/failure_mechanism.py")


def test_the_median_member_orders_by_the_stages_then_first_removal_then_seed():
    df = pd.DataFrame({"seed": [0, 1, 2, 3, 4, 5], "status": ["completed"] * 5 + ["failed"],
                       "stage1_lps": [18.0, np.nan, 12.0, np.nan, 15.0, 11.0],
                       "stage2_lps": [np.nan] * 6, "stage3_lps": [np.nan] * 6,
                       "first_removal_lps": [11.0, 20.0, 12.0, np.nan, 15.0, 11.0]})
    # completed, in order: seed 2 (12), 4 (15), 0 (18), 1 (no stage, a removal at 20), 3 (nothing);
    # the failed seed 5 is left out; the lower median of five is the third
    assert _mod().median_member(df) == 0
    assert _mod().median_member(df[df["seed"] != 3]) == 4  # of four, the second
    # first stages alike (at the release): the second stage decides, then the third
    ties = pd.DataFrame({"seed": [0, 1, 2, 3], "status": ["completed"] * 4, "stage1_lps": [10.06] * 4,
                         "stage2_lps": [14.0, 15.5, 12.7, 14.0], "stage3_lps": [15.0, 19.4, 23.4, 13.0],
                         "first_removal_lps": [10.06] * 4})
    assert _mod().median_member(ties) == 3  # order 2, 3, 0, 1
    with pytest.raises(ValueError, match="no completed member"):
        _mod().median_member(df[df["status"] == "failed"])


def test_a_stages_places_and_loads_by_hand():
    scene = Scene.maeno2008()
    w, d = scene.weir, 0.048
    # three loose stones on the downstream slope and one fixed on the bed; stones 0 and 1 leave at t = 2 s
    x0 = np.array([w.x_crest_down + 0.2, w.x_crest_down + 0.3, w.x_crest_down + 0.4, w.x_crest_down + 0.3])
    z0 = np.array([0.10, 0.05, 0.08, 0.024])
    times = np.array([0.0, 1.0, 2.0, 3.0])
    pos = np.repeat(np.column_stack([x0, z0])[None], 4, axis=0)
    pos[2:, :2, 0] += 0.1  # more than a diameter: removed at t = 2 s, a stage of two
    weight = (2650.0 - 998.2) * 9.81 * math.pi * d ** 3 / 6.0  # submerged weight [N]
    drag, pressure = np.zeros((4, 4, 2)), np.zeros((4, 4, 2))
    # stone 0: (0.5, -0.1), stone 1: (0.5, 0.3), stone 2: (0.2, -0.2) weights
    drag[1] = [[0.3, 0.0], [0.5, 0.2], [0.1, 0.0], [9.0, 9.0]]  # times the weight, at t = 1 s
    pressure[1] = [[0.2, -0.1], [0.0, 0.1], [0.1, -0.2], [0.0, 0.0]]
    data = SimpleNamespace(times=times, pos=pos, diameter=np.full(4, d), fixed=np.array([0, 0, 0, 1], bool),
                           active=np.ones((4, 4), bool), force_drag=drag * weight, force_pressure=pressure * weight,
                           y=None, width=None)
    a = analyse(times, pos, data.diameter, w, lambda t: 10.0 + t, active=data.active, fixed=data.fixed)
    (row,) = _mod().stage_rows(data, a, scene)
    assert (row["stage"], row["stones"], row["discharge_lps"]) == (1, 2, 12.0)
    assert row["where"] == "downstream slope 2" and row["t_before"] == 1.0
    assert row["height"] == pytest.approx(0.075 / w.height, rel=1e-12)
    assert row["load_x"] == pytest.approx(0.5, rel=1e-12) and row["load_x_max"] == pytest.approx(0.5, rel=1e-12)
    assert row["load_z"] == pytest.approx(0.1, rel=1e-12) and row["load_z_max"] == pytest.approx(0.3, rel=1e-12)
    # the others: stone 2 alone (stone 3 is fixed)
    assert row["others"] == 1 and row["others_x"] == pytest.approx(0.2) and row["others_z"] == pytest.approx(-0.2)
    assert math.isnan(row["side_wall"])  # stones in the plane


def test_the_script_on_an_ensemble_of_the_test_double(tmp_path):
    from vofdem.ensemble import run_ensemble

    scene = Scene.maeno2008().quick().replace(end_time=36.0).validate()
    thresholds = {0: [12.1, 12.3, 18.1, 18.2, 18.4], 1: [14.1, 14.3, 22.1, 22.2, 22.4], 2: [40.0] * 5}
    run_ensemble(scene, [0, 1, 2], tmp_path / "ens", workers=0, progress=False, log=lambda *a: None,
                 build=lambda s: FakeSimulation(s, thresholds_lps=thresholds[s.seed]))
    mod = _mod()
    mod.main([str(tmp_path / "ens"), "--tag", "t", "--results", str(tmp_path), "--figures", str(tmp_path)])
    text = (tmp_path / "failure_mechanism_t.md").read_text()
    # first stages at 12.25, 14.25 l/s and none: the median member is packing 1, its stages of 2 and 3 stones
    assert "packing 1" in text.splitlines()[0]
    assert "| 1 | 14.25 | 2 | downstream slope 2 |" in text and "| 2 | 22.25 | 3 | downstream slope 3 |" in text
    assert (tmp_path / "failure_mechanism_t_destruction.png").stat().st_size > 0


def test_the_weight_from_a_nominal_diameter_is_the_weight_from_the_stones_volume():
    # run.h5 keeps nominal diameters: for a clump as for a disc, the volume-equivalent sphere's, so that
    # sphere_volume of them is the stone's own volume and the studies share one submerged weight
    from vofdem import _core
    from vofdem.study import number_or_dash, sphere_volume, submerged_weight

    p = _core.DEMParams()
    p.width = 0.2
    s = _core.DEMSystem(p, np.array([[0.1, 0.1], [0.3, 0.1]]), np.array([0.01, 0.02]), np.array([2650.0, 2650.0]),
                        [0, 0])
    s.set_clumps(np.vstack([_core.quarried_stone("pair_2", 0.02), _core.quarried_stone("tetra_4", 0.04)]), [0, 2, 6])
    volume = np.array([s.volume(i) for i in range(s.n)])
    d = np.array([s.nominal_diameter(i) for i in range(s.n)])
    assert sphere_volume(d) == pytest.approx(volume, rel=1e-12)
    w = submerged_weight(volume, s.stone_density)
    assert w == pytest.approx((2650.0 - 998.2) * 9.81 * volume, rel=1e-12)
    assert (number_or_dash(None), number_or_dash(math.nan), number_or_dash(0.125, "{:.1f}")) == ("-", "-", "0.1")
