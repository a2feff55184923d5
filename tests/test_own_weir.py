"""scenes/own_weir.toml, a graded two-layer weir under a CSV flood, through the commands a user types, and the
reports of a scene without reference data: no text they write, print or draw names a source it does not
cite. The solver is the test double (tests/fake_sim.py) but for one short real run."""
import re
from pathlib import Path

import pytest
from fake_sim import FakeSimulation
from matplotlib.figure import Figure
from matplotlib.text import Text

from vofdem import cli
from vofdem.ensemble import run_ensemble
from vofdem.scene import load_scene

ROOT = Path(__file__).resolve().parents[1]
SCENE = ROOT / "scenes" / "own_weir.toml"
# the years as words: a measured time such as 0.2008 s or 2008.5 s in a cost table is not a citation
UNCITED = re.compile(r"paper|maeno|tomita|experiment|(?<![\d.])(?:2002|2008)(?!\.?\d)|observed|model's", re.IGNORECASE)


@pytest.fixture
def drawn_texts(monkeypatch):
    """Every text of every figure saved while the test runs."""
    texts = []
    save = Figure.savefig

    def spy(fig, *a, **k):
        texts.extend(t.get_text() for t in fig.findobj(Text))
        return save(fig, *a, **k)

    monkeypatch.setattr(Figure, "savefig", spy)
    return texts


def _reports(out: Path):
    return {p.relative_to(out).as_posix(): p.read_text(encoding="utf-8")
            for p in out.rglob("*") if p.suffix in (".md", ".csv") and p.name != "crest_lowering.csv"}


def test_the_scene_is_graded_two_layer_under_a_csv_flood_without_reference():
    s = load_scene(SCENE)
    assert s.hydrograph.kind == "csv" and s.hydrograph.file == "own_weir_flood.csv" and len(s.hydrograph.times) == 7
    assert [z.name for z in s.zones] == ["armour"] and s.stones.grading() is not None and s.weir.outline
    assert not s.reference.given


def test_check_and_quick_run_report_without_naming_an_uncited_source(tmp_path, capsys, drawn_texts):
    assert cli.main(["check", str(SCENE)]) == 0
    capsys.readouterr()
    out = tmp_path / "run"
    assert cli.main(["run", str(SCENE), "--quick", "--out", str(out), "--no-progress", "--no-animation"],
                    build=lambda s: FakeSimulation(s)) == 0
    printed = capsys.readouterr().out
    reports = _reports(out)
    assert {"stage_table.md", "stage_table.csv", "profile.md", "grading.md"} <= set(reports)
    assert (out / "figures" / "hydrograph.png").exists() and (out / "figures" / "grading.png").exists()
    assert "| armour |" not in reports["grading.md"] and "**armour**" in reports["grading.md"]
    assert "**core**" in reports["grading.md"] and "measured flood own_weir_flood.csv" in " ".join(drawn_texts)
    for name, text in [("stdout", printed), *reports.items(), ("figures", "\n".join(drawn_texts))]:
        hit = UNCITED.search(text)
        assert hit is None, f"{name} mentions {hit.group(0)!r}"


def test_until_failure_ensemble_reports_without_naming_an_uncited_source(tmp_path, drawn_texts):
    s = load_scene(SCENE).quick().until_failure()
    run_ensemble(s, [0, 1], tmp_path, build=lambda sc: FakeSimulation(sc), workers=0, n_boot=50, progress=False,
                 dashboard=False, log=lambda *a: None)
    reports = _reports(tmp_path)
    assert "until_failure.md" in reports and "ensemble.md" in reports and "fragility.csv" in reports
    for name, text in [*reports.items(), ("figures", "\n".join(drawn_texts))]:
        hit = UNCITED.search(text)
        assert hit is None, f"{name} mentions {hit.group(0)!r}"


def test_the_maeno_scene_names_the_sources_it_cites(tmp_path, drawn_texts):
    out = tmp_path / "m"
    assert cli.main(["run", "maeno2008", "--quick", "--out", str(out), "--no-progress", "--no-animation"],
                    build=lambda s: FakeSimulation(s)) == 0
    md = (out / "stage_table.md").read_text()
    assert "experiment of Maeno et al. (2002), as cited by Maeno & Tomita (2008)" in md
    assert "model: VOF-DEM model of Maeno & Tomita (2008)" in md
    assert any("observed stages 14 / 16.5 / 20.4 l/s" in t for t in drawn_texts)


def test_a_short_real_run_of_the_own_weir(tmp_path):
    from vofdem.run import run_scene

    s = load_scene(SCENE).quick().replace(end_time=6.0)
    res = run_scene(s, tmp_path, progress=False, figures=False, animation=False)
    assert res.simulated_seconds == pytest.approx(6.0)
    md = (tmp_path / "grading.md").read_text()
    assert "**armour**" in md and "**core**" in md and "DEM step" in md
    assert UNCITED.search(md + (tmp_path / "stage_table.md").read_text()) is None
