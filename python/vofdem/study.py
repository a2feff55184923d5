"""The prediction study's pieces: what an ensemble says about each failure event, how far a numerical
setting moves the ensemble's medians from a reference and what it costs, and the knob settings.

**Event discharges with censoring.** Per member and event (first removal, stage 1, 2, 3; see
`fragility.EVENTS`) the discharge at which it happened, or, where it never did, the discharge at the
run's end (right-censored). The ensemble's median and 16-84 % band are the Kaplan-Meier quantiles
(`fragility.empirical_quantile`): the smallest discharge by which the censored empirical distribution
reaches 0.5 (0.16, 0.84). Where the censored members keep it below that level, the quantile is
unknown ("not reached": it lies above the runs' last discharge), never a median of the members that
failed alone. The lognormal fit of `fragility` is reported beside it.

**Shift of a median.** A setting run over the same seeds (packings) as the reference: the shift is
``m_setting - m_reference`` of the Kaplan-Meier medians [l/s]. Its uncertainty: a paired bootstrap
over the seeds both ran (`n_boot` resamples of the seeds with replacement, numpy's default generator
seeded; each resample takes a seed's member from both), the 16-84 % interval of the resampled shifts;
a resample in which either median is not reached is left out (its share is reported). The packings'
own spread, against which a shift is judged, is the reference's 16-84 % band.

**Knob settings** (`knob_settings`): one knob at a time from the reference scene, each a set of scene
keys (docs/verdict.md): the grid twice as coarse or as fine, the ramp's duration, the fluid's CFL, the
porosity by the paper's lookup table instead of exact areas (its sub-areas per side m: 'lookup4',
'lookup' (m = 8), 'lookup16'), the DEM steps per contact at the same contact stiffness (dem_dt and
dem_contact_steps together), and the spin-up's length.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

from .builder import GRAVITY, WATER_DENSITY
from .fragility import BAND, EVENTS, empirical_quantile, event_fragility
from .stone_models import front


def stone_model(scene) -> str:
    """The stone model in words: 'discs', 'discs, mu_r = 0.5', or the shape's name."""
    st = scene.stones
    return front(getattr(st, "shape", "disc")).label(st)


def coupling(scene) -> str:
    """The coupling in words: the paper's (sphere drag, eq. 11 with n_exp) or the consistent one; for 3D
    stones, whose porosity is their true void fraction whatever the mapping key, by their drag alone."""
    st = scene.stones
    if st.shape in ("sphere", "clump"):
        return {"sphere": "paper's drag", "bed": "consistent"}.get(st.drag_model, f"{st.drag_model} drag") + \
            ", true void fraction"
    if st.drag_model == "sphere" and st.porosity_mapping == "paper":
        return "paper's"
    if st.drag_model == "bed" and st.porosity_mapping == "bulk":
        return "consistent"
    return f"{st.drag_model} drag, {st.porosity_mapping} mapping"


def shown_path(path, root, tail: int = 3) -> str:
    """`path` as a committed page may show it: relative to the project's `root` when inside it, else its
    last `tail` parts without the anchor (never a machine's absolute path)."""
    full = Path(path).resolve()
    try:
        return str(full.relative_to(Path(root).resolve()))
    except ValueError:
        return str(Path(*full.parts[1:][-tail:]))


def parse_numbers(spec: str, name: str, low: float, high: float, cast=float, what: str = "",
                  allow_empty: bool = False) -> list:
    """A study script's comma list: '16,24' -> [16.0, 24.0] (cast each); ValueError naming the option `name`,
    the bad part, what a value is (`what`, e.g. 'a rolling friction') and the range [low, high]; an empty
    list refused unless allow_empty."""
    vals = []
    for part in filter(None, (p.strip() for p in spec.split(","))):
        try:
            v = cast(part)
        except ValueError:
            v = math.nan
        if not low <= v <= high:
            raise ValueError(f"{name}: {part!r} is {f'not {what} in' if what else 'outside'} the allowed range "
                             f"[{low:g}, {high:g}]")
        vals.append(v)
    if not vals and not allow_empty:
        raise ValueError(f"{name}: empty (give at least one value in [{low:g}, {high:g}])")
    return vals


def number_or_dash(v, fmt: str = "{:.2f}") -> str:
    """v formatted by `fmt` for a results table, '-' where it is None or nan (not measured)."""
    return "-" if v is None or (isinstance(v, float) and math.isnan(v)) else fmt.format(v)


def sphere_volume(diameter) -> np.ndarray:
    """pi d^3 / 6 [m^3] of nominal diameters d [m]: a stone's own volume, since every stone model's nominal
    diameter is its volume-equivalent sphere's (the diameters run.h5 keeps)."""
    return math.pi * np.asarray(diameter, float) ** 3 / 6.0


def submerged_weight(volume, density) -> np.ndarray:
    """(rho_s - rho_w) g V [N]: the weight in still water of stones of volume V [m^3] and density rho_s
    [kg/m^3] (rho_w and g: the Medium's defaults, builder.WATER_DENSITY and builder.GRAVITY)."""
    return (np.asarray(density, float) - WATER_DENSITY) * GRAVITY * np.asarray(volume, float)


def write_page(out, lines: Sequence[str]) -> Path:
    """Writes a results page (Markdown lines) to the path `out`, making its folder, prints it and returns
    `out`: the last step of each study script."""
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text("\n".join(lines), encoding="utf-8")
    print("\n".join(lines))
    return out


# ---------------------------------------------------------------------------- statistics
def event_arrays(members, event: str) -> Tuple[np.ndarray, np.ndarray]:
    """(q [l/s], observed) of one event over completed members: the event's discharge where it
    happened, else the discharge at the run's end (right-censored)."""
    col = EVENTS[event][0]
    qe = members[col].astype(float).to_numpy()
    observed = np.isfinite(qe)
    return np.where(observed, qe, members["last_discharge_lps"].astype(float).to_numpy()), observed


def km_quantiles(q, observed, probs=(BAND[0], 0.5, BAND[1])) -> List[Optional[float]]:
    """Kaplan-Meier quantiles [l/s] (None: not reached)."""
    if len(q) == 0:
        return [None] * len(probs)
    return [empirical_quantile(q, observed, p) for p in probs]


def event_summary(members, event: str) -> Dict[str, Any]:
    """One event over the completed members of an outcome table: counts, Kaplan-Meier median and
    16-84 % band, the lognormal fit's median and band, the censoring discharge."""
    done = members[members["status"] == "completed"]
    q, obs = event_arrays(done, event)
    lo, med, hi = km_quantiles(q, obs)
    first = done["first_discharge_lps"].astype(float) if "first_discharge_lps" in done else None
    ef = event_fragility(event, done[EVENTS[event][0]].astype(float), done["last_discharge_lps"].astype(float),
                         first, n_boot=0) if len(done) else None
    fit = None if ef is None else ef.fit
    return {"event": event, "members": int(q.size), "happened": int(obs.sum()),
            "at_first_discharge": 0 if ef is None else int(ef.left.sum()),
            "censored_at_lps": float(q[~obs].max()) if (~obs).any() else None,
            "km_median_lps": med, "km_q16_lps": lo, "km_q84_lps": hi,
            "fit_median_lps": None if fit is None else fit.median,
            "fit_q16_lps": None if fit is None else fit.quantile(BAND[0]),
            "fit_q84_lps": None if fit is None else fit.quantile(BAND[1])}


def stage_fractions(members) -> Dict[str, float]:
    """Shares of the completed members with a removal, with 1+, 2+ (failing in separate stages: two
    stages apart by a stable period) and 3+ stages."""
    done = members[members["status"] == "completed"]
    n = max(len(done), 1)
    stages = done["stages"].fillna(0).astype(int).to_numpy()
    removed = np.isfinite(done["first_removal_lps"].astype(float).to_numpy())
    return {"with_removal": removed.sum() / n, "stages_1plus": (stages >= 1).sum() / n,
            "stages_2plus": (stages >= 2).sum() / n, "stages_3plus": (stages >= 3).sum() / n}


def spread(values) -> Tuple[Optional[float], Optional[float], Optional[float]]:
    """(16 %, median, 84 %) of finite values (plain quantiles: no censoring, e.g. a crest lowering)."""
    v = np.asarray([x for x in values if x is not None and np.isfinite(x)], float)
    if v.size == 0:
        return None, None, None
    lo, med, hi = np.quantile(v, [BAND[0], 0.5, BAND[1]])
    return float(lo), float(med), float(hi)


def _by_seed(members, event: str) -> Dict[int, Tuple[float, bool]]:
    done = members[members["status"] == "completed"]
    q, obs = event_arrays(done, event)
    return {int(s): (float(v), bool(o)) for s, v, o in zip(done["seed"], q, obs)}


def _km_median(pairs) -> Optional[float]:
    q = np.array([p[0] for p in pairs], float)
    return empirical_quantile(q, np.array([p[1] for p in pairs], bool), 0.5) if q.size else None


@dataclass
class Shift:
    """The shift of an event's median from the reference's [l/s], with its bootstrap interval."""

    event: str
    reference: Optional[float]  # Kaplan-Meier median of the reference [l/s]
    setting: Optional[float]  # of the setting
    shift: Optional[float]  # setting - reference; None where either is not reached
    lo: float = math.nan  # bootstrap 16 % [l/s]
    hi: float = math.nan  # 84 %
    left_out: float = math.nan  # share of resamples with a median not reached
    seeds: int = 0  # seeds both ran (completed)


def median_shift(reference, setting, event: str, n_boot: int = 1000, seed: int = 0, band=BAND) -> Shift:
    """The shift of the Kaplan-Meier median of `event` from `reference` to `setting` (two outcome
    tables over the same seeds), with its paired bootstrap over the seeds both completed."""
    a, b = _by_seed(reference, event), _by_seed(setting, event)
    common = sorted(set(a) & set(b))
    ma, mb = _km_median([a[s] for s in common]), _km_median([b[s] for s in common])
    out = Shift(event, ma, mb, None if ma is None or mb is None else mb - ma, seeds=len(common))
    if not common or n_boot <= 0:
        return out
    rng = np.random.default_rng(seed)
    shifts = np.full(n_boot, np.nan)
    for k in range(n_boot):
        pick = [common[i] for i in rng.integers(0, len(common), len(common))]
        ra, rb = _km_median([a[s] for s in pick]), _km_median([b[s] for s in pick])
        if ra is not None and rb is not None:
            shifts[k] = rb - ra
    kept = shifts[np.isfinite(shifts)]
    out.left_out = float(1.0 - kept.size / n_boot)
    if kept.size:
        out.lo, out.hi = (float(v) for v in np.quantile(kept, band, method="inverted_cdf"))
    return out


# ---------------------------------------------------------------------------- knob settings
@dataclass
class Setting:
    """One knob's value: the scene keys it sets (dotted key -> value, SI)."""

    knob: str
    value: str  # short, for the directory's name
    label: str  # for the tables
    values: Dict[str, Any] = field(default_factory=dict)

    @property
    def name(self) -> str:
        """The setting's directory name, e.g. 'cfl=0.25'."""
        return f"{self.knob}={self.value}"

    def scene(self, reference):
        s = reference
        if s.numerics.fidelity is not None:  # a knob moved from a preset: the scene's own values then
            s = s.with_value("numerics.fidelity", None)
        for k, v in self.values.items():
            s = s.with_value(k, v)
        return s


# the knobs and their settings by study size: (knob, factor or value), relative to the reference
KNOBS = ("grid", "ramp", "cfl", "porosity", "dem_steps", "spin_up", "viscous_substeps", "bandwidth", "overflow")
# the full size runs the grid last: its finer setting costs more than all the others together, and an
# interrupted study then holds every other knob
SIZES = {
    "full": {"ramp": [0.25, 0.5], "cfl": [0.25], "porosity": ["lookup4", "lookup", "lookup16"],
             "dem_steps": [64.0], "spin_up": [0.5], "viscous_substeps": [1], "bandwidth": [1.0, 0.75, 1.5],
             "overflow": ["drag_lift"], "grid": [2.0, 0.5]},
    "small": {"grid": [2.0, 0.5], "ramp": [0.5], "cfl": [0.25], "porosity": ["lookup"], "dem_steps": [64.0],
              "spin_up": [0.5], "viscous_substeps": [1]},
    "tiny": {"cfl": [0.25], "porosity": ["lookup"]},
}


def _grid_setting(ref, factor: float) -> Setting:
    g = ref.grid
    vals = {f"grid.{k}": round(getattr(g, k) * factor, 9) for k in ("dx", "dz", "dz_bed", "bed_layer_height")}
    return Setting("grid", f"x{factor:g}", f"{'coarser' if factor > 1 else 'finer'}: dx {vals['grid.dx'] * 100:g} cm, "
                   f"dz {vals['grid.dz'] * 100:g} cm", vals)


def setting(ref, knob: str, value) -> Setting:
    """The setting of `knob` at `value` from the reference scene `ref` (see SIZES for the values)."""
    n, h = ref.numerics, ref.hydrograph
    if knob == "grid":
        return _grid_setting(ref, float(value))
    if knob == "ramp":
        t = round(h.ramp_duration * float(value), 9)
        return Setting("ramp", f"{t:g}", f"{t:g} s", {"hydrograph.ramp_duration": t})
    if knob == "cfl":
        return Setting("cfl", f"{float(value):g}", f"{float(value):g}", {"numerics.cfl": float(value)})
    if knob == "porosity":
        m = int(str(value)[len("lookup"):] or 8)  # 'lookup' is the table at m = 8, 'lookup16' at m = 16
        return Setting("porosity", str(value), f"lookup table, m = {m}",
                       {"numerics.porosity_method": "lookup", "numerics.lookup_m": m})
    if knob == "dem_steps":  # the same contact stiffness: the contact lasts steps x dem_dt
        steps, dt = float(value), n.dem_dt * n.dem_contact_steps / float(value)
        return Setting("dem_steps", f"{steps:g}", f"{steps:g} (dem_dt {dt:.3g} s)",
                       {"numerics.dem_dt": dt, "numerics.dem_contact_steps": steps})
    if knob == "viscous_substeps":
        m = int(value)
        return Setting("viscous_substeps", f"{m}", f"{m} (the explicit stresses in one step)" if m == 1 else f"{m}",
                       {"numerics.viscous_substeps": m})
    if knob == "bandwidth":  # the kernel mapping at a width in stone diameters d, from the cell mapping
        f = float(value)
        # 1 d: the width unset, the kernel's default (the packing's mean diameter); else f x the nominal d
        b = None if f == 1.0 else round(ref.stones.diameter * f, 9)
        label = f"kernel, b = {f:g} d" + ("" if b is None else f" ({b * 1000:g} mm)")
        return Setting("bandwidth", f"{f:g}d", label,
                       {"numerics.coupling_mapping": "kernel", "numerics.coupling_bandwidth": b})
    if knob == "overflow":  # an effect switched on: the overflow's drag and lift on the protruding stones
        return Setting("overflow", str(value), f"overflow load {value}", {"numerics.overflow_load": str(value)})
    if knob == "spin_up":
        t = round(h.spin_up_duration * float(value), 9)
        return Setting("spin_up", f"{t:g}", f"{t:g} s", {"hydrograph.spin_up_duration": t})
    raise ValueError(f"knob = {knob!r} is not one of {', '.join(KNOBS)}")


def preset_of(scene) -> Optional[str]:
    """The fidelity preset whose knob values the scene holds (set or not), else None."""
    from .fidelity import PRESETS

    for name, vals in PRESETS.items():
        if all(scene.value_of(k) == v for k, v in vals.items()):
            return name
    return None


def knob_settings(ref, size: str = "full", knobs: Optional[Sequence[str]] = None) -> List[Setting]:
    """The settings of a study size ('full', 'small', 'tiny'), of the `knobs` named (default all of
    that size), each validated on the reference scene (ValueError naming the key)."""
    if size not in SIZES:
        raise ValueError(f"size = {size!r} is not one of {', '.join(SIZES)}")
    for k in knobs or ():
        if k not in KNOBS:
            raise ValueError(f"knobs: {k!r} is not one of {', '.join(KNOBS)}")
    out = []
    for knob, values in SIZES[size].items():
        if knobs is not None and knob not in knobs:
            continue
        for v in values:
            st = setting(ref, knob, v)
            st.scene(ref)  # validate now, before anything runs
            out.append(st)
    return out
