"""Collects the catalogue's outcomes and writes docs/hard_cases.md once every case has run."""
import platform
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
TABLE = ROOT / "docs" / "hard_cases.md"
# the wall time of each case changes with every run and machine: a build artefact, not the page
COSTS = ROOT / "build" / "hard_cases_cost.md"
_RESULTS = {}
_OUTCOMES = {}


@pytest.fixture(scope="session")
def hard_case_results():
    return _RESULTS


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    rep = outcome.get_result()
    if item.originalname != "test_hard_case" or rep.when not in ("setup", "call"):
        return
    name = item.callspec.params["case"].name
    if rep.when == "setup" and rep.passed:
        return
    if hasattr(rep, "wasxfail"):
        _OUTCOMES[name] = "xfail" if rep.skipped else "xpass"
    else:
        _OUTCOMES[name] = "pass" if rep.passed else "FAIL"


def _counts(cases):
    out = {"pass": 0, "xfail": 0, "FAIL": 0, "xpass": 0}
    for c in cases:
        out[_OUTCOMES[c.name]] += 1
    return out


def _result_text(case):
    entry = _RESULTS.get(case.name, {})
    outcome = _OUTCOMES[case.name]
    if outcome == "pass":
        measured = entry.get("measured") or {}
        return "pass" + (": " + ", ".join(f"{k} {v}" for k, v in measured.items()) if measured else "")
    err = entry.get("error", "").splitlines()[0] if entry.get("error") else ""
    err = err.replace("|", "/")
    if len(err) > 220:
        err = err[:217] + "..."
    if outcome == "xfail":
        return f"expected failure: {err}"
    if outcome == "xpass":
        return "unexpected pass (strict expected failure: remove the mark)"
    return f"**FAIL**: {err}"


def _costs(cases) -> str:
    total = sum(_RESULTS.get(c.name, {}).get("seconds", 0.0) for c in cases)
    lines = ["# Hard cases: wall time of the last run", "",
             f"{total:.1f} s in all ({platform.machine()}, one core of a shared machine).", "",
             "| # | case | cost s |", "|---|---|---|"]
    for j, c in enumerate(cases, 1):
        lines.append(f"| {j} | `{c.name}` | {_RESULTS.get(c.name, {}).get('seconds', float('nan')):.1f} |")
    return "\n".join(lines) + "\n"


def _table(cases) -> str:
    n = _counts(cases)
    lines = [
        "# Hard cases",
        "",
        "Extreme situations the solver must survive, each a small scene in `tests/hard_cases/` with what must",
        "hold stated and asserted. This page is written by `tests/hard_cases/conftest.py` whenever the whole",
        "catalogue runs (`make test` runs it; alone: `python -m pytest tests/hard_cases`). Expected failures are",
        "strict: a case that starts to pass fails the suite until its mark is removed.",
        "",
        "A water budget to 1e-9 is closed by the advection's own bookkeeping: the stored water against the start,",
        "the fluxes through the boundary faces and the water its divergence correction makes where the pressure",
        "solve leaves a residual divergence (`VOFGrid.dilatation_volume`). That last water is asserted apart, below",
        "0.1 x the relative pressure tolerance of the volume (1e-6 at the scenes' 1e-5), and shown in the table.",
        "",
        f"**{len(cases)} cases: {n['pass']} pass, {n['xfail']} expected to fail"
        + (f", {n['FAIL']} FAIL" if n["FAIL"] else "") + (f", {n['xpass']} unexpected pass" if n["xpass"] else "")
        + ".** The wall time of each case goes to `build/hard_cases_cost.md`.",
        "",
        "| # | case | group | what is hard | what must hold | result |",
        "|---|---|---|---|---|---|",
    ]
    for j, c in enumerate(cases, 1):
        lines.append(f"| {j} | `{c.name}` | {c.group} | {c.hard} | {c.must_hold} | {_result_text(c)} |")
    xf = [c for c in cases if c.xfail]
    if xf:
        lines += ["", "## Expected failures and why", ""]
        lines += [f"- `{c.name}`: {c.xfail}" for c in xf]
    return "\n".join(lines) + "\n"


def pytest_sessionfinish(session, exitstatus):
    from hc_harness import CASES

    # a pytest-xdist worker prints nothing: its summary goes to the main process (tests/conftest.py shows it)
    if hasattr(session.config, "workeroutput") and _summary():
        session.config.workeroutput["hard_cases_summary"] = _summary()
    if not CASES or any(c.name not in _OUTCOMES for c in CASES):
        return  # only part of the catalogue ran: the table stays as it is
    if TABLE.parent.is_dir():
        text = _table(CASES)
        if not TABLE.exists() or TABLE.read_text(encoding="utf-8") != text:
            TABLE.write_text(text, encoding="utf-8")
        COSTS.parent.mkdir(exist_ok=True)
        COSTS.write_text(_costs(CASES), encoding="utf-8")


def _summary() -> str:
    from hc_harness import CASES

    ran = [c for c in CASES if c.name in _OUTCOMES]
    if not ran:
        return ""
    n = _counts(ran)
    return (f"hard cases: {len(ran)} run, {n['pass']} pass, {n['xfail']} expected to fail, {n['FAIL']} fail, "
            f"{n['xpass']} unexpected pass")


def pytest_terminal_summary(terminalreporter):
    if _summary():
        terminalreporter.write_line(_summary())
