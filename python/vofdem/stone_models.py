"""The Python front's side of the stone models (the C++ side: ``stone_model.h``, docs/stone_models.md).

Every stone model the scene can name (``stones.shape``, the C++ registry's names) has a front here,
registered under the same name: what the scene refuses for it, what its options give the packing
generator, how the shapes of explicit stones are drawn and put into a ``DEMSystem``, and what plots and
the run's output draw of it (tops, outlines, the shapes written to run.h5). The builder, the
calibration, the run loop, the study's labels and the scene's checks call the front of the model they
hold and never ask which one it is. A model of one's own adds a ``StoneFront`` subclass and calls
``register_front`` (its C++ part registered with ``register_stone_model``).
"""
from __future__ import annotations

import math
from typing import Dict, List, Optional, Tuple

import numpy as np

from . import _core
from . import polygon_output as _poly
from .schema import _fmt


class StoneFront:
    """A stone model's front. The defaults are those of stones that are circles of their diameter
    (discs): no shapes of their own, the rolling resistance available, the paper's lookup table and the
    outline packer usable."""

    name = "disc"
    dimensions = 2  # 3: stones that also move across the flume's width (DEMParams.width = flume.width;
                    # run.h5's output_3d.py series)
    lookup_table = True  # the paper's porosity lookup table (numerics.porosity_method = 'lookup') maps them
    outline_packer = True  # outline_packing.py places them (own outlines, zones, sieve curves)

    def label(self, stones) -> str:
        """The model in words for tables: 'discs' or 'discs, mu_r = 0.5'."""
        mu_r = getattr(stones, "rolling_friction", 0.0)
        return f"{self.name}s, mu_r = {mu_r:g}" if mu_r > 0 else f"{self.name}s"

    def check(self, stones, prefix: str) -> None:
        """ValueError for the scene's stone options this model cannot honour (stones: scene.Stones)."""

    def spec_options(self, stones, spec) -> None:
        """The model's options on the packing generator's WeirSpec (its shape is set by the caller)."""

    def draw_shapes(self, stones, diameters, seed: int):
        """The shapes of stones of these (nominal) diameters [m] drawn from seed; None: none of their own."""
        return None

    def install(self, system, shapes) -> None:
        """Puts the model and the drawn shapes into a DEMSystem made of the stones' centres and radii."""
        if system.shape != self.name:
            system.set_model(self.name)

    def lowest(self, pos, diameters, shapes) -> np.ndarray:
        """Height of each unrotated stone's lowest point [m] at centres pos (n, 2)."""
        return np.asarray(pos, float)[:, 1] - 0.5 * np.asarray(diameters, float)

    def diameters(self, system) -> np.ndarray:
        """The stones' (nominal) diameters [m]."""
        return 2.0 * np.asarray(system.stone_radius, float)

    def tops(self, system) -> np.ndarray:
        """Height of each stone's highest point [m]."""
        return np.asarray(system.stone_pos)[:, 1] + np.asarray(system.stone_radius)

    def outlines(self, system) -> Optional[List[np.ndarray]]:
        """The world outline (v, 2) [m] of every stone for plots; None: draw circles of the radii."""
        return None

    def turn_base(self, system, seed: int, nb: int) -> Optional[np.ndarray]:
        """A random orientation per stone [rad] from seed, the nb base stones turned and set on the bed
        by their lowest point; None for stones whose orientation does not show."""
        return None

    def output_shapes(self, system) -> Optional[Tuple[np.ndarray, np.ndarray]]:
        """What run.h5 keeps of the stones' shapes (polygon_output.py's format); None: nothing."""
        return None


class PolygonFront(StoneFront):
    """Convex polygons of quarried-stone form (polygon.h): shapes drawn from the scene's polygon
    options, no rolling resistance (they resist rolling by their shape), packed by pack_weir only."""

    name = "polygon"
    lookup_table = False
    outline_packer = False

    def label(self, stones) -> str:
        return "polygons"

    def check(self, stones, prefix: str) -> None:
        for key in ("rolling_friction", "rolling_friction_wall"):
            value = getattr(stones, key)
            if value > 0.0:
                raise ValueError(f"{prefix}.{key} = {_fmt(value)} is outside the allowed range [0, 0] "
                                 f"with {prefix}.shape = 'polygon': the rolling resistance is a law for disc stones "
                                 "(polygon stones resist rolling by their shape)")

    @staticmethod
    def options(stones) -> Dict[str, float]:
        return dict(polygon_vertices_min=stones.polygon_vertices_min, polygon_vertices_max=stones.polygon_vertices_max,
                    aspect_ratio=stones.aspect_ratio, radial_jitter=stones.polygon_radial_jitter)

    def spec_options(self, stones, spec) -> None:
        for key, value in self.options(stones).items():
            setattr(spec, key, value)

    def draw_shapes(self, stones, diameters, seed: int):
        o = self.options(stones)
        return _core.random_polygons(np.asarray(diameters, float), seed=int(seed),
                                     vertices_min=o["polygon_vertices_min"], vertices_max=o["polygon_vertices_max"],
                                     aspect_ratio=o["aspect_ratio"], radial_jitter=o["radial_jitter"])

    def install(self, system, shapes) -> None:
        system.set_polygons(*shapes)

    def lowest(self, pos, diameters, shapes) -> np.ndarray:
        vertex, offset = shapes
        pos = np.asarray(pos, float)
        return pos[:, 1] + np.array([vertex[offset[i]:offset[i + 1], 1].min() for i in range(len(pos))])

    def diameters(self, system) -> np.ndarray:
        # the nominal diameter: the equal-area disc's
        return np.array([system.nominal_diameter(i) for i in range(system.n)], float)

    def tops(self, system) -> np.ndarray:
        offset = np.asarray(system.poly_offset)
        w = _poly.world_polygon_vertices(system.poly_vertex, offset, system.stone_pos, system.stone_angle)
        return np.maximum.reduceat(w[:, 1], offset[:-1])

    def outlines(self, system) -> Optional[List[np.ndarray]]:
        return _poly.outlines(np.asarray(system.poly_vertex), np.asarray(system.poly_offset), system.stone_pos,
                              system.stone_angle)

    def turn_base(self, system, seed: int, nb: int) -> Optional[np.ndarray]:
        # a generator of its own, so that the discs' draws stay as they were
        turn = np.random.default_rng([seed, 1]).uniform(0.0, 2.0 * math.pi, system.n)
        offset = np.asarray(system.poly_offset)
        low = np.minimum.reduceat(
            _poly.world_polygon_vertices(system.poly_vertex, offset, np.zeros((system.n, 2)), turn)[:, 1], offset[:-1])
        system.stone_angle[:nb] = turn[:nb]
        system.stone_pos[:nb, 1] = -low[:nb]
        return turn

    def output_shapes(self, system) -> Optional[Tuple[np.ndarray, np.ndarray]]:
        return np.array(system.poly_vertex, float), np.array(system.poly_offset, np.int64)


class SphereFront(StoneFront):
    """3D spheres across the flume's width (sphere_model.h): a scene's weir of them is packed in 3D by
    pack_weir (weir_packing_3d.h) across ``flume.width``, and coupled with eq. (11)'s packing porosity
    n_exp = 0 (their footprint is their volume: the porosity is the true void fraction). Trapezoids of
    uniform sizes only (the outline packer places discs and polygons)."""

    name = "sphere"
    dimensions = 3
    lookup_table = False
    outline_packer = False

    def install(self, system, shapes) -> None:
        """The model set, and explicit stones placed on the flume's centre line across the width."""
        super().install(system, shapes)
        system.stone_y[:] = 0.5 * system.params.width


class ClumpFront(StoneFront):
    """Rigid clumps of 1 to 8 overlapping spheres across the flume's width (clump_model.h): a scene's weir of
    them is packed in 3D by pack_weir (``WeirSpec.shape = 'clump'``: the default mix of library shapes,
    pair_2 / triangle_3 / tetra_4 at 1 : 0.8 : 0.6, turned at random, poured on a lattice of their real
    extent and lightly compacted: clump_packing.cpp) across ``flume.width``, and coupled with n_exp = 0 as
    spheres are (their union's volume in each cell's slab). Trapezoids of uniform sizes only, packed only
    (no explicit stones: they would need shapes drawn for them). Their stable DEM step is about 0.7 of the
    spheres' at the same stiffness: a scene gives a numerics.dem_dt they allow (the DEMSystem refuses one
    too long, naming it). The calibration takes other mixes as an argument (calibration_3d.ClumpMix)."""

    name = "clump"
    dimensions = 3
    lookup_table = False
    outline_packer = False

    def diameters(self, system) -> np.ndarray:
        return np.array([system.nominal_diameter(i) for i in range(system.n)])

    def tops(self, system) -> np.ndarray:
        """Height of each stone's highest point [m]: the highest of its sub-spheres' tops."""
        sph, off = np.asarray(system.clump_sphere), np.asarray(system.clump_offset)
        q = np.asarray(system.stone_quat)
        stone = np.repeat(np.arange(system.n), np.diff(off))
        w, x, y, z = (q[stone, k] for k in range(4))
        # the z row of the rotation matrix of each sub-sphere's stone
        rz = np.c_[2.0 * (x * z - w * y), 2.0 * (y * z + w * x), 1.0 - 2.0 * (x * x + y * y)]
        top = np.asarray(system.stone_pos)[stone, 1] + np.sum(rz * sph[:, :3], axis=1) + sph[:, 3]
        out = np.full(system.n, -np.inf)
        np.maximum.at(out, stone, top)
        return out

    def check(self, stones, prefix: str) -> None:
        if stones.positions:
            raise ValueError(f"{prefix}.positions is not allowed with {prefix}.shape = 'clump' (allowed: empty, the "
                             "weir packed by pack_weir): explicit clump stones would need shapes drawn for them")


_FRONTS: Dict[str, StoneFront] = {}


def register_front(front: StoneFront) -> None:
    """Adds a model's front under its name (the name its C++ model is registered under)."""
    if not front.name or front.name in _FRONTS:
        raise ValueError(f"register_front: a front needs a name not taken (got {front.name!r})")
    _FRONTS[front.name] = front


def front(name: str) -> StoneFront:
    """The front of the stone model `name`; ValueError naming the registered ones."""
    try:
        return _FRONTS[name]
    except KeyError:
        raise ValueError(f"stones.shape = {name!r} is not one of the stone models with a Python front "
                         f"{', '.join(repr(k) for k in _FRONTS)}") from None


def has_front(name: str) -> bool:
    """Whether the stone model `name` has a front."""
    return name in _FRONTS


def front_of(system) -> StoneFront:
    """The front of the model a DEMSystem holds."""
    return front(system.shape)


def stone_diameters(system) -> np.ndarray:
    """(Nominal) diameters [m] of the stones, as their model gives them (2 r for discs)."""
    return front_of(system).diameters(system)


register_front(StoneFront())
register_front(PolygonFront())
register_front(SphereFront())
register_front(ClumpFront())
