"""vofdem: VOF-DEM coupled model of a rubble mound weir and its destruction, stone by stone.

The C++ core (``vofdem._core``) holds the solvers; this package adds the Python front. All
quantities are SI unless a name says otherwise (``discharge_lps`` is in litres per second).
"""
from __future__ import annotations

from . import _core
from ._core import *  # noqa: F401,F403
from ._core import __version__
from .closure import drag_force, porous_resistance
from .porosity import make_porosity_mapper, porosity_from_discs

__all__ = [name for name in dir(_core) if not name.startswith("_")] + [
    "__version__",
    "drag_force",
    "porous_resistance",
    "make_porosity_mapper",
    "porosity_from_discs",
]
