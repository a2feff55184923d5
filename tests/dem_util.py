"""What the tests of the stones share: a hash of a DEMSystem's whole state, and the check that a system
restarted from its checkpoint goes on bit for bit."""
from __future__ import annotations

import hashlib

import numpy as np


def state_hash(s) -> str:
    """SHA-256 of every array of s.export_state(), in key order."""
    h = hashlib.sha256()
    for key, a in sorted(s.export_state().items()):
        h.update(key.encode())
        h.update(np.ascontiguousarray(a).tobytes())
    return h.hexdigest()


def restarts_bit_for_bit(make, before: float, after: float, empty: bool = False):
    """make() advanced `before` seconds and checkpointed, then `after` more; a second make() given the
    checkpoint advanced `after` seconds must hold the same arrays to the bit. empty: the second system is
    one of no stones with the first's parameters, as a resumed run builds its stones (builder.checkpoint_stones),
    and the checkpoint makes them. Returns (first, second, checkpoint)."""
    from vofdem import _core

    s = make()
    s.advance(before)
    checkpoint = s.export_state()
    s.advance(after)
    r = _core.DEMSystem(s.params, 0) if empty else make()
    r.import_state(checkpoint)
    r.advance(after)
    for key, value in s.export_state().items():
        np.testing.assert_array_equal(r.export_state()[key], value, err_msg=key)
    return s, r, checkpoint
