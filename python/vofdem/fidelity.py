"""Fidelity presets: named sets of numerical knob values (``vofdem run SCENE --fidelity draft``, or the
scene key ``numerics.fidelity``).

A preset fixes the grid (the knob that sets most of a run's cost) and the numerical options the
accuracy-against-cost study varies around it (studies/maeno2008_verdict.py, docs/verdict.md):

=========  ==================================  =====  ========
preset     grid dx x dz, bed row dz_bed [cm]    CFL    porosity
=========  ==================================  =====  ========
draft      5 x 2, 1 (twice as coarse)           0.5    exact
standard   2.5 x 1, 0.5 (the paper's)           0.5    exact
fine       1.25 x 0.5, 0.25 (twice as fine)     0.5    exact
=========  ==================================  =====  ========

The values are absolute: the grid is the one the Maeno weir's 4.8 cm stones were studied on. The
DEM's step is not part of a preset: it belongs to the stone model (rolling resistance and polygons
need their own steps per contact, docs/dem.md). Without a preset (the key unset, the default) the
scene's own values are used. A scene at a preset holds exactly the preset's values: a scene file
naming a preset and giving one of its keys with another value is refused, naming both (set the
key, or drop the preset). ``--quick`` is the draft grid on a shortened flume under a hydrograph four
times faster (Scene.quick); a scene at a preset becomes 'draft' under it. Each preset's measured cost
per member and shift of the answer from 'standard' are in docs/verdict.md (The fidelity presets).
"""
from __future__ import annotations

from typing import Any, Dict, Optional

PRESETS: Dict[str, Dict[str, Any]] = {
    "draft": {"grid.dx": 0.05, "grid.dz": 0.02, "grid.dz_bed": 0.01, "grid.bed_layer_height": 0.01,
              "numerics.cfl": 0.5, "numerics.porosity_method": "exact"},
    "standard": {"grid.dx": 0.025, "grid.dz": 0.01, "grid.dz_bed": 0.005, "grid.bed_layer_height": 0.005,
                 "numerics.cfl": 0.5, "numerics.porosity_method": "exact"},
    "fine": {"grid.dx": 0.0125, "grid.dz": 0.005, "grid.dz_bed": 0.0025, "grid.bed_layer_height": 0.0025,
             "numerics.cfl": 0.5, "numerics.porosity_method": "exact"},
}
KEY = "numerics.fidelity"


def preset(name: str) -> Dict[str, Any]:
    """The knob values of a preset; ValueError naming the key and the allowed values."""
    if name not in PRESETS:
        raise ValueError(f"{KEY} = {name!r} is not one of {', '.join(map(repr, PRESETS))}")
    return PRESETS[name]


def fill_table(data: Dict[str, Any]) -> None:
    """A scene file's tables (a dict of sections) completed in place with the values of the preset it
    names in [numerics] fidelity, where the file does not give them (a conflict is left for `check`)."""
    numerics = data.get("numerics")
    name = numerics.get("fidelity") if isinstance(numerics, dict) else None
    if not isinstance(name, str) or name not in PRESETS:
        return  # no preset, or a bad one that the validation names
    for key, value in PRESETS[name].items():
        section, _, field = key.partition(".")
        table = data.setdefault(section, {})
        if isinstance(table, dict):
            table.setdefault(field, value)


def apply(scene, name: Optional[str]):
    """`scene` (modified in place) at the preset `name` (None: no preset, the values kept)."""
    scene.numerics.fidelity = name
    if name is None:
        return scene
    for key, value in preset(name).items():
        section, _, field = key.partition(".")
        setattr(getattr(scene, section), field, value)
    return scene


def check(scene) -> None:
    """A scene naming a preset holds its values; ValueError naming the preset, the key and both values."""
    name = scene.numerics.fidelity
    if name is None:
        return
    for key, value in preset(name).items():
        have = scene.value_of(key)
        if have != value:
            raise ValueError(f"{KEY} = {name!r} sets {key} = {value!r}, the scene has {have!r}: give the key "
                             f"the preset's value, or no preset (remove {KEY}) to choose it yourself")


def describe() -> str:
    """A markdown table of the presets' knob values."""
    keys = list(PRESETS["standard"])
    rows = ["| preset | " + " | ".join(keys) + " |", "|---|" + "---|" * len(keys)]
    rows += [f"| {n} | " + " | ".join(f"{v:g}" if isinstance(v, float) else str(v) for v in p.values()) + " |"
             for n, p in PRESETS.items()]
    return "\n".join(rows)
