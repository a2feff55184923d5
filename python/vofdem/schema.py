"""The scene's schema engine, apart from the scene's sections (scene.py, flood.py, reference.py): the field
helpers every section shares (units, ranges, choices, flags), the validation of one value, a section to
and from a TOML table (units converted, unknown keys refused with the closest valid one suggested), TOML
text, and the parameter table. A numeric field carries its unit kind and allowed range in its metadata;
a value given as a string in a TOML file may carry a unit ("4.8 cm"), converted to the field's unit.
Errors are ValueError naming the parameter's dotted name, the value and the allowed range."""
from __future__ import annotations

import copy
import dataclasses
import difflib
import math
import re
from dataclasses import field
from typing import Any, Dict, List, Optional, Sequence, Tuple

try:  # Python >= 3.11
    import tomllib as _toml
except ModuleNotFoundError:  # pragma: no cover - Python 3.9/3.10
    import tomli as _toml  # type: ignore[no-redef]

# units a value given as a string may carry, by kind, as factors to the SI unit of that kind
_UNITS: Dict[str, Dict[str, float]] = {
    "length": {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "km": 1e3},
    "angle": {"deg": 1.0, "degree": 1.0, "degrees": 1.0, "rad": 180.0 / math.pi},  # to degrees
    "discharge": {"l/s": 1.0, "lps": 1.0, "m3/s": 1e3, "m^3/s": 1e3},  # to l/s
    "time": {"s": 1.0, "ms": 1e-3, "min": 60.0, "h": 3600.0},
    "density": {"kg/m3": 1.0, "kg/m^3": 1.0, "g/cm3": 1e3, "g/cm^3": 1e3},
    "discharge rate": {"l/s/s": 1.0, "lps/s": 1.0, "l/s/min": 1.0 / 60.0, "l/s/h": 1.0 / 3600.0,
                       "m3/s/s": 1e3, "m3/s/min": 1e3 / 60.0, "m3/s/h": 1e3 / 3600.0},  # to l/s per s
}
# the unit a field of each kind is stored in
_BASE_UNIT = {"length": "m", "angle": "deg", "discharge": "l/s", "time": "s", "density": "kg/m3",
              "discharge rate": "l/s per s"}


def _p(default, kind: Optional[str], lo: float, hi: float, doc: str, closed: str = "[]"):
    """A numeric parameter: unit kind, allowed range [lo, hi] (closed='()' etc. for open ends)."""
    return field(default=default, metadata=dict(kind=kind, lo=lo, hi=hi, closed=closed, doc=doc))


def _choice(default, choices: Sequence[str], doc: str):
    return field(default=default, metadata=dict(choices=tuple(choices), doc=doc))


def _flag(default: bool, doc: str):
    return field(default=default, metadata=dict(flag=True, doc=doc))


def _fmt(v: float) -> str:
    return repr(float(v)) if isinstance(v, float) else str(v)


def _range_text(md) -> str:
    lo, hi, c = md["lo"], md["hi"], md["closed"]
    unit = _BASE_UNIT.get(md["kind"], "")
    return f"{c[0]}{_fmt(lo)}, {_fmt(hi)}{c[1]}" + (f" {unit}" if unit else "")


def _check_number(name: str, value, md) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f"{name} = {value!r} must be a number in {_range_text(md)}")
    v = float(value)
    lo, hi, c = md["lo"], md["hi"], md["closed"]
    ok = math.isfinite(v) and (v >= lo if c[0] == "[" else v > lo) and (v <= hi if c[1] == "]" else v < hi)
    if not ok:
        hint = ""
        if md["kind"] == "discharge" and v > hi:
            hint = " (discharges ending in _lps are in l/s; write e.g. \"0.01 m3/s\" to give m3/s)"
        elif md["kind"] == "discharge" and 0 < v < 0.5:
            hint = " (looks like m3/s; this field is in l/s)"
        elif md["kind"] == "length" and v > hi:
            hint = " (lengths are in metres; write e.g. \"4.8 cm\" to give another unit)"
        elif md["kind"] == "angle" and 0 < v < 1.6 and lo > 1.6:
            hint = " (angles ending in _deg are in degrees; this looks like radians)"
        raise ValueError(f"{name} = {_fmt(value)} is outside the allowed range {_range_text(md)}{hint}")
    return v


def _check_list(name: str, value, md: Optional[dict] = None) -> None:
    """A list field: a list (a TOML array) whose entries are numbers, in md's range if given. Checked
    whatever the section's kind, so a key the kind ignores is still refused when it is malformed."""
    if not isinstance(value, (list, tuple)):
        raise ValueError(f"{name} = {value!r} must be a list of numbers")
    for j, v in enumerate(value):
        if md is None:
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise ValueError(f"{name}[{j}] = {v!r} must be a finite number")
        else:
            _check_number(f"{name}[{j}]", v, md)


def _parse_quantity(name: str, value, kind: Optional[str]):
    """Converts '4.8 cm' to the field's unit; numbers pass unchanged."""
    if not isinstance(value, str):
        return value
    m = re.fullmatch(r"\s*([-+0-9.eE]+)\s*([A-Za-z/^0-9]*)\s*", value)
    if m is None:
        raise ValueError(f"{name} = {value!r} is not a number or a number with a unit")
    number, unit = float(m.group(1)), m.group(2)
    if kind is None:
        if unit:
            raise ValueError(f"{name} = {value!r}: this parameter is dimensionless, it takes no unit")
        return number
    if unit == "":
        return number
    table = _UNITS[kind]
    if unit not in table:
        other = [k for k, t in _UNITS.items() if unit in t]
        what = f"'{unit}' is a unit of {other[0]}" if other else f"unknown unit '{unit}'"
        raise ValueError(f"{name} = {value!r}: {what}; {name.split('.')[-1]} is a {kind} "
                         f"(use one of {', '.join(table)})")
    return number * table[unit]


class _Section:
    """Field-by-field validation shared by the scene's sections."""

    def _validate_fields(self, prefix: str) -> None:
        for f in dataclasses.fields(self):
            md = f.metadata
            name = f"{prefix}.{f.name}"
            value = getattr(self, f.name)
            if "lo" in md:
                if value is None and f.default is None:
                    continue
                setattr(self, f.name, _check_number(name, value, md))
            elif "choices" in md:
                if value is None and f.default is None:  # an optional choice left unset
                    continue
                if value not in md["choices"]:
                    raise ValueError(f"{name} = {value!r} is not one of {', '.join(map(repr, md['choices']))}")
            elif "flag" in md:
                if not isinstance(value, bool):
                    raise ValueError(f"{name} = {value!r} must be true or false")


def _unknown(key: str, valid, where: str, prefix: Optional[str] = None) -> str:
    close = difflib.get_close_matches(key, list(valid), n=1, cutoff=0.5)
    name = f"{prefix}.{key}" if prefix else key
    hint = f"; did you mean '{close[0]}'?" if close else f"; valid keys: {', '.join(sorted(valid))}"
    return f"unknown key '{name}' in {where}{hint}"


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return repr(v) if math.isfinite(v) else ("inf" if v > 0 else "-inf" if v < 0 else "nan")
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    raise TypeError(f"cannot write {type(v).__name__} to TOML")


def section_dict(sec) -> Dict[str, Any]:
    """A section's keys and values (TOML-ready), without the Python-only fields and unset optional ones."""
    d = {}
    for f in dataclasses.fields(sec):
        v = getattr(sec, f.name)
        if f.metadata.get("python_only") or v is None:
            continue
        d[f.name] = copy.deepcopy(v)
    return d


def section_args(sec_cls, table: Dict[str, Any], where: str, list_kinds: Dict[str, Optional[str]]) -> Dict[str, Any]:
    """A section's constructor arguments from a TOML table: unknown keys refused, units converted (also of
    the entries of the lists named in list_kinds, {key: unit kind})."""
    fields = {f.name: f for f in dataclasses.fields(sec_cls) if not f.metadata.get("python_only")}
    args = {}
    for k, v in table.items():
        if k not in fields:
            raise ValueError(_unknown(k, fields, f"[{where}]", prefix=where))
        md = fields[k].metadata
        args[k] = _parse_quantity(f"{where}.{k}", v, md.get("kind")) if "lo" in md else v
    for k, kind in list_kinds.items():
        if k in args and isinstance(args[k], list):
            args[k] = [_parse_quantity(f"{where}.{k}[{j}]", v, kind) if not isinstance(v, list) else v
                       for j, v in enumerate(args[k])]
    return args


def parse_toml(text: str, source: str) -> Dict[str, Any]:
    """The tables of a TOML text; ValueError naming `source` when it is not TOML."""
    try:
        return _toml.loads(text)
    except _toml.TOMLDecodeError as e:
        raise ValueError(f"{source}: not valid TOML: {e}") from None


def toml_table(header: Optional[str], table: Dict[str, Any]) -> List[str]:
    """The lines of one TOML table (header '[name]' or '[[name]]'; None: top-level keys)."""
    return ([header] if header else []) + [f"{k} = {_toml_value(v)}" for k, v in table.items()]


def describe(sections: Sequence[Tuple[str, Any]]) -> str:
    """A markdown table of every field of the sections [(key, class)]: name, default, range, meaning."""
    rows = ["| parameter | default | allowed | meaning |", "|---|---|---|---|"]
    for key, cls in sections:
        for f in dataclasses.fields(cls):
            md = f.metadata
            if md.get("python_only"):
                continue
            default = f.default if f.default is not dataclasses.MISSING else f.default_factory()
            allowed = _range_text(md) if "lo" in md else (" / ".join(md["choices"]) if "choices" in md
                                                            else ("true / false" if "flag" in md else
                                                                  ("text" if "text" in md else "list")))
            rows.append(f"| {key}.{f.name} | {default!r} | {allowed} | {md.get('doc', '')} |")
    return "\n".join(rows)
