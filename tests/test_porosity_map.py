"""Porosity from stone discs (seed section 2.4, eq. 11): exact areas, the lookup table, the mapper."""
import gc
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import vofdem
from vofdem import stone_cell_area


def reference_area(cx, cz, r, x0, x1, z0, z1, n=200_000):
    """Slow obvious reference: midpoint rule on the length of each vertical chord inside [z0, z1]."""
    a, b = max(x0, cx - r), min(x1, cx + r)
    if b <= a:
        return 0.0
    h = (b - a) / n
    x = a + h * (np.arange(n) + 0.5)
    s = np.sqrt(np.maximum(0.0, r * r - (x - cx) ** 2))
    return float(h * np.maximum(0.0, np.minimum(z1, cz + s) - np.maximum(z0, cz - s)).sum())


def cell_areas(grid, x, z, r):
    """Areas of one disc in every cell of `grid` with the closed form, shape (nz, nx)."""
    xf = grid.x0 + grid.dx * np.arange(grid.nx + 1)
    zf = np.asarray(grid.z_faces)
    return stone_cell_area(x, z, r, xf[None, :-1], xf[None, 1:], zf[:-1, None], zf[1:, None])


def mapper(grid, r_min, r_max, method="exact", m=8, **kw):
    return vofdem.make_porosity_mapper(grid, r_min, r_max, method=method, m=m, **kw)


def paper_grid(nx=40, length=1.0, height=0.3):
    # 2.5 cm x 1.0 cm cells, 0.5 cm rows up to 2 cm above the bed
    return vofdem.Grid2D.graded(nx=nx, length_x=length, height_z=height, dz=0.01, dz_bed=0.005, z_bed_top=0.02)


# ---------------------------------------------------------------- disc-rectangle area
def test_hand_computed_areas():
    r = 0.024
    full = math.pi * r * r
    assert stone_cell_area(0.5, 0.5, r, 0, 1, 0, 1) == pytest.approx(full, rel=1e-15)
    assert stone_cell_area(0.0, 0.0, r, 0, 1, 0, 1) == pytest.approx(full / 4, rel=1e-15)
    assert stone_cell_area(0.0, 0.5, r, 0, 1, 0, 1) == pytest.approx(full / 2, rel=1e-15)
    # a rectangle inside the disc is covered entirely
    assert stone_cell_area(0.0, 0.0, r, -0.01, 0.005, -0.002, 0.003) == pytest.approx(0.015 * 0.005, rel=1e-14)
    # a disc far away, or merely touching
    assert stone_cell_area(0.0, 0.0, r, 0.03, 0.04, 0, 1) == 0.0
    assert stone_cell_area(0.0, 0.0, r, r, 0.04, -1, 1) == 0.0
    # circular segment cut at distance r/2 from the centre: r^2 (theta - sin theta) / 2, theta = 2 pi / 3
    theta = 2 * math.pi / 3
    assert stone_cell_area(0.0, 0.0, r, r / 2, 1, -1, 1) == pytest.approx(r * r * (theta - math.sin(theta)) / 2,
                                                                         rel=1e-13)


@pytest.mark.parametrize(
    "cx, cz",
    [(0.0125, 0.005), (0.001, 0.0), (-0.02, 0.013), (0.03, -0.01), (0.0125, 0.029), (0.05, 0.05)],
)
def test_closed_form_matches_the_slow_reference_on_a_papers_cell(cx, cz):
    # a 4.8 cm stone against a 2.5 cm x 1.0 cm cell [0, 0.025] x [0, 0.01]: every relative position
    r = 0.024
    got = stone_cell_area(cx, cz, r, 0.0, 0.025, 0.0, 0.01)
    assert got == pytest.approx(reference_area(cx, cz, r, 0.0, 0.025, 0.0, 0.01), abs=1e-6 * r * r)


@settings(max_examples=60, deadline=None)
@given(
    cx=st.floats(-0.05, 0.05), cz=st.floats(-0.05, 0.05), r=st.floats(1e-3, 0.05),
    x0=st.floats(-0.04, 0.04), w=st.floats(1e-4, 0.06), z0=st.floats(-0.04, 0.04), h=st.floats(1e-4, 0.06),
)
def test_closed_form_matches_the_slow_reference_everywhere(cx, cz, r, x0, w, z0, h):
    got = stone_cell_area(cx, cz, r, x0, x0 + w, z0, z0 + h)
    rect = ((x0 + w) - x0) * ((z0 + h) - z0)  # the rectangle as represented
    assert 0.0 <= got <= rect
    assert got <= math.pi * r * r * (1 + 1e-14)
    assert got == pytest.approx(reference_area(cx, cz, r, x0, x0 + w, z0, z0 + h), abs=2e-6 * r * r)


def test_area_refuses_bad_input():
    with pytest.raises(ValueError, match=r"r = -0.01 is outside the allowed range \[0, inf\)"):
        stone_cell_area(0, 0, -0.01, 0, 1, 0, 1)
    with pytest.raises(ValueError, match=r"x1 = -1 is outside the allowed range \[0, inf\]"):
        stone_cell_area(0, 0, 0.01, 0, -1, 0, 1)
    with pytest.raises(ValueError, match=r"cz = nan is outside"):
        stone_cell_area(0, float("nan"), 0.01, 0, 1, 0, 1)


# ---------------------------------------------------------------- the mapper, exact method
def test_disc_inside_one_cell():
    g = vofdem.Grid2D.uniform(4, 4, 0.4, 0.4)
    mp = mapper(g, 0.02, 0.02)
    mp.map([0.15], [0.25], [0.02])
    area = math.pi * 0.02**2
    expected = np.zeros((4, 4))
    expected[2, 1] = area
    np.testing.assert_allclose(mp.cell_solid_area, expected, rtol=1e-14, atol=0)
    assert mp.cell_porosity[2, 1] == pytest.approx(1 - 0.59 * area / 0.01, rel=1e-14)
    assert mp.cell_porosity.sum() - mp.cell_porosity[2, 1] == 15.0
    assert list(mp.stone_cell_offsets) == [0, 1]
    assert list(mp.stone_cell_index) == [1 + 4 * 2]


def test_disc_over_many_cells_sums_to_pi_r_squared():
    g = vofdem.Grid2D.uniform(60, 50, 0.3, 0.25)  # 5 mm cells: a 4.8 cm stone covers ~90 of them
    r = 0.024
    mp = mapper(g, r, r, max_discs=2)
    mp.map([0.1234567], [0.1111111], [r])
    assert mp.stone_cell_area.size > 80
    assert mp.stone_cell_area.sum() == pytest.approx(math.pi * r * r, rel=1e-12, abs=0)
    assert mp.cell_solid_area.sum() == pytest.approx(math.pi * r * r, rel=1e-12, abs=0)
    # every (disc, cell) area is the closed form for that cell
    ref = cell_areas(g, 0.1234567, 0.1111111, r).ravel()
    np.testing.assert_allclose(mp.stone_cell_area, ref[mp.stone_cell_index], rtol=1e-12, atol=1e-18)


def test_symmetric_placements_give_symmetric_areas():
    g = vofdem.Grid2D.uniform(8, 8, 0.2, 0.08)  # 2.5 cm x 1 cm cells
    mp = mapper(g, 0.024, 0.024)
    # a centre on a grid node: the four quadrants are mirror images
    mp.map([0.1], [0.04], [0.024])
    a = np.array(mp.cell_solid_area)
    np.testing.assert_allclose(a, a[::-1, :], rtol=1e-12, atol=1e-18)
    np.testing.assert_allclose(a, a[:, ::-1], rtol=1e-12, atol=1e-18)
    assert a.sum() == pytest.approx(math.pi * 0.024**2, rel=1e-12)
    # a centre at a cell centre of a symmetric grid
    mp.map([0.0875], [0.035], [0.024])
    b = np.array(mp.cell_solid_area)
    np.testing.assert_allclose(b[:7, :7], b[:7, :7][::-1, ::-1], rtol=1e-12, atol=1e-18)


def test_overlapping_discs_are_capped_at_the_cell_area():
    g = vofdem.Grid2D.uniform(8, 8, 0.2, 0.08)
    mp = mapper(g, 0.024, 0.024)
    mp.map([0.1, 0.1, 0.1], [0.04, 0.04, 0.041], [0.024] * 3)
    ac = g.dx * np.diff(np.asarray(g.z_faces))[:, None]
    assert np.all(mp.cell_solid_area <= ac)
    # the cells around the centre are fully covered three times over: A_s = A_c, n = n_exp exactly
    assert mp.cell_solid_area[4, 4] == ac[4, 0]
    assert mp.cell_porosity[4, 4] == 0.41
    # the per-disc lists keep the uncapped areas
    off = mp.stone_cell_offsets
    for j in range(3):
        assert mp.stone_cell_area[off[j]:off[j + 1]].sum() == pytest.approx(math.pi * 0.024**2, rel=1e-12)


def test_porosity_stays_in_n_exp_1_for_a_dense_random_packing():
    g = paper_grid()
    rng = np.random.default_rng(7)
    n = 500
    x, z, r = rng.uniform(0, 1, n), rng.uniform(-0.02, 0.3, n), rng.uniform(0.0216, 0.0264, n)
    for method in ("exact", "lookup"):
        mp = mapper(g, 0.0216, 0.0264, method=method, n_exp=0.41, max_discs=n)
        mp.map(x, z, r)
        assert mp.cell_porosity.min() == 0.41
        assert mp.cell_porosity.max() == 1.0
        assert np.all((mp.cell_porosity >= 0.41) & (mp.cell_porosity <= 1.0))


def test_non_uniform_rows_of_the_papers_grid():
    g = paper_grid()
    rng = np.random.default_rng(3)
    x, z, r = rng.uniform(0, 1, 40), rng.uniform(0, 0.06, 40), rng.uniform(0.0216, 0.0264, 40)
    mp = mapper(g, 0.0216, 0.0264, max_discs=40)
    mp.map(x, z, r)
    total = sum(cell_areas(g, *d) for d in zip(x, z, r))
    ac = g.dx * np.diff(np.asarray(g.z_faces))[:, None]
    np.testing.assert_allclose(mp.cell_solid_area, np.minimum(total, ac), rtol=1e-12, atol=1e-18)
    np.testing.assert_allclose(mp.cell_porosity, 1 - 0.59 * np.minimum(total, ac) / ac, rtol=1e-12)


def test_active_mask_skips_discs():
    g = paper_grid()
    mp = mapper(g, 0.024, 0.024, max_discs=3)
    mp.map([0.2, 0.5, 0.8], [0.1, 0.1, 0.1], [0.024] * 3, active=np.array([1, 0, 1], dtype=np.uint8))
    off = mp.stone_cell_offsets
    assert off[1] == off[2]  # the inactive disc covers nothing
    assert mp.cell_solid_area[:, 18:22].sum() == 0.0
    assert mp.cell_solid_area.sum() == pytest.approx(2 * math.pi * 0.024**2, rel=1e-12)


def test_map_is_deterministic_and_allocates_nothing():
    g = paper_grid()
    rng = np.random.default_rng(11)
    x, z, r = rng.uniform(0, 1, 200), rng.uniform(0, 0.3, 200), rng.uniform(0.0216, 0.0264, 200)
    for method in ("exact", "lookup"):
        mp = mapper(g, 0.0216, 0.0264, method=method, max_discs=200)
        por = mp.cell_porosity
        mp.map(x, z, r)
        first = np.array(por), np.array(mp.stone_cell_area)
        mp.map(x, z, r)
        # the same memory, the same bits
        assert np.shares_memory(por, mp.cell_porosity)
        assert np.array_equal(first[0], mp.cell_porosity) and np.array_equal(first[1], mp.stone_cell_area)
        assert list(mp.profile.names) == ["porosity_map"] and mp.profile.calls[0] == 2


def test_views_keep_the_mapper_alive():
    g = paper_grid()
    mp = mapper(g, 0.024, 0.024)
    mp.map([0.5], [0.1], [0.024])
    por = mp.cell_porosity
    area = mp.stone_cell_area
    expected = por.copy(), area.copy()
    del mp
    gc.collect()
    assert np.array_equal(por, expected[0]) and np.array_equal(area, expected[1])
    assert por.shape == (g.nz, g.nx)


def test_mapper_refuses_bad_input_and_keeps_the_last_map():
    g = paper_grid()
    mp = mapper(g, 0.0216, 0.0264, max_discs=2)
    mp.map([0.5], [0.1], [0.024])
    before = np.array(mp.cell_porosity)
    with pytest.raises(ValueError, match=r"disc_r = 0.03 is outside the allowed range \[0.0216, 0.0264\]"):
        mp.map([0.5], [0.1], [0.03])
    with pytest.raises(ValueError, match=r"disc_x = nan is outside"):
        mp.map([float("nan")], [0.1], [0.024])
    with pytest.raises(ValueError, match=r"ndisc = 3 is outside the allowed range \[0, 2\]"):
        mp.map([0.1, 0.2, 0.3], [0.1] * 3, [0.024] * 3)
    with pytest.raises(ValueError, match="same length"):
        mp.map([0.1, 0.2], [0.1], [0.024])
    assert np.array_equal(before, mp.cell_porosity)
    with pytest.raises(ValueError, match=r"n_exp = 1.5 is outside the allowed range \[0, 1\]"):
        mapper(g, 0.02, 0.03, n_exp=1.5)
    with pytest.raises(ValueError, match=r"r_max = 0.01 is outside"):
        mapper(g, 0.02, 0.01)
    with pytest.raises(ValueError, match=r"m = 0 is outside the allowed range \[1, 256\]"):
        mapper(g, 0.02, 0.03, method="lookup", m=0)
    with pytest.raises(ValueError, match="method = 'fast' is outside"):
        mapper(g, 0.02, 0.03, method="fast")
    with pytest.raises(ValueError, match=r"disc_d = -0.1 is outside the allowed range \(0, inf\)"):
        vofdem.porosity_from_discs(g, [0.1], [0.1], [-0.1])


@settings(max_examples=40, deadline=None)
@given(
    nx=st.integers(1, 12), dx=st.floats(0.003, 0.05), x0=st.floats(-0.1, 0.1),
    dz=st.lists(st.floats(0.002, 0.04), min_size=1, max_size=12),
    discs=st.lists(st.tuples(st.floats(-0.2, 0.8), st.floats(-0.2, 0.5), st.floats(0.005, 0.06)),
                   min_size=1, max_size=6),
    method=st.sampled_from(["exact", "lookup"]),
)
def test_areas_sum_to_the_disc_part_inside_the_grid(nx, dx, x0, dz, discs, method):
    zf = np.concatenate([[0.0], np.cumsum(dz)])
    g = vofdem.Grid2D(nx=nx, dx=dx, z_faces=list(zf), x0=x0)
    x, z, r = (np.array(v) for v in zip(*discs))
    m = 4
    if method == "lookup":
        # one radius (no interpolation): the table holds the exact areas of the disc moved to its
        # sub-area centre, so the sum is the part inside the grid of the moved disc
        r[:] = r[0]
    mp = mapper(g, r.min(), r.max(), method=method, m=m, max_discs=len(discs))
    mp.map(x, z, r)
    cx, cz = x.copy(), z.copy()
    if method == "lookup":
        i, k = np.floor((x - x0) / dx), np.searchsorted(zf, z, side="right") - 1
        inner = (i >= 0) & (i < nx) & (k >= 0) & (k < len(dz))
        kk = np.clip(k, 0, len(dz) - 1)
        a = np.minimum(m - 1, np.floor(((x - x0) / dx - i) * m))
        b = np.minimum(m - 1, np.floor((z - zf[kk]) / np.diff(zf)[kk] * m))
        cx = np.where(inner, x0 + dx * (i + (a + 0.5) / m), x)
        cz = np.where(inner, zf[kk] + np.diff(zf)[kk] * (b + 0.5) / m, z)
    off = np.asarray(mp.stone_cell_offsets)
    area = np.asarray(mp.stone_cell_area)
    inside = stone_cell_area(cx, cz, r, x0, x0 + nx * dx, 0.0, zf[-1])
    for j in range(len(discs)):
        got = area[off[j]:off[j + 1]].sum()
        assert got == pytest.approx(inside[j], rel=1e-11, abs=1e-18)
    assert np.all(mp.cell_porosity >= 0.41) and np.all(mp.cell_porosity <= 1.0)
    # the cell totals are the capped sums of the lists
    total = np.bincount(np.asarray(mp.stone_cell_index), weights=area, minlength=g.ncell).reshape(g.nz, g.nx)
    ac = dx * np.diff(zf)[:, None]
    np.testing.assert_allclose(mp.cell_solid_area, np.minimum(total, ac), rtol=1e-12, atol=1e-18)


# ---------------------------------------------------------------- the lookup table
def subarea_centres(g, m, rng, count):
    """Disc centres placed exactly at sub-area centres of random cells (where the table is exact)."""
    zf = np.asarray(g.z_faces)
    i = rng.integers(0, g.nx, count)
    k = rng.integers(0, g.nz, count)
    a = rng.integers(0, m, count)
    b = rng.integers(0, m, count)
    x = g.x0 + g.dx * (i + (a + 0.5) / m)
    z = zf[k] + (zf[k + 1] - zf[k]) * (b + 0.5) / m
    return x, z


@pytest.mark.parametrize("m", [1, 3, 8])
def test_lookup_is_exact_at_subarea_centres_and_radius_nodes(m):
    g = paper_grid(nx=20, length=0.5, height=0.12)
    rng = np.random.default_rng(m)
    x, z = subarea_centres(g, m, rng, 60)
    # radii on the nodes r_min + q dr of the tables
    r = 0.0216 + 0.0008 * rng.integers(0, 7, 60)
    ex = mapper(g, 0.0216, 0.0264, max_discs=60)
    lk = mapper(g, 0.0216, 0.0264, method="lookup", m=m, dr=0.0008, max_discs=60)
    ex.map(x, z, r)
    lk.map(x, z, r)
    np.testing.assert_allclose(lk.cell_solid_area, ex.cell_solid_area, rtol=0, atol=1e-15)
    assert lk.table_count == len(set(lk.row_class)) * 7


def test_rows_with_equal_neighbourhoods_share_one_table():
    g = paper_grid(nx=8, length=0.2, height=0.3)
    lk = mapper(g, 0.024, 0.024, method="lookup", m=4)
    rc = list(lk.row_class)
    # the 0.5 cm bed rows and the rows near the bed, the top and the transition differ; the middle is one class
    assert len(set(rc)) < 15
    assert len(set(rc[10:-5])) == 1
    assert lk.table_count == len(set(rc)) and lk.table_bytes > 0
    assert mapper(g, 0.024, 0.024).table_count == 0  # the exact method builds no table


def lookup_error(g, x, z, r, m, dr=5e-4):
    ex = mapper(g, r.min(), r.max(), max_discs=x.size)
    lk = mapper(g, r.min(), r.max(), method="lookup", m=m, dr=dr, max_discs=x.size)
    ex.map(x, z, r)
    lk.map(x, z, r)
    return np.abs(np.asarray(lk.cell_porosity) - ex.cell_porosity).max()


def test_lookup_error_shrinks_as_m_grows():
    g = paper_grid()
    rng = np.random.default_rng(5)
    n = 150
    x, z = rng.uniform(0, 1, n), rng.uniform(0, 0.25, n)
    for r in (np.full(n, 0.024), rng.uniform(0.0216, 0.0264, n)):
        errors = [lookup_error(g, x, z, r, m) for m in (2, 4, 8, 16)]
        assert all(b < a for a, b in zip(errors, errors[1:])), errors
        # snapping the centre by half a sub-area is a first-order error: 8x finer, at least 4x smaller
        assert errors[-1] < errors[0] / 4, errors


def test_lookup_falls_back_to_exact_for_centres_outside_the_grid():
    g = paper_grid()
    x, z, r = np.array([-0.01, 1.005, 0.5]), np.array([0.1, 0.2, -0.015]), np.full(3, 0.024)
    ex = mapper(g, 0.024, 0.024, max_discs=3)
    lk = mapper(g, 0.024, 0.024, method="lookup", m=4, max_discs=3)
    ex.map(x, z, r)
    lk.map(x, z, r)
    np.testing.assert_array_equal(lk.cell_solid_area, ex.cell_solid_area)


def test_porosity_from_discs_returns_a_field():
    g = paper_grid()
    x, z, d = [0.3, 0.33, 0.6], [0.024, 0.07, 0.05], [0.048, 0.05, 0.045]
    n = vofdem.porosity_from_discs(g, x, z, d)
    assert n.shape == (g.nz, g.nx)
    n8 = vofdem.porosity_from_discs(g, x, z, d, method="lookup", m=8)
    assert np.abs(n8 - n).max() < 0.15
    assert np.abs(n8 - n).max() > 0.0
    assert vofdem.porosity_from_discs(g, [], [], []).min() == 1.0


@pytest.mark.parametrize("method", ["exact", "lookup"])
def test_hexagonal_packing_gives_the_packing_fraction(method):
    # touching discs on a hexagonal lattice cover pi / (2 sqrt 3) = 0.9069 of the plane; on a grid of
    # whole lattice periods (discs across the edges included) the area-weighted mean porosity is
    # exactly 1 - (1 - n_exp) 0.9069 with the exact areas
    d = 0.048
    px, pz = d, math.sqrt(3) * d
    g = vofdem.Grid2D(nx=48, dx=6 * px / 48, z_faces=list(np.linspace(0.0, 3 * pz, 31)), x0=0.0)
    xs, zs = [], []
    for row in range(-1, 7):
        for col in range(-1, 8):
            xs.append(col * px + (0.5 * px if row % 2 else 0.0))
            zs.append(row * pz / 2)
    x, z = np.array(xs), np.array(zs)
    r = np.full(x.size, d / 2)
    mp = mapper(g, d / 2, d / 2, method=method, m=16, max_discs=x.size)
    mp.map(x, z, r)
    ac = g.dx * np.diff(np.asarray(g.z_faces))[:, None]
    mean_n = float((mp.cell_porosity * ac).sum() / (ac.sum() * g.nx))
    expected = 1 - 0.59 * math.pi / (2 * math.sqrt(3))
    # exact: round-off only. lookup: each disc moved by up to half a sub-area, which shifts area across
    # the grid's edges; with m = 16 the mean stays within 1e-3
    tol = 1e-12 if method == "exact" else 1e-3
    assert mean_n == pytest.approx(expected, abs=tol)
