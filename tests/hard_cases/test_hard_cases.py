"""The hard-case catalogue: one parametrised suite over every registered case (hc_*.py).

Each case builds a small scene, runs it, asserts what must hold and returns what it measured; the
conftest writes the results into docs/hard_cases.md (the costs into build/hard_cases_cost.md) when the whole
catalogue has run.
"""
import time

import pytest

import hc_flow  # noqa: F401  (each module registers its cases, in the table's order)
import hc_stones  # noqa: F401
import hc_coupled  # noqa: F401
import hc_errors  # noqa: F401
from hc_harness import CASES

# on several processes (pytest-xdist, --dist loadgroup) the catalogue runs on one, whose conftest sees every
# outcome and so writes docs/hard_cases.md; the session fixture is made once
pytestmark = pytest.mark.xdist_group("hard_cases")


def _params():
    out = []
    for c in CASES:
        marks = [pytest.mark.xfail(strict=True, reason=c.xfail)] if c.xfail else []
        out.append(pytest.param(c, id=c.name, marks=marks))
    return out


@pytest.mark.parametrize("case", _params())
def test_hard_case(case, hard_case_results):
    entry = hard_case_results.setdefault(case.name, {})
    t0 = time.perf_counter()
    try:
        entry["measured"] = case.run()
    except BaseException as e:
        entry["error"] = f"{type(e).__name__}: {e}"
        raise
    finally:
        entry["seconds"] = time.perf_counter() - t0


def test_catalogue_is_large_and_named():
    assert len(CASES) >= 30
    for c in CASES:
        assert c.name.replace("_", "").replace("-", "").replace(".", "").isalnum(), c.name
        assert c.hard and c.must_hold and c.group in ("flow", "stones", "coupled", "errors")


def test_the_overview_quotes_the_counts():
    import re
    from pathlib import Path

    text = (Path(__file__).resolve().parents[2] / "docs" / "overview.md").read_text(encoding="utf-8")
    total = re.search(r"runs (\d+) small scenes", text)
    counts = re.search(r"\*\*(\d+) pass, (\d+) are expected to fail\*\*", text)
    assert total and counts, "docs/overview.md's reliability paragraph is missing its counts"
    xfail = sum(1 for c in CASES if c.xfail)
    assert (int(total.group(1)), int(counts.group(1)), int(counts.group(2))) == (len(CASES), len(CASES) - xfail, xfail)
