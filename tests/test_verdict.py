"""The prediction study (studies/maeno2008_verdict.py, vofdem.study): the censored statistics and the
paired bootstrap of a shift against hand values, the study end to end in this process with a test
double whose stones go at known discharges (its tables against a hand computation; a second call runs
nothing), the study with the real solver at a tiny size, and the fidelity presets."""
import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from fake_sim import FakeSimulation
from script_loader import load_script

from vofdem.cli import main as cli_main
from vofdem.fragility import empirical_quantile
from vofdem.scene import Scene, load_scene
from vofdem.study import event_summary, knob_settings, km_quantiles, median_shift, shown_path, stage_fractions
from vofdem.study import parse_numbers

ROOT = Path(__file__).resolve().parents[1]


def _script():
    return load_script("studies/maeno2008_verdict.py")


def _frame(seeds, first, last=25.0, stages=None):
    """An outcome table by hand: first removal [l/s] per seed (None: never), censored at `last`."""
    n = len(seeds)
    return pd.DataFrame({"member": [f"seed{s}" for s in seeds], "seed": seeds, "status": ["completed"] * n,
                         "first_removal_lps": [np.nan if v is None else v for v in first],
                         "stage1_lps": [np.nan] * n, "stage2_lps": [np.nan] * n, "stage3_lps": [np.nan] * n,
                         "stages": stages or [0] * n, "last_discharge_lps": [last] * n,
                         "first_discharge_lps": [10.06] * n})


def test_the_cost_figure_separates_the_labels_of_neighbours_in_cost():
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(4.0, 3.0))
    FigureCanvasAgg(fig)
    ax = fig.subplots()
    ax.set_xscale("log")
    pts = [(47.4, 0.06), (50.3, 0.0), (60.3, 0.0), (60.4, -0.06), (65.3, 0.0), (68.4, 0.06), (111.0, 0.12)]
    for x, y in pts:
        ax.plot([x], [y], "o")
    texts = [ax.annotate(f"setting number {i}", p, textcoords="offset points", xytext=(4, 4), fontsize=7)
             for i, p in enumerate(pts)]
    fig.canvas.draw()
    boxes = lambda: [t.get_window_extent(fig.canvas.get_renderer()) for t in texts]  # noqa: E731
    overlapping = lambda bb: sum(a.overlaps(b) for i, a in enumerate(bb) for b in bb[i + 1:])  # noqa: E731
    assert overlapping(boxes()) > 0  # as placed, the labels of points this close overlap
    _script().separate_labels(fig, texts)
    assert overlapping(boxes()) == 0
    # the cheapest keeps its place; each moved one is a whole number of steps away from it
    assert texts[0].xyann == (4, 4)
    assert all((t.xyann[1] - 4) % 9 == 0 for t in texts)


def test_kaplan_meier_quantiles_with_censoring_by_hand():
    # 12 and 14 l/s, one member standing to 25 l/s: F = 1/3 after 12, 2/3 after 14, never 1
    q, obs = np.array([12.0, 14.0, 25.0]), np.array([True, True, False])
    assert km_quantiles(q, obs) == [12.0, 14.0, None]
    # the naive median of the two that failed would be 13; the censored one counts
    assert empirical_quantile(q, obs, 0.5) == 14.0
    s = event_summary(_frame([0, 1, 2], [12.0, 14.0, None]), "first_removal")
    assert (s["members"], s["happened"], s["censored_at_lps"]) == (3, 2, 25.0)
    assert (s["km_q16_lps"], s["km_median_lps"], s["km_q84_lps"]) == (12.0, 14.0, None)
    fr = stage_fractions(_frame([0, 1, 2, 3], [12.0, 14.0, None, 11.0], stages=[2, 1, 0, 3]))
    assert fr == {"with_removal": 0.75, "stages_1plus": 0.75, "stages_2plus": 0.5, "stages_3plus": 0.25}


def test_the_paired_bootstrap_of_a_shift_against_its_exact_distribution():
    ref = _frame([0, 1, 2], [12.0, 14.0, None])
    setting = _frame([0, 1, 2], [13.0, 16.0, None])
    sh = median_shift(ref, setting, "first_removal", n_boot=4000, seed=1)
    assert (sh.reference, sh.setting, sh.shift, sh.seeds) == (14.0, 16.0, 2.0, 3)
    # resamples of 3 seeds: a median is not reached when seed 2 is drawn twice or more, P = 7/27; of the
    # others, seed 0 drawn twice or more (P = 7/27) gives the shift +1, the rest (13/27) +2
    assert sh.left_out == pytest.approx(7 / 27, abs=0.02)
    assert (sh.lo, sh.hi) == (1.0, 2.0)
    # a constant shift of every seed is the shift of every resample
    same = median_shift(ref, _frame([0, 1, 2], [12.5, 14.5, None]), "first_removal", n_boot=200)
    assert (same.shift, same.lo, same.hi) == (0.5, 0.5, 0.5)
    # a median not reached has no shift; only the seeds both completed are paired
    none = median_shift(ref, _frame([0, 1, 2], [None, None, 13.0]), "first_removal", n_boot=50)
    assert none.setting is None and none.shift is None
    part = median_shift(ref, _frame([0, 1], [12.0, 14.0]), "first_removal", n_boot=0)
    assert part.seeds == 2 and (part.reference, part.setting) == (12.0, 12.0)


def test_the_cost_ratio_is_paired_with_the_references_members_at_the_same_seeds():
    mod = _script()
    ref = _frame([0, 1, 2, 3, 4], [12.0] * 5).assign(cpu_seconds=[10.0, 20.0, 30.0, 40.0, 50.0], wall_seconds=1.0,
                                                     steps=[100, 200, 300, 400, 500])
    fast = _frame([0, 1], [12.0, 12.0]).assign(cpu_seconds=[5.0, 7.0], wall_seconds=1.0, steps=[300, 500])
    res = {"verdict": {"s": ref}, "cost_scene": "s", "cost": {"cfl=0.25": fast},
           "settings": knob_settings(load_scene(ROOT / "scenes" / "maeno2008_rolling.toml"), "tiny", ["cfl"])}
    rows = {r["setting"]: r for r in mod.cost_rows(res, n_boot=0) if r["event"] == "first_removal"}
    # the reference's median over all its members is 30 s; over seeds 0 and 1 it is 15 s: 6 / 15
    assert rows["reference"]["cpu_s_per_member"] == 30.0 and rows["reference"]["cost_ratio"] == 1.0
    assert rows["cfl=0.25"]["cpu_s_per_member"] == 6.0
    assert rows["cfl=0.25"]["cost_ratio"] == pytest.approx(0.4, abs=1e-12)
    # the steps likewise: 400 against 150
    assert rows["reference"]["steps_per_member"] == 300.0 and rows["cfl=0.25"]["steps_ratio"] == pytest.approx(400 / 150)
    # a setting none of whose members finished is said to be not run, not to have a median not reached
    res["cost"]["cfl=0.25"] = fast.iloc[0:0]
    assert "| cfl: 0.25 | 0 of 0 | - (x-) | - (x-) | not run | not run | not run | not run |" in mod._cost_md(mod.cost_rows(res, 0))


def test_knob_settings_are_scene_keys_relative_to_the_reference():
    ref = load_scene(ROOT / "scenes" / "maeno2008_rolling.toml")
    by = {s.name: s for s in knob_settings(ref, "full")}
    assert by["grid=x2"].values == {"grid.dx": 0.05, "grid.dz": 0.02, "grid.dz_bed": 0.01,
                                    "grid.bed_layer_height": 0.01}
    assert by["ramp=30"].values == {"hydrograph.ramp_duration": 30.0}
    # the same contact stiffness: 64 steps of half the reference's step (32 of 6.25e-5 s)
    assert by["dem_steps=64"].values == {"numerics.dem_dt": 3.125e-05, "numerics.dem_contact_steps": 64.0}
    assert by["porosity=lookup"].scene(ref).numerics.porosity_method == "lookup"
    # the table's sub-areas per side: m = 8 unless named
    assert [by[f"porosity={v}"].scene(ref).numerics.lookup_m for v in ("lookup4", "lookup", "lookup16")] == [4, 8, 16]
    # the kernel mapping: at 1 d its default width (unset), else in metres from the nominal diameter (4.8 cm)
    assert by["bandwidth=1d"].scene(ref).numerics.coupling_mapping == "kernel"
    assert by["bandwidth=1d"].scene(ref).numerics.coupling_bandwidth is None
    assert by["bandwidth=1.5d"].values == {"numerics.coupling_mapping": "kernel", "numerics.coupling_bandwidth": 0.072}
    assert by["overflow=drag_lift"].scene(ref).numerics.overflow_load == "drag_lift"
    with pytest.raises(ValueError, match="knobs: 'mesh' is not one of grid"):
        knob_settings(ref, "small", ["mesh"])


def _build(scene):
    """Stones of the downstream face go at known discharges per seed; a CFL of 0.25 delays each by
    1 l/s (2 s of the quick scene's ramp, four snapshots), the porosity table changes nothing."""
    base = {0: [12.1, 12.3, 18.1, 18.2, 18.4], 1: [14.1, 14.3, 22.1, 22.2, 22.4], 2: [40.0] * 5}[scene.seed]
    delay = 1.0 if scene.numerics.cfl == 0.25 else 0.0
    return FakeSimulation(scene, thresholds_lps=[q + delay for q in base])


def test_the_study_end_to_end_against_a_hand_computation(tmp_path):
    mod = _script()
    args = ["--tiny", "--scenes", "maeno2008_rolling", "--seeds", "0-2", "--end-time", "36", "--widths", "0.5",
            "--workers", "0", "--n-boot", "200", "--out", str(tmp_path / "ens"), "--results", str(tmp_path),
            "--figures", str(tmp_path)]
    md = mod.main(args, build=_build, log=lambda *a: None)
    cost = pd.read_csv(tmp_path / "maeno2008_verdict_tiny_cost.csv")
    first = cost[cost["event"] == "first_removal"].set_index("setting")
    # the quick ramp: 10 -> 25 l/s over 30 s after 5 s; a stone going at 12.1 l/s (t = 9.2 s) is seen
    # removed at the next snapshot, 9.5 s (12.25 l/s); at 14.1 l/s at 13.5 s (14.25 l/s); seed 2 never
    # (censored at 25 l/s): the Kaplan-Meier median is the second of three, 14.25 l/s
    assert first.loc["reference", "median_lps"] == pytest.approx(14.25, abs=1e-9)
    assert first.loc["cfl=0.25", "median_lps"] == pytest.approx(15.25, abs=1e-9)
    assert first.loc["cfl=0.25", "shift_lps"] == pytest.approx(1.0, abs=1e-9)
    assert first.loc["cfl=0.25", ["shift_lo_lps", "shift_hi_lps"]].tolist() == pytest.approx([1.0, 1.0], abs=1e-9)
    assert first.loc["porosity=lookup", "shift_lps"] == pytest.approx(0.0, abs=1e-12)
    # the packings' spread: 16 % at 12.25, 84 % not reached
    assert first.loc["reference", "spread_lo_lps"] == pytest.approx(-2.0, abs=1e-9)
    assert np.isnan(first.loc["reference", "spread_hi_lps"])
    # stage 2 (three stones at 18.1-18.4 l/s for seed 0, 22.1-22.4 for seed 1): median 22.25
    st2 = cost[(cost["event"] == "stage2")].set_index("setting")
    assert st2.loc["reference", "median_lps"] == pytest.approx(22.25, abs=1e-9)
    verdict = pd.read_csv(tmp_path / "maeno2008_verdict_tiny_verdict.csv").set_index("event")
    assert verdict.loc["stage1", ["km_q16_lps", "km_median_lps"]].tolist() == pytest.approx([12.25, 14.25])
    assert np.isnan(verdict.loc["stage1", "km_q84_lps"]) and verdict.loc["stage2", "observed_lps"] == 16.5
    text = md.read_text()
    assert "with a removal 67%, failing in 2+ separate stages 67%, 3+ 0%" in text
    assert "| stage 1 | 2 of 3 (0) | 14.25 [12.25 to > 25.00] |" in text
    assert "| cfl: 0.25 | 3 of 3 |" in text and "| +1.00 [+1.00 to +1.00] |" in text
    # the quick reference holds the draft preset's values; no setting here is another preset
    assert "| draft | reference |" in text and "| median 14.25 |" in text
    assert "| standard | not in this study's settings |" in text
    assert (tmp_path / "maeno2008_verdict_tiny_cost.png").stat().st_size > 0
    assert (tmp_path / "maeno2008_verdict_tiny_fragility.png").stat().st_size > 0
    # the cost figure drawn again from its CSV: the reference a star of its own, not a text among the knobs'
    fig = mod.fig_cost(mod.cost_rows_from_csv(tmp_path / "maeno2008_verdict_tiny_cost.csv"), tmp_path / "again.png")
    assert [line.get_marker() for line in fig.axes[0].get_lines() if line.get_label() == "reference"] == ["*"]
    names = {t.get_text() for ax in fig.axes for t in ax.texts}
    assert "reference" not in names and {"cfl=0.25", "porosity=lookup"} <= names
    png = mod.main(["--tiny", "--redraw-cost", "--results", str(tmp_path), "--figures", str(tmp_path / "fig")],
                   log=lambda *a: None)
    assert png == tmp_path / "fig" / "maeno2008_verdict_tiny_cost.png" and png.stat().st_size > 0
    # resumable: a second call finds every member finished and runs none
    logs = []
    mod.run_study(mod._parser().parse_args(args), build=_build, log=logs.append)
    assert [m for m in logs if "ensemble of" in m] == [
        f"vofdem: ensemble of 3 members (3 already finished in {tmp_path / 'ens' / d})"
        for d in ("verdict/maeno2008_rolling", "cost/reference", "cost/cfl=0.25", "cost/porosity=lookup")]
    # --no-run: a member cut short is a row 'not run', its setting paired on the seeds both finished
    (tmp_path / "ens" / "cost" / "cfl=0.25" / "seed1" / "outcome.json").unlink()
    text = mod.main(args + ["--no-run"], build=_build, log=lambda *a: None).read_text()
    assert "| cfl: 0.25 | 2 of 3 |" in text
    assert not (tmp_path / "ens" / "cost" / "cfl=0.25" / "seed1" / "outcome.json").exists()
    cost = pd.read_csv(tmp_path / "maeno2008_verdict_tiny_cost.csv").set_index(["setting", "event"])
    assert cost.loc[("cfl=0.25", "first_removal"), "seeds"] == 2
    # the CPU ratios are against the reference's rerun at the knob seeds, not its verdict members; the
    # steps (the same on any machine) against its verdict members
    assert "removed the same stones as the verdict's members in 3 of 3 seeds" in text
    for d, cpu in (("reference", 2.0), ("porosity=lookup", 3.0)):
        for f in (tmp_path / "ens" / "cost" / d).glob("seed*/outcome.json"):
            row = json.loads(f.read_text())
            f.write_text(json.dumps({**row, "cpu_seconds": cpu, "steps": row["steps"] * (2 if "lookup" in d else 1)}))
    mod.main(args + ["--no-run"], build=_build, log=lambda *a: None)
    cost = pd.read_csv(tmp_path / "maeno2008_verdict_tiny_cost.csv").set_index(["setting", "event"])
    assert cost.loc[("porosity=lookup", "first_removal"), "cost_ratio"] == pytest.approx(1.5, abs=1e-12)
    assert cost.loc[("reference", "first_removal"), "cpu_s_per_member"] == pytest.approx(2.0, abs=1e-12)
    assert cost.loc[("porosity=lookup", "first_removal"), "steps_ratio"] == 2.0


def _earlier_verdict(tmp_path):
    """(the script, the tiny study's common options, the _verdict.csv of an earlier verdict over seeds 0-2)."""
    mod = _script()
    common = ["--tiny", "--scenes", "maeno2008_rolling", "--end-time", "36", "--workers", "0", "--n-boot", "20",
              "--results", str(tmp_path), "--figures", str(tmp_path)]
    mod.main(common + ["--parts", "verdict", "--seeds", "0-2", "--tag", "base", "--out", str(tmp_path / "a")],
             build=_build, log=lambda *a: None)
    return mod, common, tmp_path / "maeno2008_verdict_tiny_base_verdict.csv"


def test_the_width_part_alone_takes_the_scenes_own_width_from_an_earlier_verdict(tmp_path):
    mod, common, base_csv = _earlier_verdict(tmp_path)
    before = base_csv.read_bytes()
    wide = common + ["--parts", "width", "--widths", "0.4", "--width-seeds", "0-1", "--width-base", str(base_csv),
                     "--tag", "w", "--out", str(tmp_path / "b")]
    text = mod.main(wide, build=_build, log=lambda *a: None).read_text()
    # no verdict member ran and no verdict table was written; the earlier study's files are as they were
    assert not (tmp_path / "b" / "verdict").exists()
    assert not (tmp_path / "maeno2008_verdict_tiny_w_verdict.csv").exists()
    assert base_csv.read_bytes() == before and "## The verdict" not in text
    rows = pd.read_csv(tmp_path / "maeno2008_verdict_tiny_w_width.csv").set_index(["width_m", "event"])
    # B = 0.5 m: the earlier rows over seeds 0-2 (stage 1 at 12.25, 14.25, never: median 14.25); B = 0.4 m run
    # at seeds 0-1 (the test double's stones go at the same discharges: median 12.25, the lower of two)
    assert rows.loc[(0.5, "stage1"), ["km_median_lps", "members", "source"]].tolist() == [14.25, 3, "earlier study"]
    assert rows.loc[(0.4, "stage1"), ["km_median_lps", "members", "source"]].tolist() == [12.25, 2, "run"]
    assert rows.loc[(0.5, "stage1"), "stages_2plus"] == pytest.approx(2 / 3)
    assert "maeno2008_verdict_tiny_base_verdict.csv`) |" in text and "| 2 (0-1) |" in text
    assert str(tmp_path) not in text  # no machine's path
    assert (tmp_path / "maeno2008_verdict_tiny_w_width.png").stat().st_size > 0
    with pytest.raises(ValueError, match="width_base: .* width part alone"):
        mod.main(wide + ["--parts", "verdict", "width"], build=_build, log=lambda *a: None)


def test_the_wall_part_runs_the_stone_wall_frictions_and_takes_the_scenes_own_from_an_earlier_verdict(tmp_path):
    mod, common, base_csv = _earlier_verdict(tmp_path)
    seen = []  # the stone-wall friction of each member built

    def build(scene):
        seen.append(scene.stones.friction_wall)
        return _build(scene)

    wall = common + ["--parts", "wall", "--wall-frictions", "0.176", "0.35", "--wall-seeds", "0-1", "--wall-base",
                     str(base_csv), "--tag", "m", "--out", str(tmp_path / "b")]
    text = mod.main(wall, build=build, log=lambda *a: None).read_text()
    # the scene's own 0.176 is not run again: two members at 0.35, none of the verdict
    assert seen == [0.35, 0.35] and not (tmp_path / "b" / "verdict").exists()
    assert not (tmp_path / "maeno2008_verdict_tiny_m_verdict.csv").exists() and "## The verdict" not in text
    assert not (tmp_path / "maeno2008_verdict_tiny_m_width.csv").exists() and "## The width sweep" not in text
    rows = pd.read_csv(tmp_path / "maeno2008_verdict_tiny_m_wall.csv").set_index(["friction_wall", "event"])
    # 0.176: the earlier rows over seeds 0-2 (stage 1 at 12.25, 14.25, never: median 14.25); 0.35 run at seeds
    # 0-1 (the test double's stones go at the same discharges: median 12.25, the lower of two)
    assert rows.loc[(0.176, "stage1"), ["km_median_lps", "members", "source"]].tolist() == [14.25, 3, "earlier study"]
    assert rows.loc[(0.35, "stage1"), ["km_median_lps", "members", "source"]].tolist() == [12.25, 2, "run"]
    assert "## The stone-wall friction's sweep" in text and "| 0.35 | 0 | 24 | 12.25 |" in text
    assert "maeno2008_verdict_tiny_base_verdict.csv`) |" in text and "| 2 (0-1) |" in text
    assert "--wall-frictions 0.176 0.35 --wall-seeds 0-1" in text and str(tmp_path) not in text
    assert (tmp_path / "maeno2008_verdict_tiny_m_wall.png").stat().st_size > 0
    # resumable: a second call runs none of the finished members
    seen.clear()
    mod.main(wall, build=build, log=lambda *a: None)
    assert seen == []
    with pytest.raises(ValueError, match="wall_base: .* wall part alone"):
        mod.main(wall + ["--parts", "verdict", "wall"], build=build, log=lambda *a: None)
    with pytest.raises(ValueError, match=r"--wall-frictions: 2.5 is outside the allowed range \[0, 2\]"):
        mod.main(common + ["--parts", "wall", "--wall-frictions", "0.1", "2.5"], build=build, log=lambda *a: None)


def test_a_shown_path_is_relative_to_the_project_or_its_last_parts_never_absolute(tmp_path):
    assert shown_path(ROOT / "out" / "x", ROOT) == "out/x"
    assert shown_path(tmp_path / "a" / "b" / "c" / "d", ROOT) == "b/c/d"
    assert shown_path(tmp_path / "a" / "b", ROOT, tail=1) == "b"
    assert shown_path("/x", ROOT) == "x"  # fewer parts than asked: still without the anchor


def test_the_study_with_the_solver_at_a_tiny_size(tmp_path):
    """The script with the real solver: one seed of the quick scene for 2 s, the width sweep and one knob."""
    md = _script().main(["--tiny", "--scenes", "maeno2008_rolling", "--seeds", "0", "--end-time", "2",
                         "--knobs", "porosity", "--workers", "0", "--n-boot", "20", "--out", str(tmp_path / "ens"),
                         "--results", str(tmp_path), "--figures", str(tmp_path)], log=lambda *a: None)
    text = md.read_text()
    assert "| 0.4 | > 10.00 [> 10.00 to > 10.00] |" in text and "| 0.5 | > 10.00" in text
    assert "| porosity: lookup table, m = 8 | 1 of 1 |" in text
    width = pd.read_csv(tmp_path / "maeno2008_verdict_tiny_width.csv")
    assert sorted(set(width["width_m"])) == [0.4, 0.5] and (width["happened"] == 0).all()
    cost = pd.read_csv(tmp_path / "maeno2008_verdict_tiny_cost.csv")
    assert (cost["cpu_s_per_member"] > 0).all() and set(cost["setting"]) == {"reference", "porosity=lookup"}


# ---------------------------------------------------------------------------- fidelity presets
def test_a_preset_sets_its_knobs_and_a_scene_at_a_preset_holds_them():
    s = Scene.maeno2008().with_value("numerics.fidelity", "fine")
    assert (s.grid.dx, s.grid.dz, s.grid.dz_bed, s.numerics.cfl) == (0.0125, 0.005, 0.0025, 0.5)
    assert load_scene_text(s.to_toml()) == s.to_toml()
    with pytest.raises(ValueError, match=r"numerics.fidelity = 'fine' sets grid.dx = 0.0125, the scene has 0.03"):
        s.with_value("grid.dx", 0.03)
    with pytest.raises(ValueError, match=r"numerics.fidelity = 'ultra' is not one of 'draft', 'standard', 'fine'"):
        Scene.maeno2008().with_value("numerics.fidelity", "ultra")
    # a file naming a preset gets its values where it gives none, and is refused where it gives another
    text = Scene.maeno2008().to_toml().replace("[numerics]", '[numerics]\nfidelity = "draft"')
    with pytest.raises(ValueError, match="sets grid.dx = 0.05, the scene has 0.025"):
        Scene.from_toml(text)
    lines = [ln for ln in text.splitlines() if not ln.startswith(("dx =", "dz =", "dz_bed =", "bed_layer_height ="))]
    assert Scene.from_toml("\n".join(lines)).grid.dx == 0.05
    # --quick is the draft grid (a scene at a preset becomes 'draft'); without a preset its scene is unchanged
    assert "fidelity" not in Scene.maeno2008().quick().to_toml()
    assert Scene.maeno2008().with_value("numerics.fidelity", "standard").quick().numerics.fidelity == "draft"


def load_scene_text(text: str) -> str:
    return Scene.from_toml(text).to_toml()


def test_the_fidelity_option_of_the_command_line(capsys):
    assert cli_main(["check", "maeno2008", "--fidelity", "draft"]) == 0
    out = capsys.readouterr().out
    assert 'fidelity = "draft"' in out and "dx = 0.05" in out
    assert cli_main(["check", "maeno2008", "--fidelity", "ultra"]) == 2
    assert "numerics.fidelity = 'ultra' is not one of 'draft', 'standard', 'fine'" in capsys.readouterr().err


def test_the_width_sweep_raises_the_domain_where_the_narrower_water_would_reach_the_top():
    v = _script()
    s = load_scene(Path(__file__).resolve().parents[1] / "scenes" / "maeno2008_rolling_consistent.toml")
    # 25 l/s: the weir formula's level 0.3449 m through 0.5 m, 0.3604 m through 0.4 m, 0.3837 m through 0.3 m
    assert v.sweep_height(s, [0.3, 0.4]) == 0.42 and v.sweep_height(s, [0.4]) == 0.40  # 0.38 + 0.0388 / 0.0155
    assert v.sweep_height(s, []) == v.sweep_height(s, [0.5]) == v.sweep_height(s, [0.6]) == 0.38
    assert v.sweep_height(s.replace(end_time=10.0), [0.3]) == 0.41  # 10 l/s held: 0.3017 -> 0.3225 m, 0.4008 m


def test_the_coupling_in_words_names_3d_stones_by_their_drag_alone():
    from vofdem.study import coupling

    assert coupling(load_scene(ROOT / "scenes" / "maeno2008_rolling_consistent.toml")) == "consistent"
    assert coupling(load_scene(ROOT / "scenes" / "maeno2008_rolling.toml")) == "paper's"
    # spheres map their true void fraction whatever porosity_mapping says
    assert coupling(load_scene(ROOT / "scenes" / "maeno2008_spheres_rolling_consistent.toml")) == \
        "consistent, true void fraction"
    assert coupling(load_scene(ROOT / "scenes" / "maeno2008_spheres.toml")) == "paper's drag, true void fraction"


def test_parse_numbers_names_the_option_the_value_and_the_range():
    assert parse_numbers("16, 24", "--steps", 5.0, 1000.0) == [16.0, 24.0]
    assert parse_numbers("0,3", "--seeds", 0, 10, int) == [0, 3]
    assert parse_numbers("", "--mu-r", 0.0, 2.0, allow_empty=True) == []
    with pytest.raises(ValueError, match=r"--steps: '4' is outside the allowed range \[5, 1000\]"):
        parse_numbers("16,4", "--steps", 5.0, 1000.0)
    with pytest.raises(ValueError, match=r"--mu-r: 'x' is not a rolling friction in the allowed range \[0, 2\]"):
        parse_numbers("x", "--mu-r", 0.0, 2.0, what="a rolling friction")
    with pytest.raises(ValueError, match="--seeds: empty"):
        parse_numbers(" , ", "--seeds", 0, 10, int)
