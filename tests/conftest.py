"""The suite's solvers run on one thread: their results are the same bits for any thread count (which
tests/test_threads.py checks on two threads), and threads that wait for each other at every loop are
many times slower while other work holds the cores of a shared machine (docs/threads.md)."""
import pytest

from vofdem import _core


@pytest.fixture(autouse=True, scope="session")
def one_solver_thread():
    before = _core.threads()
    _core.set_threads(1)
    yield
    _core.set_threads(before)


_WORKER_LINES = []


@pytest.hookimpl(optionalhook=True)
def pytest_testnodedown(node, error):
    """pytest-xdist: keeps the summary line a worker's run of the hard-case catalogue sent."""
    line = getattr(node, "workeroutput", {}).get("hard_cases_summary")
    if line:
        _WORKER_LINES.append(line)


def pytest_terminal_summary(terminalreporter):
    for line in _WORKER_LINES:
        terminalreporter.write_line(line)
