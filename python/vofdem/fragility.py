"""Fragility curves of an ensemble: at what discharge each failure event happens, over the members.

For one event (the first removal of any stone, stage 1, 2 or 3; see `analysis`) and one parameter
combination, each member gives either the discharge Q_i at which the event happened (an observation)
or, when it never happened before the run ended, only that Q_i > c_i, the discharge at the run's end
(a right-censored observation). Dropping the censored members would move the curve to lower
discharges; they are kept, as censored values. An event seen at the first snapshot after the stones
were released (a weir that fails as soon as it is loaded) happened at that discharge or below it: it
is left-censored there (q_first), since the run cannot say at which lower discharge it would have.

**Empirical distribution.** The Kaplan-Meier estimator F(q) = 1 - prod_{q_j <= q} (1 - d_j / r_j)
(d_j events at q_j, r_j members not yet failed nor censored just before q_j). When every member is
censored at the same discharge above all events (one hydrograph), it is the plain fraction
#{Q_i <= q} / n, censored members counted in n.

**Lognormal fit.** ln Q ~ N(mu, sigma^2), by maximum likelihood with the censoring::

    ln L(mu, sigma) = sum_exact [-ln sigma - z_i^2 / 2 - ln Q_i - ln sqrt(2 pi)]
                      + sum_right ln S(z_j) + sum_left ln S(-z_k),
    z = (ln Q - mu) / sigma,   S(z) = 1 - Phi(z) = erfc(z / sqrt 2) / 2,

maximised by Newton's method on (mu, ln sigma) with the analytic gradient and Hessian (a censored
term has d ln S / dz = -lambda(z), lambda = phi / S the inverse Mills ratio, and
d lambda / dz = lambda (lambda - z)). The median is exp(mu) and the band exp(mu -+ sigma) holds
the 15.9-84.1 % of the fitted distribution ("16-84 %"). The fit needs one exact observation at
least: with none, the likelihood has no maximum (no event: the median lies beyond the censoring
discharge; only left- and right-censored members: any median between them fits, with sigma -> 0).
With every exact observation equal and none censored, the maximum is at sigma = 0 (a step).
A fitted median or band beyond the censoring discharge is an extrapolation and is marked so.

**Uncertainty of the median.** A bootstrap over members: `n_boot` resamples of the n members with
replacement (numpy's default generator, seeded), each refitted; the 16-84 % interval of their
medians. A resample without any event has its median beyond the censoring discharge (+inf); one
without an exact observation in which at least half the members failed at the first discharge has
its median there or below (-inf); any other resample without a fit is left out of the interval (its
share is reported).

The table and the figure set the events next to the scene's reference data (`reference.Reference`:
observed and modelled discharges, with their sources) when the scene has any, and next to nothing
otherwise.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from statistics import NormalDist
from typing import List, Optional, Sequence, Tuple

import numpy as np

from .reference import Reference

# event name -> (column of the outcome table, label)
EVENTS = {"first_removal": ("first_removal_lps", "first removal of any stone"),
          "stage1": ("stage1_lps", "stage 1"), "stage2": ("stage2_lps", "stage 2"),
          "stage3": ("stage3_lps", "stage 3")}
BAND = (0.16, 0.84)

_LN_SQRT_2PI = 0.5 * math.log(2.0 * math.pi)
_erfc = np.frompyfunc(math.erfc, 1, 1)


def log_sf(z) -> np.ndarray:
    """ln S(z) = ln(1 - Phi(z)) of the standard normal, accurate far into the upper tail."""
    z = np.atleast_1d(np.asarray(z, float))
    out = np.empty_like(z)
    far = z > 30.0  # erfc underflows near z = 37; the asymptotic series is exact to ~1e-10 here
    zn = z[~far]
    out[~far] = np.log(0.5 * _erfc(zn / math.sqrt(2.0)).astype(float))
    zf = z[far]
    w = 1.0 / (zf * zf)
    out[far] = -0.5 * zf * zf - np.log(zf) - _LN_SQRT_2PI + np.log1p(w * (-1.0 + w * (3.0 - 15.0 * w)))
    return out


def mills_ratio(z) -> np.ndarray:
    """lambda(z) = phi(z) / S(z), the inverse Mills ratio of the standard normal."""
    z = np.atleast_1d(np.asarray(z, float))
    return np.exp(-0.5 * z * z - _LN_SQRT_2PI - log_sf(z))


def censored_loglik(mu: float, sigma: float, q_obs, q_cens, q_left=()) -> float:
    """ln L of the lognormal (mu, sigma) for exact discharges q_obs, right-censored q_cens (the
    event had not happened by then) and left-censored q_left (it had happened by then)."""
    y, c, b = (np.log(np.asarray(v, float)) for v in (q_obs, q_cens, q_left))
    z = (y - mu) / sigma
    return float(np.sum(-math.log(sigma) - 0.5 * z * z - y - _LN_SQRT_2PI) + np.sum(log_sf((c - mu) / sigma))
                 + np.sum(log_sf((mu - b) / sigma)))


@dataclass
class LognormalFit:
    """ln Q ~ N(mu, sigma^2) [Q in l/s]."""

    mu: float
    sigma: float
    n: int  # members
    n_observed: int  # members in which the event happened (exactly or by the first discharge)
    loglik: float
    iterations: int

    @property
    def median(self) -> float:
        return math.exp(self.mu)

    def quantile(self, p: float) -> float:
        """Discharge [l/s] by which the event has happened with probability p (0 < p < 1)."""
        return math.exp(self.mu + self.sigma * NormalDist().inv_cdf(p))

    def cdf(self, q) -> np.ndarray:
        q = np.asarray(q, float)
        if self.sigma == 0.0:
            return (q >= self.median).astype(float)
        return 1.0 - np.exp(log_sf((np.log(q) - self.mu) / self.sigma))


def _censored_terms(sig: float, zc: np.ndarray, sign: float):
    """Gradient (mu, sigma) and Hessian terms of sum ln S(w), w = sign (ln c - mu) / sigma:
    sign +1 for right-censored members, -1 for left-censored ones (ln Phi(z) = ln S(-z))."""
    w = sign * zc
    lam = mills_ratio(w)
    dl = lam * (lam - w)
    g = np.array([sign * lam.sum() / sig, (lam * w).sum() / sig])
    h = -np.array([[dl.sum(), sign * (dl * w + lam).sum()],
                   [sign * (dl * w + lam).sum(), (dl * w * w + 2.0 * lam * w).sum()]]) / sig ** 2
    return g, h


def _gradient_hessian(mu: float, s: float, y: np.ndarray, c: np.ndarray, b: np.ndarray):
    """Gradient and Hessian of ln L in (mu, s = ln sigma); y exact, c right-, b left-censored logs."""
    sig = math.exp(s)
    z = (y - mu) / sig
    g = np.array([z.sum() / sig, (z * z - 1.0).sum() / sig])
    h = np.array([[-y.size, -2.0 * z.sum()], [-2.0 * z.sum(), (1.0 - 3.0 * z * z).sum()]]) / sig ** 2
    for vals, sign in ((c, 1.0), (b, -1.0)):
        if vals.size:
            gc, hc = _censored_terms(sig, (vals - mu) / sig, sign)
            g, h = g + gc, h + hc
    # to (mu, s): d/ds = sigma d/dsigma
    g_s = np.array([g[0], sig * g[1]])
    h_s = np.array([[h[0, 0], sig * h[0, 1]], [sig * h[0, 1], sig * sig * h[1, 1] + sig * g[1]]])
    return g_s, h_s


def fit_lognormal(q, observed, left=None, max_iter: int = 100, tol: float = 1e-10) -> Optional[LognormalFit]:
    """Maximum-likelihood lognormal of discharges q [l/s]: observed[i] False where q[i] is a
    right-censoring discharge, left[i] True where the event happened at q[i] or below (see the
    module's docstring). None when there is no exact observation (no maximum)."""
    q, observed = np.asarray(q, float), np.asarray(observed, bool)
    left = np.zeros(q.shape, bool) if left is None else np.asarray(left, bool)
    if q.shape != observed.shape or q.shape != left.shape or q.ndim != 1:
        raise ValueError(f"q, observed and left must be 1D of one length, got {q.shape}, {observed.shape}, "
                         f"{left.shape}")
    if not np.all(np.isfinite(q) & (q > 0)):
        raise ValueError("q: every discharge must be finite and positive [l/s]")
    if np.any(left & ~observed):
        raise ValueError("left: a left-censored member must be one in which the event happened (observed)")
    exact = observed & ~left
    y, c, b = np.log(q[exact]), np.log(q[~observed]), np.log(q[left])
    if y.size == 0:
        return None
    if c.size == 0 and b.size == 0 and np.ptp(y) == 0.0:  # a step: sigma = 0 maximises ln L
        return LognormalFit(float(y[0]), 0.0, q.size, int(observed.sum()), math.inf, 0)
    allv = np.log(q)
    mu, s = float(allv.mean()), math.log(max(float(allv.std()), 0.05))
    ll = _loglik_s(mu, s, y, c, b)
    for it in range(1, max_iter + 1):
        g, h = _gradient_hessian(mu, s, y, c, b)
        step = _ascent_step(g, h)
        t = 1.0
        while True:  # backtracking: ln L must not decrease
            mu_n, s_n = float(mu + t * step[0]), float(s + t * step[1])
            ll_n = _loglik_s(mu_n, s_n, y, c, b)
            if ll_n >= ll or t < 1e-12:
                break
            t *= 0.5
        done = abs(t * step[0]) < tol and abs(t * step[1]) < tol
        mu, s, ll = mu_n, s_n, max(ll, ll_n)
        if done or np.max(np.abs(g)) < tol:
            sig = math.exp(s)
            return LognormalFit(mu, sig, q.size, int(observed.sum()),
                                censored_loglik(mu, sig, q[exact], q[~observed], q[left]), it)
    raise RuntimeError(f"lognormal fit: no convergence in {max_iter} Newton steps (mu {mu:.6g}, sigma "
                       f"{math.exp(s):.6g}, {y.size} exact, {c.size} right-, {b.size} left-censored)")


def _loglik_s(mu: float, s: float, y: np.ndarray, c: np.ndarray, b: np.ndarray) -> float:
    # a trial step of the line search far out (sigma underflowing to 0, z overflowing) gives ln L = -inf,
    # which the search rejects: not worth a warning
    with np.errstate(divide="ignore", over="ignore"):
        sig = math.exp(s)
        z = (y - mu) / sig
        out = float(np.sum(-s - 0.5 * z * z))
        if c.size:
            out += float(np.sum(log_sf((c - mu) / sig)))
        if b.size:
            out += float(np.sum(log_sf((mu - b) / sig)))
    return out


def _ascent_step(g: np.ndarray, h: np.ndarray) -> np.ndarray:
    """Newton's step where the Hessian is negative definite, a bounded gradient step elsewhere."""
    if h[0, 0] < 0 and np.linalg.det(h) > 0:
        return -np.linalg.solve(h, g)
    return g / max(1.0, float(np.max(np.abs(g))))


def kaplan_meier(q, observed) -> Tuple[np.ndarray, np.ndarray]:
    """(discharges of the events [l/s], F just after each): the censored empirical distribution. A
    left-censored member counts as an event at its discharge: F is right from there on."""
    q, observed = np.asarray(q, float), np.asarray(observed, bool)
    qs = np.unique(q[observed])
    surv, F = 1.0, []
    for v in qs:
        at_risk = np.sum(q >= v)  # a member censored at v is still at risk at v
        surv *= 1.0 - np.sum((q == v) & observed) / at_risk
        F.append(1.0 - surv)
    return qs, np.asarray(F, float)


def empirical_quantile(q, observed, p: float) -> Optional[float]:
    """The smallest discharge by which the Kaplan-Meier F reaches p; None if it never does (the
    censored members leave it unknown, above their censoring discharge)."""
    qs, F = kaplan_meier(q, observed)
    hit = np.flatnonzero(F >= p - 1e-12)
    return float(qs[hit[0]]) if hit.size else None


def empirical_median(q, observed) -> Optional[float]:
    """The smallest discharge by which the Kaplan-Meier F reaches 1/2; None if it never does."""
    return empirical_quantile(q, observed, 0.5)


def bootstrap_median(q, observed, left=None, n_boot: int = 1000, seed: int = 0,
                     band=BAND) -> Tuple[float, float, float]:
    """(low, high, share of resamples left out): the `band` quantiles of the fitted median over
    `n_boot` resamples of the members (see the module's docstring); nan if every resample is left out."""
    q, observed = np.asarray(q, float), np.asarray(observed, bool)
    left = np.zeros(q.shape, bool) if left is None else np.asarray(left, bool)
    rng = np.random.default_rng(seed)
    med = np.full(n_boot, np.nan)
    for b in range(n_boot):
        idx = rng.integers(0, q.size, q.size)
        if not observed[idx].any():
            med[b] = math.inf
            continue
        fit = fit_lognormal(q[idx], observed[idx], left[idx])
        if fit is not None:
            med[b] = fit.median
        elif np.mean(left[idx]) >= 0.5:
            med[b] = -math.inf
    kept = med[~np.isnan(med)]
    if kept.size == 0:
        return math.nan, math.nan, 1.0
    lo, hi = np.quantile(kept, band, method="inverted_cdf")
    return float(lo), float(hi), float(1.0 - kept.size / n_boot)


@dataclass
class EventFragility:
    """One event of one parameter combination."""

    event: str
    q: np.ndarray  # [l/s] event discharge, or the censoring discharge where observed is False
    observed: np.ndarray  # the event happened
    left: np.ndarray  # it happened at the first discharge a run could see it: at q or below
    fit: Optional[LognormalFit]
    median_band: Tuple[float, float]  # bootstrap 16-84 % of the median [l/s]
    boot_left_out: float  # share of bootstrap resamples without a fit

    @property
    def censored_at(self) -> Optional[float]:
        c = self.q[~self.observed]
        return float(c.max()) if c.size else None

    def row(self) -> dict:
        f = self.fit
        return {"event": self.event, "members": int(self.q.size), "happened": int(self.observed.sum()),
                "at_first_discharge": int(self.left.sum()), "censored_at_lps": self.censored_at,
                "empirical_median_lps": empirical_median(self.q, self.observed),
                "fit_median_lps": None if f is None else f.median,
                "fit_q16_lps": None if f is None else f.quantile(BAND[0]),
                "fit_q84_lps": None if f is None else f.quantile(BAND[1]),
                "fit_sigma_ln": None if f is None else f.sigma,
                "median_boot_lo_lps": self.median_band[0], "median_boot_hi_lps": self.median_band[1],
                "boot_left_out": self.boot_left_out}


def event_fragility(event: str, q_event: Sequence[Optional[float]], q_end: Sequence[float],
                    q_first: Optional[Sequence[float]] = None, n_boot: int = 1000, seed: int = 0) -> EventFragility:
    """Fragility of one event: q_event[i] the member's event discharge (None or nan: never), q_end[i]
    the discharge at its run's end (right-censoring), q_first[i] the first discharge at which its run
    could see the event (an event there is left-censored)."""
    qe = np.array([np.nan if v is None else float(v) for v in q_event], dtype=float)
    observed = np.isfinite(qe)
    q = np.where(observed, qe, np.asarray(q_end, float))
    left = np.zeros(q.shape, bool)
    if q_first is not None:
        left = observed & (qe <= np.asarray(q_first, float) * (1 + 1e-12))
    if q.size == 0:
        return EventFragility(event, q, observed, left, None, (math.nan, math.nan), math.nan)
    fit = fit_lognormal(q, observed, left)
    lo, hi, out = bootstrap_median(q, observed, left, n_boot, seed) if n_boot > 0 else (math.nan,) * 3
    return EventFragility(event, q, observed, left, fit, (lo, hi), out)


def fragility_of(members, n_boot: int = 1000, seed: int = 0) -> List[EventFragility]:
    """Every event's fragility over a table of completed members (pandas DataFrame with the
    columns of `EVENTS`, `last_discharge_lps` and `first_discharge_lps`)."""
    first = members["first_discharge_lps"].astype(float) if "first_discharge_lps" in members else None
    return [event_fragility(ev, members[col].astype(float), members["last_discharge_lps"].astype(float), first,
                            n_boot, seed) for ev, (col, _) in EVENTS.items()]


# ---------------------------------------------------------------------------- tables and figure
def combination_of(member: str) -> str:
    """'stones.k1=200/seed3' -> 'stones.k1=200'; 'seed3' -> '' (no varied parameter)."""
    return member.rpartition("/")[0]


def fragility_by_combination(members, n_boot: int = 1000, seed: int = 0):
    """{combination: [EventFragility per event]} over the completed members of an outcome table."""
    done = members[members["status"] == "completed"]
    combos = dict.fromkeys(combination_of(m) for m in members["member"])
    out = {}
    for combo in combos:
        sel = done[[combination_of(m) == combo for m in done["member"]]]
        out[combo] = fragility_of(sel, n_boot, seed)
    return out


def fragility_table(by_combo):
    """A pandas DataFrame: one row per combination and event (see EventFragility.row)."""
    import pandas as pd

    rows = [{"combination": combo, **ef.row()} for combo, evs in by_combo.items() for ef in evs]
    return pd.DataFrame.from_records(rows)


def _num(v, fmt: str = "{:.2f}") -> str:
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "-"
    return "beyond the end" if math.isinf(v) else fmt.format(v)


def _q(v: Optional[float], end: Optional[float], first: Optional[float] = None) -> str:
    """A discharge, marked with * where it lies beyond the censoring discharge (an extrapolation)."""
    if v is not None and v == -math.inf:
        return f"<= {_num(first)}"
    text = _num(v)
    return text + "*" if v is not None and end is not None and math.isfinite(v) and v > end else text


def _given(reference: Optional[Reference]) -> Optional[Reference]:
    return reference if reference is not None and reference.given else None


def fragility_markdown(by_combo, n_members: Optional[dict] = None, reference: Optional[Reference] = None) -> str:
    """Per combination, each event's empirical median, lognormal fit and (when the scene has reference
    data) the observed and modelled discharges."""
    ref = _given(reference)
    sources = [] if ref is None else ([(False, "observed")] if ref.has_observed else []) + (
        [(True, "model")] if ref.has_model else [])
    out = []
    if sources:
        out += ["Compared with " + "; ".join(f"{w}: {ref.model_citation if m else ref.citation}"
                                             for m, w in sources) + ".", ""]
    for combo, evs in by_combo.items():
        n_all = (n_members or {}).get(combo)
        n_done = evs[0].q.size if evs else 0
        cens = next((e.censored_at for e in evs if e.censored_at is not None), None)
        extra = f" ({n_all - n_done} failed or lost members left out)" if n_all is not None and n_all > n_done else ""
        out += [f"**{combo or 'all members'}**: {n_done} completed members{extra}; where an event never happened "
                f"the member is censored at the discharge at its run's end ({_num(cens)} l/s).", "",
                "| event | happened in (at the first discharge) | empirical median [l/s] | lognormal median "
                "[16-84 %] [l/s] | median's bootstrap 16-84 % [l/s] |" + "".join(f" {w} [l/s] |" for _, w in sources),
                "|---|---|---|---|---|" + "---|" * len(sources)]
        for e in evs:
            r, end = e.row(), e.censored_at
            fit = "no fit" if e.fit is None else (f"{_q(r['fit_median_lps'], end)} [{_q(r['fit_q16_lps'], end)}-"
                                                  f"{_q(r['fit_q84_lps'], end)}]")
            emp = r["empirical_median_lps"]
            lo, hi = e.median_band
            first = float(np.max(e.q[e.left])) if e.left.any() else None
            boot = "-" if math.isnan(lo) else (_q(lo, end, first) if lo == hi
                                               else f"{_q(lo, end, first)} to {_q(hi, end, first)}")
            refs = [] if ref is None else ref.event_lps(e.event)
            cells = "".join(f" {'-' if refs[m] is None else f'{refs[m]:g}'} |" for m, _ in sources)
            out.append(f"| {EVENTS[e.event][1]} | {r['happened']} of {r['members']} ({r['at_first_discharge']}) | "
                       f"{'not reached' if emp is None else _num(emp)} | {fit} | {boot} |{cells}")
        out += ["", "(n): members in which it happened at the first discharge at which the run could see it, "
                "left-censored there. *: beyond the run's end, an extrapolation of the fit. No fit: no member "
                "in which it happened after the first discharge.", ""]
    return "\n".join(out)


def fig_fragility(by_combo, reference: Optional[Reference] = None):
    """Fragility curves: per event, the probability that it has happened by a discharge; the
    empirical distribution (steps), the lognormal fit (dashed) and its median's bootstrap interval,
    and the reference's observed (dotted) and modelled (dash-dot) discharges when the scene has any."""
    from matplotlib.figure import Figure

    ref = _given(reference)
    fig = Figure(figsize=(9.0, 6.4), layout="constrained")
    axes = fig.subplots(2, 2, sharex=True, sharey=True).ravel()
    qs = [e.q for evs in by_combo.values() for e in evs if e.q.size]
    refs = [] if ref is None else [v for ev in EVENTS for v in ref.event_lps(ev) if v is not None]
    lo = min([float(np.min(q)) for q in qs] + refs) * 0.97
    hi = max([float(np.max(q)) for q in qs] + refs) * 1.02
    colors = [f"C{i % 10}" for i in range(len(by_combo))]
    for ax, event in zip(axes, EVENTS):
        for color, (combo, evs) in zip(colors, by_combo.items()):
            e = next(x for x in evs if x.event == event)
            _draw_event(ax, e, color, combo or "members", lo)
        exp_q, mod_q = (None, None) if ref is None else ref.event_lps(event)
        if exp_q is not None:
            ax.axvline(exp_q, color="k", ls=":", lw=1.2, label=f"observed: {ref.short()}")
            ax.annotate(f"{exp_q:g}", (exp_q, 1.0), textcoords="offset points", xytext=(2, -10), fontsize=8)
        if mod_q is not None:
            ax.axvline(mod_q, color="0.4", ls="-.", lw=1.2, label=f"model: {ref.short(model=True)}")
            ax.annotate(f"{mod_q:g}", (mod_q, 1.0), textcoords="offset points", xytext=(2, -20), fontsize=8,
                        color="0.4")
        ax.set_title(EVENTS[event][1])
        ax.set_xlim(lo, hi)
        ax.set_ylim(-0.02, 1.02)
        ax.grid(alpha=0.3)
    for ax in axes[2:]:
        ax.set_xlabel("discharge Q [l/s]")
    for ax in axes[::2]:
        ax.set_ylabel("P(happened by Q)")
    figure_legend(fig, axes, 3)
    return fig


def figure_legend(fig, axes, max_cols: int) -> None:
    """One legend below the panels of `fig`: every label of `axes` once, in the order first drawn."""
    handles, labels = [], []
    for ax in axes:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            if lab not in labels:
                handles.append(h)
                labels.append(lab)
    fig.legend(handles, labels, loc="outside lower center", ncols=legend_columns(fig, labels, max_cols), fontsize=8)


def legend_columns(fig, labels, max_cols: int, fontsize: float = 8.0) -> int:
    """Columns of a legend as wide as `fig` at most: a character of `fontsize` points is about 0.55 of it
    wide, and each entry takes its handle and padding (about 8 characters) besides its label."""
    fit = int(fig.get_figwidth() * 72.0 / (0.55 * fontsize) // (max(map(len, labels), default=1) + 8))
    return max(1, min(max_cols, len(labels), fit))


def _draw_event(ax, e: EventFragility, color: str, label: str, lo: float) -> None:
    if not e.q.size:
        return
    qk, F = kaplan_meier(e.q, e.observed)
    end = float(np.max(e.q))
    x = np.concatenate([[lo], qk, [end]])
    y = np.concatenate([[0.0], F, [F[-1] if F.size else 0.0]])
    ax.step(x, y, where="post", color=color, lw=1.6, label=f"{label}: empirical (n = {e.q.size})")
    if e.censored_at is not None:  # never happened by the run's end
        ax.plot([e.censored_at], [y[-1]], marker=">", color=color, ls="none")
    if e.left.any():  # happened at the first discharge the runs could see, or below it
        b = float(np.max(e.q[e.left]))
        ax.plot([b], [float(F[np.searchsorted(qk, b)])], marker="<", color=color, ls="none")
    if e.fit is not None:
        grid = np.linspace(lo, end, 200)
        ax.plot(grid, e.fit.cdf(grid), color=color, ls="--", lw=1.2, label=f"{label}: lognormal fit")
        b0, b1 = e.median_band
        if np.isfinite(b0) and b0 < end:  # the median's bootstrap interval, cut at the run's end
            ax.plot([b0, min(b1, end)], [0.5, 0.5], color=color, lw=4, alpha=0.35, solid_capstyle="butt")
        ax.plot([e.fit.median], [0.5], marker="o", color=color, ms=4)


def write_fragility(out_dir, members, param_keys: Sequence[str] = (), n_boot: int = 1000, seed: int = 0,
                    reference: Optional[Reference] = None) -> str:
    """fragility.csv and fragility.png of an outcome table in `out_dir`, compared with `reference` (the
    scene's reference data) when given; returns the markdown tables ('' when no member completed)."""
    from pathlib import Path

    out = Path(out_dir)
    if not (members["status"] == "completed").any():
        return ""
    by_combo = fragility_by_combination(members, n_boot, seed)
    table = fragility_table(by_combo)
    combos = [combination_of(m) for m in members["member"]]
    params = members[list(param_keys)].assign(combination=combos).drop_duplicates("combination")
    table = params[["combination", *param_keys]].merge(table, on="combination", how="right")
    table.to_csv(out / "fragility.csv", index=False, lineterminator="\n")
    fig_fragility(by_combo, reference).savefig(out / "fragility.png", dpi=110)
    counts = {c: combos.count(c) for c in set(combos)}
    return fragility_markdown(by_combo, counts, reference)
