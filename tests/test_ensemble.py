"""An ensemble over packings: seed parsing, one run per seed, the summary table (with the test double)."""
import pytest
from fake_sim import FakeSimulation, short_scene

from vofdem.cli import main
from vofdem.ensemble import parse_seeds, run_ensemble
from vofdem.io import RunData


def test_parse_seeds():
    assert parse_seeds("0-4") == [0, 1, 2, 3, 4]
    assert parse_seeds("0-2, 7") == [0, 1, 2, 7]
    assert parse_seeds("5") == [5]
    for bad in ("a", "3-1", "1,1", "-2", ""):
        with pytest.raises(ValueError, match="seeds"):
            parse_seeds(bad)


# per seed, the discharges [l/s] at which the double's five downstream stones go
THRESHOLDS = {0: [15.0, 15.2, 18.0, 18.1, 18.3], 1: [12.0, 12.2, 21.0, 21.1, 21.2], 2: [40.0] * 5}


def _build(scene):
    return FakeSimulation(scene, thresholds_lps=THRESHOLDS[scene.seed])



def test_ensemble_runs_each_seed_and_summarises(tmp_path):
    out = run_ensemble(short_scene(), [0, 1, 2], tmp_path, build=_build, progress=False, figures=False,
                       animation=False, log=lambda *a: None)
    assert [o.seed for o in out] == [0, 1, 2]
    for seed in (0, 1, 2):
        assert RunData(tmp_path / f"seed{seed}" / "run.h5").attrs["seed"] == seed
    # snapshots every 1 s = every 0.5 l/s: a removal is seen at the first snapshot at or above its discharge
    assert [len(o.stages) for o in out] == [2, 2, 0]
    assert out[0].stages[0] == (pytest.approx(15.0), 2) and out[1].stages[0] == (pytest.approx(12.0), 2)
    assert out[2].first_removal_lps is None and out[2].removed == 0
    md = (tmp_path / "ensemble.md").read_text()
    # stage 1 at 15.0 and 12.0 l/s: median 13.5, range 12-15; seed 2 has none
    assert "| stage 1 | 2 of 3 seeds: median 13.50, range 12.00-15.00 | 14.0 | none |" in md
    assert "| 2 | none | none | 0 of" in md
    csv = (tmp_path / "ensemble.csv").read_text().splitlines()
    assert csv[0].startswith("seed,first_removal_lps,stage1_lps") and len(csv) == 4


def test_cli_seeds_option(tmp_path, capsys):
    code = main(["run", "maeno2008", "--quick", "--seeds", "0-1", "--end-time", "3", "--out", str(tmp_path),
                 "--no-animation", "--no-figures", "--no-progress"], build=_build)
    assert code == 0 and "| first removal of any stone |" in capsys.readouterr().out
    assert (tmp_path / "seed0" / "run.h5").exists() and (tmp_path / "seed1" / "run.h5").exists()
    assert main(["run", "maeno2008", "--seeds", "2-1"]) == 2
    assert "seeds: '2-1'" in capsys.readouterr().err
