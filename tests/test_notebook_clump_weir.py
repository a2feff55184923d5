"""notebooks/clump_weir.ipynb runs from top to bottom: a small weir of clumps packed by a scene of
stones.shape = 'clump', drawn in side and plan view, run a moment with the water kept."""
from notebook_util import run_notebook


def test_the_clump_weir_notebook_packs_draws_and_runs(tmp_path, monkeypatch):
    run = run_notebook("clump_weir.ipynb", tmp_path, monkeypatch, VOFDEM_NOTEBOOK_END_TIME="0.2")
    assert "clumps** (" in run.markdown and "after 0.2 s: water gained" in run.markdown
    assert run.images == 2
