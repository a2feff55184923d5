"""The command line: scene errors in one line with exit 2, a run with the test double, python -m."""
import os
import subprocess
import sys
from pathlib import Path

import pytest
from fake_sim import FakeSimulation

import vofdem
from vofdem.cli import main
from vofdem.io import RunData

ROOT = Path(__file__).resolve().parents[1]
# subprocesses import the same vofdem as this test (installed, or the source tree with its _core)
ENV = dict(os.environ, PYTHONPATH=str(Path(vofdem.__file__).resolve().parents[1]) + os.pathsep
           + os.environ.get("PYTHONPATH", ""))


def _cli(*args):
    return subprocess.run([sys.executable, "-m", "vofdem", *args], capture_output=True, text=True, env=ENV,
                          timeout=120)


def test_bad_scene_file_is_one_line_and_exit_2(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[weir]\nheight = 0.25\ncrest = 0.2\n")
    r = _cli("run", str(bad), "--out", str(tmp_path / "out"))
    assert r.returncode == 2
    assert r.stderr.strip().count("\n") == 0
    assert r.stderr.startswith("vofdem: error: ") and "unknown key 'weir.crest'" in r.stderr
    assert "did you mean 'crest_length'" in r.stderr
    assert not (tmp_path / "out").exists()


def test_unknown_scene_name_and_missing_file(capsys):
    assert main(["run", "nosuchscene"]) == 2
    assert "neither a file nor a ready scene (maeno2008)" in capsys.readouterr().err
    assert main(["run", "missing.toml"]) == 2
    assert "scene file 'missing.toml' does not exist" in capsys.readouterr().err


def test_check_and_params_commands():
    r = _cli("check", str(ROOT / "scenes" / "maeno2008.toml"), "--quick")
    assert r.returncode == 0 and 'name = "maeno2008_quick"' in r.stdout
    r = _cli("params")
    assert r.returncode == 0 and "| stones.n_exp | 0.41 |" in r.stdout


def test_run_with_a_test_double(tmp_path, capsys):
    sims = []

    def build(scene):
        sims.append(FakeSimulation(scene))
        return sims[-1]

    out = tmp_path / "out"
    code = main(["run", "maeno2008", "--quick", "--seed", "3", "--end-time", "6", "--out", str(out),
                 "--no-animation", "--no-figures", "--no-progress"], build=build)
    assert code == 0
    printed = capsys.readouterr().out
    assert "| fake_fluid |" in printed and "| event |" in printed
    d = RunData(out / "run.h5")
    assert d.attrs["seed"] == 3 and d.times[-1] == pytest.approx(6.0)
    assert sims[0].scene.name == "maeno2008_quick"


def test_solver_failure_exits_1_and_keeps_output(tmp_path, capsys):
    out = tmp_path / "out"
    code = main(["run", "maeno2008", "--quick", "--out", str(out), "--no-progress"],
                build=lambda s: FakeSimulation(s, fail_at=1.2))
    assert code == 1
    err = capsys.readouterr().err
    assert err.startswith("vofdem: solver failed at t = 1.2 s: fake stage 'pressure'")
    assert RunData(out / "run.h5").times.tolist() == [0.0, 0.5, 1.0]


def test_sigterm_closes_the_output_as_interrupted(tmp_path):
    import signal
    import time

    script = (
        "import sys, time; sys.path.insert(0, %r)\n"
        "from fake_sim import FakeSimulation\n"
        "class Slow(FakeSimulation):\n"
        "    def advance(self, t):\n"
        "        if self.time > 0: open(%r, 'w').close(); time.sleep(120)\n"
        "        super().advance(t)\n"
        "from vofdem.cli import main\n"
        "sys.exit(main(['run', 'maeno2008', '--quick', '--out', %r, '--no-progress'], build=Slow))\n"
    ) % (str(ROOT / "tests"), str(tmp_path / "stepping"), str(tmp_path / "out"))
    p = subprocess.Popen([sys.executable, "-c", script], env=ENV, stderr=subprocess.PIPE, text=True)
    # the second advance marks that one snapshot is written, then blocks until the signal comes
    deadline = time.monotonic() + 120
    while not (tmp_path / "stepping").exists() and time.monotonic() < deadline:
        time.sleep(0.05)
    p.send_signal(signal.SIGTERM)
    _, err = p.communicate(timeout=60)
    assert p.returncode == 130 and "interrupted" in err
    d = RunData(tmp_path / "out" / "run.h5")
    assert d.attrs["status"] == "interrupted" and d.times.size >= 1 and d.profile is not None


@pytest.mark.parametrize("option", ["checkpoint_seconds", "xdmf_seconds"])
def test_the_wall_time_intervals_are_checked_and_for_single_runs(tmp_path, capsys, option):
    flag = "--" + option.replace("_", "-")
    assert main(["run", "maeno2008", "--seeds", "0-1", flag, "5"]) == 2
    assert f"{flag} is for single runs" in capsys.readouterr().err
    built = []
    assert main(["run", "maeno2008", "--quick", "--out", str(tmp_path / "out"), flag, "-1",
                 "--no-progress"], build=lambda s: built.append(s) or FakeSimulation(s)) == 2
    assert f"{option} = -1.0 is out of range (allowed: >= 0 s)" in capsys.readouterr().err
    assert not built  # refused before the simulation is built
