"""benchmarks/demo_time.py, the source of the README's time of `make demo`: it reads the demo's runs from the
Makefile (one copy of the commands) and refuses a recipe without them."""
import pytest

from script_loader import ROOT, load_script

demo = load_script("benchmarks/demo_time.py")


def test_the_demo_commands_are_the_makefiles_runs_ending_with_the_ensemble():
    cmds = demo.demo_commands(ROOT / "Makefile", "PY", "OUTDIR")
    assert len(cmds) == 2
    assert all(c[:4] == ["PY", "-m", "vofdem", "run"] for c in cmds)
    assert cmds[0][cmds[0].index("--out") + 1] == "OUTDIR/maeno2008_quick"
    assert "--seeds" in cmds[-1] and cmds[-1][cmds[-1].index("--out") + 1] == "OUTDIR/maeno2008_quick_fragility"


def test_a_recipe_without_runs_is_refused(tmp_path):
    mk = tmp_path / "Makefile"
    mk.write_text("demo: install\n\t@echo nothing\n")
    with pytest.raises(ValueError, match="demo recipe"):
        demo.demo_commands(mk, "PY", "OUT")


def test_the_table_adds_the_commands_up():
    text, cpu, wall = demo.table([(["PY", "a"], 1.25, 2.0), (["PY", "b"], 3.5, 4.0)], True, "")
    assert (cpu, wall) == (4.75, 6.0)
    assert "| total | 4.8 | 6.0 |" in text and "fragility figure: yes" in text
