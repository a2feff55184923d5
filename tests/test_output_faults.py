"""Output faults: an unwritable output directory is an error before the run starts; a full disk is an
error at the failing write naming the file, with the snapshots written before it kept and readable."""
import errno
import os
import pathlib
import shutil
import subprocess

import h5py
import numpy as np
import pytest
from fake_sim import FakeSimulation, short_scene

from vofdem.cli import main
from vofdem.io import OutputError, completed_snapshots
from vofdem.run import run_scene


def _never_built(scene):
    raise AssertionError("the simulation was built although the output cannot be written")


def test_unwritable_output_directory_is_an_error_before_the_run(tmp_path, capsys):
    blocker = tmp_path / "a_file"
    blocker.write_text("not a directory")
    with pytest.raises(ValueError, match=r"output directory '.*a_file/out' is not writable: Not a directory"):
        run_scene(short_scene(), blocker / "out", build=_never_built, progress=False)
    code = main(["run", "maeno2008", "--quick", "--out", str(blocker / "out"), "--no-progress"], build=_never_built)
    assert code == 2
    err = capsys.readouterr().err
    assert err.startswith("vofdem: error: output directory") and err.count("\n") == 1


def _full_disk_after(monkeypatch, calls: int):
    """Path.write_text fails with ENOSPC, as on a full disk, from its `calls`-th use on (the XDMF files)."""
    real = pathlib.Path.write_text
    count = [0]

    def write_text(self, *a, **kw):
        count[0] += 1
        if count[0] >= calls:
            raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC), str(self))
        return real(self, *a, **kw)

    monkeypatch.setattr(pathlib.Path, "write_text", write_text)


def test_a_full_disk_stops_the_run_at_the_failing_write_and_keeps_the_snapshots(tmp_path, monkeypatch, capsys):
    s = short_scene()
    # the XDMF files rewritten after every snapshot (xdmf_seconds = 0): scene.toml, the two XDMF files
    # when made, two per snapshot: the 14th write is snapshot 5's
    _full_disk_after(monkeypatch, 14)
    with pytest.raises(OutputError, match=r"writing '.*\.xmf' failed: \[Errno 28\] No space left on device") as e:
        run_scene(s, tmp_path / "out", sim=FakeSimulation(s), progress=False, xdmf_seconds=0.0)
    assert e.value.errno == errno.ENOSPC
    monkeypatch.undo()
    with h5py.File(tmp_path / "out" / "run.h5", "r") as f:  # plain h5py
        T = completed_snapshots(f["time"][()])
        assert T == 6 and f["time"][:T].tolist() == [0.0, 1.0, 2.0, 3.0, 4.0, 5.0]
        assert np.isfinite(f["fields/F"][:T]).all() and f.attrs["status"] == "failed: output could not be written"
    assert not list((tmp_path / "out").glob("*.tmp"))
    # the command line: one line, exit 1
    _full_disk_after(monkeypatch, 6)
    code = main(["run", "maeno2008", "--quick", "--end-time", "5", "--out", str(tmp_path / "cli"), "--no-progress",
                 "--xdmf-seconds", "0"], build=FakeSimulation)
    assert code == 1
    err = capsys.readouterr().err
    assert err.startswith("vofdem: output error: writing '") and "No space left on device" in err


def _mount_tmpfs(path, size):
    path.mkdir()
    r = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={size}", "tmpfs", str(path)], capture_output=True)
    if r.returncode != 0:
        pytest.skip(f"cannot mount a small tmpfs here (needs root and CAP_SYS_ADMIN): {r.stderr.decode().strip()}")


@pytest.mark.skipif(shutil.which("mount") is None or os.geteuid() != 0, reason="mounting a tmpfs needs root")
def test_a_real_full_disk(tmp_path):
    s = short_scene()  # 33 snapshots, run.h5 of about 1.1 MB made at once
    small, medium = tmp_path / "small", tmp_path / "medium"
    _mount_tmpfs(small, "400k")
    try:
        # the file is made at its full size: a disk too small for it fails before the first step
        with pytest.raises(OutputError, match=r"(?s)cannot make .*run.h5. \(33 snapshots\).*No space left") as e:
            run_scene(s, small / "out", sim=FakeSimulation(s), progress=False)
        assert e.value.errno == errno.ENOSPC
    finally:
        subprocess.run(["umount", "-l", str(small)], check=True)
    _mount_tmpfs(medium, "1150k")
    try:
        # the file fits, the XDMF files (rewritten after every snapshot) and the checkpoints fill the rest
        # during the run
        with pytest.raises(OutputError, match="No space left on device") as e:
            run_scene(s, medium / "out", sim=FakeSimulation(s), progress=False, figures=False, animation=False,
                      xdmf_seconds=0.0)
        assert e.value.errno == errno.ENOSPC
        with h5py.File(medium / "out" / "run.h5", "r") as f:
            T = completed_snapshots(f["time"][()])
            assert 1 <= T < 33 and np.isfinite(f["stones/pos"][:T]).all()
    finally:
        subprocess.run(["umount", "-l", str(medium)], check=True)


@pytest.mark.skipif(shutil.which("mount") is None or os.geteuid() != 0, reason="mounting a tmpfs needs root")
def test_a_read_only_file_system_is_an_error_before_the_run(tmp_path):
    ro = tmp_path / "ro"
    _mount_tmpfs(ro, "100k")
    try:
        subprocess.run(["mount", "-o", "remount,ro", str(ro)], check=True)
        with pytest.raises(ValueError, match=r"output directory '.*ro/out' is not writable: Read-only file system"):
            run_scene(short_scene(), ro / "out", build=_never_built, progress=False)
    finally:
        subprocess.run(["umount", "-l", str(ro)], check=True)
