"""Fuzzing the scene files: 240 seeded mutations of the Maeno 2008 scene and 60 of scenes/own_weir.toml (an
outline, sieve curves, a zone, a CSV flood) (wrong types, NaN, inf, negative,
huge, missing and unknown keys, broken lists, garbage TOML, an empty file). Each must load as a valid
scene or fail with a ValueError that names the key; through `vofdem check` it must exit 2 with one line
on stderr. Never a traceback of another type, never a crash."""
import copy
import math
from pathlib import Path
import random
import re
import subprocess
import sys

import pytest

from vofdem import cli
from vofdem.scene import Scene, load_scene

N_VARIANTS = 240
N_OWN = 60  # more, of the own weir's scene (outline, sieve curves, a zone, a CSV flood held in the scene)
BASE = Scene.maeno2008().to_dict()
OWN = load_scene(Path(__file__).resolve().parents[1] / "scenes" / "own_weir.toml").to_dict()

# replacement values, each a kind of wrong a user (or a script) writes
_WRONG = {
    "string": "abc", "unit string": "4.8 parsecs", "list": [1, 2], "empty list": [], "table": {"a": 1},
    "bool": True, "nan": math.nan, "inf": math.inf, "-inf": -math.inf, "negative": -1.0, "zero": 0,
    "huge": 1e300, "tiny": 1e-300, "big int": 10**30, "negative int": -3,
}


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return repr(v) if math.isfinite(v) else ("nan" if v != v else ("inf" if v > 0 else "-inf"))
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{k} = {_toml_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(type(v))


def to_toml(d) -> str:
    lines = [f"{k} = {_toml_value(v)}" for k, v in d.items() if not isinstance(v, dict)]
    for k, v in d.items():
        if isinstance(v, dict):
            lines += ["", f"[{k}]"] + [f"{kk} = {_toml_value(vv)}" for kk, vv in v.items()]
    return "\n".join(lines) + "\n"


def _paths(d):
    """(section or None, key) of every leaf of the scene dict."""
    out = []
    for k, v in d.items():
        if isinstance(v, dict):
            out += [(k, kk) for kk in v]
        else:
            out.append((None, k))
    return out


def mutate(rng: random.Random, base=None):
    """One mutated scene: (toml text, the key it names or None for garbage, what was done)."""
    d = copy.deepcopy(BASE if base is None else base)
    roll = rng.random()
    if "zones" in d and rng.random() < 0.3:  # a zone's key gone wrong
        key = rng.choice(list(d["zones"][0]))
        kind = rng.choice(list(_WRONG))
        d["zones"][0][key] = _WRONG[kind]
        return to_toml(d), f"zones[0].{key}", f"zone {kind}"
    if roll < 0.08:  # garbage TOML from a valid text
        text = to_toml(d)
        cut = rng.randrange(len(text))
        junk = rng.choice(["[", "]]", "=", '"', "{", "\x00", " = = ", "[flume", "\n[grid]\n[grid]\n"])
        return text[:cut] + junk + text[cut:], None, f"garbage at {cut}"
    sections = [k for k, v in d.items() if isinstance(v, dict)]
    if roll < 0.14:  # an unknown key
        sec = rng.choice(sections + [None])
        key = rng.choice(["bogus", "diamter", "lenght", "Q", "seeds"])
        (d[sec] if sec else d)[key] = 1.0
        return to_toml(d), key, "unknown key"
    if roll < 0.20:  # a missing key or section
        sec = rng.choice(sections)
        if rng.random() < 0.3:
            del d[sec]
            return to_toml(d), sec, "missing section"
        key = rng.choice(list(d[sec]))
        del d[sec][key]
        return to_toml(d), f"{sec}.{key}", "missing key"
    if roll < 0.24:  # a section that is not a table
        sec = rng.choice(sections)
        d[sec] = rng.choice([1, "abc", [1, 2]])
        return to_toml(d), sec, "section not a table"
    if roll < 0.34:  # keys a kind ignores: the table lists under a ramp, broken list entries
        key = rng.choice(["times", "discharge_lps"])
        d["hydrograph"][key] = rng.choice(["abc", 5, [0, "x"], [0, math.nan], [[1, 2]], [-1.0, 3.0], [True]])
        if rng.random() < 0.5:
            d["hydrograph"]["kind"] = "table"
        return to_toml(d), f"hydrograph.{key}", "list under any kind"  # all of them wrong: must fail
    if roll < 0.40:  # explicit stones gone wrong
        d["stones"]["positions"] = rng.choice(
            [5, "abc", [1, 2], [[1.0]], [[1.0, "x"]], [[math.nan, 0.1]], [[1e300, 0.1]], [[1.2, 0.03]] * 2])
        if rng.random() < 0.5:
            d["stones"]["diameters"] = rng.choice([0.05, ["x"], [0.05, 0.05], [-0.05], [[0.05]]])
        return to_toml(d), "stones.", "explicit stones"
    sec, key = rng.choice(_paths(d))
    kind = rng.choice(list(_WRONG))
    (d[sec] if sec else d)[key] = _WRONG[kind]
    return to_toml(d), f"{sec}.{key}" if sec else key, kind


VARIANTS = []
_rng = random.Random(20261124)
for _j in range(N_VARIANTS):
    VARIANTS.append(mutate(_rng))
for _j in range(N_OWN):
    VARIANTS.append(mutate(_rng, OWN))
VARIANTS.append(("", "empty", "empty file"))
VARIANTS.append(("# only a comment\n\n", "empty", "comment only"))


_MUST_FAIL = ("list under any kind", "empty file", "comment only", "section not a table")


def _check_outcome(path, names, what):
    try:
        scene = load_scene(path)
        assert not what.startswith(_MUST_FAIL), f"{what}: accepted as a valid scene"
    except ValueError as e:
        msg = str(e)
        assert "\n" not in msg.strip(), f"{what}: a multi-line message: {msg!r}"
        if names is None:  # garbage: broken TOML, or (inside a quoted text) a bad value named by its key
            assert "not valid TOML" in msg or re.search(r"\b[a-z_]+\.[a-z_]+(\[\d+\])? = ", msg), f"{what}: {msg}"
        else:
            assert names in msg or names.split(".")[-1] in msg, f"{what}: {msg!r} does not name {names!r}"
        return "error"
    # a valid scene: it validates again and round-trips through TOML
    scene.validate()
    assert Scene.from_toml(scene.to_toml()) == scene, what
    return "valid"


@pytest.mark.parametrize("j", range(0, len(VARIANTS), 20))
def test_mutated_scenes_load_or_name_the_key(tmp_path, j):
    outcomes = []
    for k in range(j, min(j + 20, len(VARIANTS))):
        text, names, what = VARIANTS[k]
        path = tmp_path / f"v{k}.toml"
        path.write_text(text, encoding="utf-8", errors="surrogateescape")
        outcomes.append(_check_outcome(path, names, f"variant {k} ({what}, {names})"))
    assert len(outcomes) == min(20, len(VARIANTS) - j)


@pytest.mark.parametrize("j", range(0, len(VARIANTS), 20))
def test_vofdem_check_exits_2_with_one_line(tmp_path, capsys, j):
    for k in range(j, min(j + 20, len(VARIANTS))):
        text, names, what = VARIANTS[k]
        path = tmp_path / f"v{k}.toml"
        path.write_text(text, encoding="utf-8", errors="surrogateescape")
        code = cli.main(["check", str(path)])
        out, err = capsys.readouterr()
        assert code in (0, 2), f"variant {k} ({what}): exit {code}"
        if code == 2:
            assert len(err.strip().splitlines()) == 1 and err.startswith("vofdem: error: "), err
        else:
            assert err == "" and Scene.from_toml(out) is not None


def test_the_fuzz_is_large_varied_and_reproducible():
    assert len(VARIANTS) >= 200
    kinds = {what.split(" at ")[0] for _, _, what in VARIANTS}
    for expected in ("garbage", "unknown key", "missing key", "nan", "inf", "negative", "huge", "string",
                     "list under any kind", "explicit stones", "empty file"):
        assert expected in kinds, expected
    rng = random.Random(20261124)
    again = [mutate(rng) for _ in range(3)]
    assert [v[0] for v in again] == [v[0] for v in VARIANTS[:3]]


def test_the_console_script_exits_2_with_one_line(tmp_path):
    # the installed entry point (a new process): a few variants of each outcome
    for k in (0, 1, N_VARIANTS + N_OWN):
        text, _, _ = VARIANTS[k]
        path = tmp_path / f"v{k}.toml"
        path.write_text(text, encoding="utf-8")
        r = subprocess.run([sys.executable, "-m", "vofdem", "check", str(path)], capture_output=True, text=True)
        assert r.returncode in (0, 2) and "Traceback" not in r.stderr
        if r.returncode == 2:
            assert len(r.stderr.strip().splitlines()) == 1
