"""vofdem: VOF-DEM coupled model of a rubble mound weir and its destruction, stone by stone.

The C++ core (``vofdem._core``) holds the solvers; this package adds the Python front. All
quantities are SI unless a name says otherwise (``discharge_lps`` is in litres per second).

``import vofdem`` gives what a user starts from (``__all__``): the scene (`Scene`, `load_scene`),
the run (`run_scene`), the three solver classes stepped in place (`VOFGrid`, `DEMSystem`, `Coupler`)
and the thread count. Every other class and function of the C++ core is reached as ``vofdem.Name``
too (or in ``vofdem._core``), and the modules as ``vofdem.scene``, ``vofdem.builder``, ...; the
scene and run modules are imported when first named, so ``import vofdem`` stays light.
"""
from __future__ import annotations

import importlib

from . import _core
from ._core import Coupler, DEMSystem, VOFGrid, __version__, set_threads

__all__ = ["Scene", "load_scene", "run_scene", "VOFGrid", "DEMSystem", "Coupler", "set_threads", "__version__"]

# names of the Python front, by the module that defines them (imported when first asked for)
_FRONT = {"Scene": "scene", "load_scene": "scene", "run_scene": "run", "drag_force": "closure",
          "porous_resistance": "closure", "make_porosity_mapper": "porosity", "porosity_from_discs": "porosity"}


def __getattr__(name: str):
    if name in _FRONT:
        value = getattr(importlib.import_module(f".{_FRONT[name]}", __name__), name)
        globals()[name] = value
        return value
    if not name.startswith("__"):
        try:
            return getattr(_core, name)
        except AttributeError:
            pass
    raise AttributeError(f"module 'vofdem' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(__all__) | set(_FRONT))
