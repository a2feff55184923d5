"""Failure analysis on synthetic trajectories whose removals and bursts are known by construction."""
import csv
import io

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from vofdem.analysis import StageCriterion, analyse, crest_level, find_bursts, removal_times
from vofdem.scene import Scene

D = 0.048


def _weir_stones(weir):
    """One layer of stones along the weir's surface: (n, 2) centres [m]."""
    xs = np.arange(weir.toe_x + D, weir.x_toe_down - D / 2, D)
    return np.stack([xs, np.maximum(weir.surface(xs) - D / 2, D / 2)], axis=1)


def _synthetic(removals, vib=0.3, seed=0):
    """Trajectories: stone i still (plus a vibration of `vib` diameters) until removals[i], then
    jumps 1.5 diameters downstream and keeps moving. Returns scene, times, pos, diameters."""
    scene = Scene.maeno2008()
    p0 = _weir_stones(scene.weir)
    n = len(p0)
    times = np.arange(0.0, 100.0 + 1e-9, 0.5)
    rng = np.random.default_rng(seed)
    pos = np.repeat(p0[None], times.size, axis=0)
    pos[1:] += vib * D * (rng.random((times.size - 1, n, 2)) - 0.5) * 2 / np.sqrt(2)
    for i, tr in removals.items():
        later = times >= tr
        pos[later, i, 0] = p0[i, 0] + 1.5 * D + 0.2 * (times[later] - tr)
        pos[later, i, 1] = max(D / 2, p0[i, 1] - 0.5 * D)
    return scene, times, pos, np.full(n, D)


def _index_at(weir, p0, x):
    return int(np.argmin(np.abs(p0[:, 0] - x)))


def test_bursts_are_found_with_their_time_discharge_count_and_place():
    scene = Scene.maeno2008()
    w = scene.weir
    p0 = _weir_stones(w)
    down = [i for i in range(len(p0)) if p0[i, 0] > w.x_crest_down + 2 * D][:4]
    shoulder = [i for i in range(len(p0)) if abs(p0[i, 0] - w.x_crest_down) <= D][:2]
    assert len(shoulder) == 2
    lone = _index_at(w, p0, w.toe_x + 3 * D)
    removals = {down[0]: 40.0, down[1]: 40.5, down[2]: 41.0, down[3]: 42.0,  # stage 1: 4 stones
                lone: 50.0,  # isolated
                shoulder[0]: 70.0, shoulder[1]: 71.5}  # stage 2: 2 stones
    scene, times, pos, d = _synthetic(removals)
    h = scene.hydrograph
    a = analyse(times, pos, d, w, h.discharge_lps_at, ramp_start=h.ramp_start)
    assert [s.n_stones for s in a.stages] == [4, 2]
    assert sorted(a.stages[0].stones) == sorted(down) and sorted(a.stages[1].stones) == sorted(shoulder)
    assert a.isolated == [lone]
    assert a.stages[0].start_time == 40.0 and a.stages[1].start_time == 70.0
    assert a.stages[0].clock_time == 20.0
    assert a.stages[0].discharge_lps == pytest.approx(10 + 15 * 20 / 120)
    assert a.stages[1].discharge_lps == pytest.approx(10 + 15 * 50 / 120)
    assert a.stages[0].location == "downstream slope" and a.stages[1].location == "shoulder"
    assert a.region[lone] == "upstream slope"
    # vibrating stones (0.3 d) are never removed
    assert np.isfinite(a.removal_time).sum() == len(removals)
    # the two shoulder stones were on the crest: the crest lowers when they go, not before
    assert a.crest_lowering[times < 70].max() < 0.3 * D + 1e-12
    assert a.crest_lowering[-1] > 0.3 * D


def test_stage_table_is_consistent_with_the_displacements():
    rng = np.random.default_rng(3)
    scene = Scene.maeno2008()
    n = len(_weir_stones(scene.weir))
    chosen = rng.choice(n, 12, replace=False)
    removals = {int(i): float(t) for i, t in zip(chosen, np.sort(rng.choice(np.arange(20, 180) * 0.5, 12, replace=False)))}
    scene, times, pos, d = _synthetic(removals, seed=4)
    h = scene.hydrograph
    a = analyse(times, pos, d, scene.weir, h.discharge_lps_at, ramp_start=h.ramp_start, reference=scene.reference)
    rows = list(csv.DictReader(io.StringIO(a.stage_table_csv())))
    assert len(rows) == len(a.stages)
    for row, s in zip(rows, a.stages):
        t0 = float(row["start_s"])
        k0 = int(np.flatnonzero(times == t0)[0])
        # every stone of the stage has moved more than one diameter by its end, none of them before
        # its own removal time, and the stage starts with the first of them
        for i in s.stones:
            k = np.flatnonzero(times == a.removal_time[i])[0]
            assert a.displacement[k, i] > d[i] and np.all(a.displacement[:k, i] <= d[i])
        assert min(a.removal_time[s.stones]) == t0 and times[k0] == t0
        assert int(row["stones"]) == sum(1 for t in removals.values() if s.start_time <= t <= s.end_time)
        assert float(row["discharge_lps"]) == pytest.approx(h.discharge_lps_at(t0), abs=1e-3)
    # all removals are in a stage or isolated, exactly once
    in_stages = [i for s in a.stages for i in s.stones]
    assert sorted(in_stages + a.isolated) == sorted(removals)
    md = a.stage_table_markdown()
    assert "| second stage |" in md and "16.5" in md and "17.1 (56.8)" in md and "20.4" in md
    assert "Compared with observed: experiment of Maeno et al. (2002)" in md


def _two_stage_analysis(reference):
    scene = Scene.maeno2008()
    p0 = _weir_stones(scene.weir)
    removals = {3: 40.0, 4: 40.5, 9: 70.0, 10: 71.0}
    scene, times, pos, d = _synthetic(removals)
    h = scene.hydrograph
    return analyse(times, pos, d, scene.weir, h.discharge_lps_at, ramp_start=h.ramp_start, reference=reference), p0


def test_stage_table_without_reference_compares_with_nothing():
    from vofdem.reference import Reference

    for ref in (None, Reference()):
        a, _ = _two_stage_analysis(ref)
        md, text = a.stage_table_markdown(), a.stage_table_csv()
        assert "| 1 | 40.0 | 12.50 | 2 |" in md and "| 2 | 70.0 | 16.25 | 2 |" in md
        for word in ("paper", "Paper", "Maeno", "experiment", "observed", "model", "clock", "Compared"):
            assert word not in md and word not in text, word
        assert text.splitlines()[0] == "stage,start_s,discharge_lps,stones,location"


def test_stage_table_shows_only_what_the_reference_gives():
    from vofdem.reference import Reference

    # observed discharges without times: no clock column, no model column
    ref = Reference(citation="gauge survey 2031", stage_lps=[15.5], note="read from a video")
    a, _ = _two_stage_analysis(ref)
    md, head = a.stage_table_markdown(), a.stage_table_csv().splitlines()[0]
    assert head == "stage,start_s,discharge_lps,stones,location,observed_lps"
    assert "Compared with observed: gauge survey 2031." in md and "clock" not in md and "model" not in md
    assert "| first stage | 12.50 | 15.5 |" in md and "| second stage | 16.25 | - |" in md
    assert "Observed: read from a video." in md
    # a model with times: the clock of the rise appears (simulation time - spin-up)
    ref = Reference(model_citation="a 2D model", model_stage_lps=[16.0, 19.0], model_stage_times=[24.0, 54.0])
    a, _ = _two_stage_analysis(ref)
    md, rows = a.stage_table_markdown(), list(csv.DictReader(io.StringIO(a.stage_table_csv())))
    assert "Clock of the rise = simulation time - 20 s." in md and "observed" not in md
    assert "| first stage | 12.50 (20.0) | 16 (24) |" in md
    assert rows[1]["clock_s"] == "50.0" and rows[1]["model_lps"] == "19.0" and rows[1]["model_clock_s"] == "54.0"


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(0, 200, allow_nan=False), max_size=40), st.floats(0.1, 10), st.integers(1, 4))
def test_bursts_partition_removals_and_respect_the_gap(times, gap, min_stones):
    t = np.array(times + [np.nan])
    stages, isolated = find_bursts(t, gap, min_stones)
    flat = [i for g in stages for i in g] + isolated
    assert sorted(flat) == list(range(len(times)))
    for g in stages:
        assert len(g) >= min_stones
        assert np.all(np.diff(t[g]) <= gap) and np.all(np.diff(t[g]) >= 0)
    # between consecutive stages there is a pause longer than the gap
    for a, b in zip(stages, stages[1:]):
        assert t[b[0]] - t[a[-1]] > gap


def test_removal_rules_fixed_inactive_and_factor():
    times = np.array([0.0, 1.0, 2.0])
    pos = np.zeros((3, 3, 2))
    pos[:, 0, 0] = [0.0, 0.03, 0.06]  # moves 0.06 > one diameter at t = 2
    pos[:, 1, 0] = [0.0, 0.10, 0.20]  # would move, but is fixed
    active = np.ones((3, 3), bool)
    active[1:, 2] = False  # left the domain at t = 1
    t = removal_times(times, pos, np.full(3, 0.048), active, fixed=np.array([False, True, False]))
    assert t[0] == 2.0 and np.isnan(t[1]) and t[2] == 1.0
    t2 = removal_times(times, pos, np.full(3, 0.048), factor=0.5)
    assert t2[0] == 1.0


def test_crest_level_of_a_flat_row():
    w = Scene.maeno2008().weir
    xs = np.arange(w.x_crest_up, w.x_crest_down + 1e-9, D)
    pos = np.stack([xs, np.full(xs.size, w.height - D / 2)], axis=1)[None]
    lvl = crest_level(pos, np.full(xs.size, D / 2), w, D)
    # bin centres fall between stone centres: the mean top lies between the touching-point and the tops
    assert w.height - D / 2 < lvl[0] <= w.height


def test_shape_errors_are_value_errors():
    w = Scene.maeno2008().weir
    with pytest.raises(ValueError, match=r"pos has shape \(2, 3, 2\), expected \(2, 4, 2\)"):
        analyse([0, 1], np.zeros((2, 3, 2)), np.full(4, D), w, lambda t: 10.0, criterion=StageCriterion())
