"""Each default is written once, in its C++ header: a bound parameter struct's field quotes its default
only as `default X`, formatted from a default-constructed struct when the module is built, never as a
number copied into the docstring by hand (such copies drift: the header changes, the text does not).

For every default-constructible class of the extension, every property's docstring is read: a
`default X` must equal the field's value, and a bare number standing where a default stands (after a
comma or semicolon, at the end of a clause, ranges and parentheses aside) must not equal it."""
from __future__ import annotations

import inspect
import math
import re

import pytest

from vofdem import _core

# `default X`: a number, True/False or an enum member's name
_QUOTED = re.compile(r"\bdefault ([A-Za-z_][A-Za-z0-9_]*|-?[0-9][0-9.e+-]*)")
# a range "[a, b]" / "(a, b]" / "(0, 1)" and any parenthesis: not a default
_RANGE = re.compile(r"[\[(][^\[\]()]*[\])]")
# a bare number ending a clause: ", 0.4" ", 0.91 (source)" "; usual 8"
_BARE = re.compile(r"(?:^|[,;])\s*(?:usual\s+)?(-?[0-9][0-9.]*(?:e[+-]?[0-9]+)?)\s*(?=$|[,;])")


def _structs():
    for name in sorted(dir(_core)):
        cls = getattr(_core, name)
        if not inspect.isclass(cls) or name.startswith("_"):
            continue
        try:
            obj = cls()
        except TypeError:  # not default-constructible: no defaults of its own
            continue
        yield name, cls, obj


def _fields():
    out = []
    for name, cls, obj in _structs():
        for field, prop in vars(cls).items():
            if isinstance(prop, property) and isinstance(prop.__doc__, str):
                out.append((name, field, obj, prop.__doc__))
    return out


def _text(value) -> str | None:
    """The value as the binding formats it, or None for a value with no scalar text (arrays, structs)."""
    if isinstance(value, bool):
        return str(value)
    if hasattr(value, "name") and hasattr(value, "value"):  # an enum member
        return value.name
    if isinstance(value, (int, float)):
        return repr(value)
    return None


def _equal(quoted: str, value) -> bool:
    text = _text(value)
    if text is None:
        return False
    if isinstance(value, (int, float)) and not isinstance(value, bool) and not hasattr(value, "name"):
        try:
            return float(quoted) == float(value)
        except ValueError:
            return False
    return quoted == text


def _bare_numbers(doc: str) -> list[str]:
    text = _QUOTED.sub("", doc)
    while _RANGE.search(text):
        text = _RANGE.sub("", text)
    return _BARE.findall(text)


FIELDS = _fields()


def test_the_scan_reads_the_parameter_structs():
    names = {(s, f) for s, f, _, _ in FIELDS}
    for must in [("FlowParams", "k1"), ("CouplerParams", "n_exp"), ("Medium", "rho_water"), ("DEMParams", "dt")]:
        assert must in names, f"{must} not read: the scan misses a struct's properties"


@pytest.mark.parametrize("struct,field,obj,doc", FIELDS, ids=[f"{s}.{f}" for s, f, _, _ in FIELDS])
def test_a_docstring_quotes_its_default_from_the_struct(struct, field, obj, doc):
    value = getattr(obj, field)
    for quoted in _QUOTED.findall(doc):
        assert _equal(quoted, value), f"{struct}.{field}: docstring says default {quoted}, the struct has {value!r}"
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        for bare in _bare_numbers(doc):
            assert not math.isclose(float(bare), float(value), rel_tol=1e-12, abs_tol=0.0), (
                f"{struct}.{field}: docstring quotes its default {bare} by hand: {doc!r}")


def test_the_bare_number_rule_catches_a_hand_written_default():
    assert _bare_numbers("linear resistance coefficient of eq. (7) [-], 200") == ["200"]
    assert _bare_numbers("C_D [-], (0, 5], 0.91 (Schmeeckle et al. 2007)") == ["0.91"]
    assert _bare_numbers("sub-areas per side [-]; usual 8") == ["8"]
    assert _bare_numbers("a stone this close [-], [0, 0.5], 1e-6; 0: every one") == ["1e-6"]
    assert _bare_numbers("target Courant number [-], default 0.4") == []
    assert _bare_numbers("P_k <= limit * eps (Menter 1994: 10), 0 = off [-]") == []
