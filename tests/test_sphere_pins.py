"""Pinned final states of 3D sphere runs (sphere_model.h, sphere_contact.h): a speed-up of the contact loops
must keep every bit. The pins were taken before the sphere kernels were compiled into the loops (the
out-of-line sphere_*_contact_unchecked calls); a change of the law or of its order of operations changes
them, and must then say so."""

import os
import sys

import numpy as np

import vofdem

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "benchmarks"))
import dem_settle3d_peer as settle3d  # noqa: E402
from test_dem import state_hash  # noqa: E402  (sha256 over the exported state's keys and arrays)
from test_spheres import heap  # noqa: E402


def test_a_heap_between_the_side_walls_keeps_its_pinned_state():
    s = heap()
    s.advance(0.4)
    assert s.wall_contact_count > 0 and s.contact_count > 0  # both loops ran
    assert state_hash(s) == PINS["heap"]


def test_a_heap_with_rolling_resistance_keeps_its_pinned_state():
    s = heap(seed=3)
    p = s.params
    p.rolling_friction_stone = p.rolling_friction_wall = 0.2
    s.params = p
    s.advance(0.3)
    assert np.abs(s.export_state()["sphere_contact_rolling"]).max() > 0.0  # the rolling springs worked
    assert state_hash(s) == PINS["rolling"]


def test_the_settling_of_the_peer_benchmark_keeps_its_pinned_state():
    s = settle3d.spheres(100, 5, False)  # 100 spheres, 5 across, the 3D list
    s.advance(0.2)
    assert s.contact_count > 50
    assert state_hash(s) == PINS["settle"]


# taken with the out-of-line kernels (the same bits since); taken again when the energy account booked the
# springs of contacts that open and the slip from the work done (sphere_kernels.h): only the account's
# `dissipated` (scalars[3]) changed - with it zeroed the hashes were the same before and after
PINS = {
    "heap": "8a9057770e4f971619c5f2e03ea38ddba0964cd055748ed002baf56077fc5aa9",
    "rolling": "a32b0db79e0869230574c6bf0276bb115d03a4d4a756f25ae6ee41add778ea66",
    "settle": "ae86754d07324b3b83e5395fc5684f96506a52419d8ed4d6fc3599179ded2a32",
}
