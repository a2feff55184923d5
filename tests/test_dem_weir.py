"""The weir packing generator: outline, rest, porosity, reproducibility."""
import numpy as np
import pytest

import vofdem

# on several processes (pytest-xdist, --dist loadgroup) the tests of the packed weir run on one: it is packed once
PACKED_WEIR = pytest.mark.xdist_group("packed_weir")


def packed(**keys):
    """(DEMSystem, WeirPackingReport, WeirSpec) of a WeirSpec with these keys set, the rest its defaults and
    the Maeno weir's stones (the core has no stone default)."""
    spec = vofdem.WeirSpec()
    spec.d_mean, spec.density = 0.048, 2650.0
    for k, v in keys.items():
        setattr(spec, k, v)
    return (*vofdem.pack_weir(spec), spec)


@pytest.fixture(scope="module")
def weir():
    return packed(height=0.25, crest=0.20, slope_up_deg=27, slope_down_deg=27, x_toe=1.0, d_mean=0.048, d_spread=0.1,
                  density=2650.0, seed=0)


@PACKED_WEIR
def test_weir_matches_the_trapezoid_within_one_diameter(weir):
    s, report, spec = weir
    assert report.n_stones == s.n and report.n_fixed == int(s.stone_fixed.sum())
    assert spec.x_end() == pytest.approx(1.0 + 2 * 0.25 / np.tan(np.radians(27)) + 0.2)
    assert spec.top(spec.x_toe + 0.1) == pytest.approx(0.1 * np.tan(np.radians(27)))
    # bottom layer fixed on the bed
    assert np.allclose(s.stone_pos[s.stone_fixed == 1, 1], s.stone_radius[s.stone_fixed == 1])
    assert report.outline_error == pytest.approx(vofdem.weir_outline_error(s, spec))
    # one (mean) stone diameter; seeds 0-7 give 3.6-4.6 cm
    assert report.outline_error < spec.d_mean
    free = s.stone_fixed == 0
    assert s.stone_pos[free, 1].max() < spec.z_bed + spec.height + spec.d_mean / 2


@PACKED_WEIR
def test_weir_is_at_rest_and_stays_at_rest_for_ten_seconds(weir):
    s, report, _ = weir
    assert report.max_speed < 1e-3
    speed = np.hypot(*s.stone_vel.T)
    assert speed.max() < 1e-3
    before = s.stone_pos.copy()
    s.advance(10.0)
    assert np.hypot(*s.stone_vel.T).max() < 1e-3
    assert np.abs(s.stone_pos - before).max() < 2e-3
    assert s.removed_count == 0


@pytest.mark.parametrize("seed", [0, 2, 3, 6, 9])
def test_no_free_stone_lies_on_the_bed_beyond_the_fixed_layer(seed):
    """The free stones stand on the fixed layer or on each other: none is laid on the bed at a toe's tip,
    where it would rest against one fixed stone and wash away in the first flow (these seeds laid one
    at the downstream tip before the hand-laying kept above the fixed layer)."""
    s, _, spec = packed(height=0.25, crest=0.20, slope_up_deg=27, slope_down_deg=27, x_toe=0.6, d_mean=0.048,
                        d_spread=0.1, density=2650.0, seed=seed)
    fixed = s.stone_fixed == 1
    x_fixed = s.stone_pos[fixed, 0]
    on_bed = (s.stone_fixed == 0) & (s.stone_pos[:, 1] < spec.z_bed + 0.75 * spec.d_mean)
    outside = on_bed & ((s.stone_pos[:, 0] > x_fixed.max()) | (s.stone_pos[:, 0] < x_fixed.min()))
    assert not outside.any(), s.stone_pos[outside]


@PACKED_WEIR
def test_weir_porosity_is_reported(weir):
    _, report, spec = weir
    # 2D area porosity of discs in the trapezoid (the paper's 3D value is 0.41)
    assert 0.1 < report.porosity < 0.45
    assert report.porosity == pytest.approx(vofdem.weir_porosity(weir[0], spec), abs=0.01)


def test_weir_is_reproducible_from_its_seed():
    a, ra, _ = packed(seed=3, height=0.15, crest=0.1, d_mean=0.048, d_spread=0.1)
    b, rb, _ = packed(seed=3, height=0.15, crest=0.1, d_mean=0.048, d_spread=0.1)
    c, _, _ = packed(seed=4, height=0.15, crest=0.1, d_mean=0.048, d_spread=0.1)
    assert ra.n_stones == rb.n_stones
    assert np.array_equal(a.stone_pos, b.stone_pos) and np.array_equal(a.stone_radius, b.stone_radius)
    assert a.n != c.n or not np.array_equal(a.stone_radius, c.stone_radius)
    d = a.stone_radius * 2
    assert 0.9 * 0.048 <= d.min() and d.max() <= 1.1 * 0.048


def test_weir_rejects_bad_geometry():
    with pytest.raises(ValueError, match="slope_down_deg"):
        packed(slope_down_deg=95)
    with pytest.raises(ValueError, match="height"):
        packed(height=0.05)
