"""Fragility statistics against hand-computed cases and a slow obvious reference: the censored
empirical distribution, the censored lognormal maximum likelihood, the bootstrap of the median."""
import math

import numpy as np
import pytest

from vofdem.fragility import (censored_loglik, empirical_median, event_fragility, fit_lognormal, kaplan_meier,
                              legend_columns, log_sf, mills_ratio)


def _loglik_slow(mu, sigma, q_obs, q_cens, q_left=()):
    """ln L written term by term with the standard library only."""
    total = 0.0
    for b in q_left:
        total += math.log(0.5 * math.erfc(-(math.log(b) - mu) / sigma / math.sqrt(2)))
    for q in q_obs:
        z = (math.log(q) - mu) / sigma
        total += -math.log(sigma) - 0.5 * z * z - math.log(q) - 0.5 * math.log(2 * math.pi)
    for c in q_cens:
        total += math.log(0.5 * math.erfc((math.log(c) - mu) / sigma / math.sqrt(2)))
    return total


def _argmax_slow(q_obs, q_cens, mu0, sigma0, q_left=()):
    """Zooming grid search of ln L over (mu, sigma): 21 x 21 points, the box shrunk 4x around the
    best point, 14 times (a final resolution below 1e-8 of the starting box)."""
    mu, sig, w_mu, w_sig = mu0, sigma0, 1.0, 0.9 * sigma0
    for _ in range(14):
        cands = [(m, s) for m in np.linspace(mu - w_mu, mu + w_mu, 21)
                 for s in np.linspace(max(sig - w_sig, 1e-6), sig + w_sig, 21)]
        mu, sig = max(cands, key=lambda p: _loglik_slow(p[0], p[1], q_obs, q_cens, q_left))
        w_mu, w_sig = w_mu / 4, w_sig / 4
    return mu, sig


def test_log_sf_and_mills_ratio():
    z = np.array([-5.0, -1.0, 0.0, 1.0, 3.0, 8.0, 20.0])
    ref = [math.log(0.5 * math.erfc(v / math.sqrt(2))) for v in z]
    assert np.allclose(log_sf(z), ref, rtol=1e-13, atol=0)
    # the asymptotic series beyond z = 30 meets erfc at the switch
    z = 30.0 + 1e-9
    assert log_sf([z])[0] == pytest.approx(math.log(0.5 * math.erfc(z / math.sqrt(2))), rel=1e-11)
    far = -1800 - math.log(60 * math.sqrt(2 * math.pi))  # -z^2/2 - ln(z sqrt(2 pi)), to 1/z^2
    assert log_sf([60.0])[0] == pytest.approx(far, rel=1e-6)
    assert mills_ratio([0.0])[0] == pytest.approx(math.sqrt(2 / math.pi), rel=1e-14)
    assert mills_ratio([50.0])[0] == pytest.approx(50.0 + 1 / 50, rel=1e-6)  # lambda(z) ~ z + 1/z


def test_without_censoring_the_fit_is_the_mean_and_spread_of_the_logs():
    q = np.array([12.0, 13.5, 15.0, 16.2, 18.9, 21.0])
    fit = fit_lognormal(q, np.ones(q.size, bool))
    y = np.log(q)
    assert fit.mu == pytest.approx(y.mean(), abs=1e-12)
    assert fit.sigma == pytest.approx(math.sqrt(np.mean((y - y.mean()) ** 2)), rel=1e-10)
    assert fit.median == pytest.approx(math.exp(y.mean()), rel=1e-12)
    assert fit.quantile(0.5) == pytest.approx(fit.median, rel=1e-9)
    # 16-84 %: mu -+ sigma is the 15.87-84.13 % of a normal, so 0.16 / 0.84 lie just inside it
    assert math.log(fit.quantile(0.8413447460685429)) == pytest.approx(fit.mu + fit.sigma, rel=1e-9)
    assert fit.loglik == pytest.approx(_loglik_slow(fit.mu, fit.sigma, q, []), rel=1e-12)


def test_a_known_lognormal_sample_is_recovered_with_and_without_its_upper_tail():
    """The quantiles of LN(ln 16, 0.2) at (i - 1/2) / n stand for a large sample. Censoring its upper
    30 % at the 70 % quantile must leave the fit where it was; dropping them would not."""
    from statistics import NormalDist

    n, mu, sigma = 400, math.log(16.0), 0.2
    q = np.array([math.exp(mu + sigma * NormalDist().inv_cdf((i + 0.5) / n)) for i in range(n)])
    full = fit_lognormal(q, np.ones(n, bool))
    assert full.mu == pytest.approx(mu, abs=1e-12) and full.sigma == pytest.approx(sigma, rel=0.01)
    c = float(np.quantile(q, 0.7))
    observed = q <= c
    cens = fit_lognormal(np.where(observed, q, c), observed)
    assert cens.mu == pytest.approx(full.mu, abs=0.003) and cens.sigma == pytest.approx(full.sigma, rel=0.02)
    dropped = fit_lognormal(q[observed], np.ones(observed.sum(), bool))
    assert dropped.median < 0.93 * math.exp(mu)  # what dropping the censored members would give


def test_a_fit_whose_search_walks_sigma_to_zero_warns_nothing():
    """A bootstrap resample of a study: 9 exact removals at 10.125 l/s, 11 at the first discharge
    10.0625 (left-censored). The maximum has sigma near 0, and the line search's trials beyond it
    underflow sigma (ln L = -inf, rejected): numpy's divide and overflow warnings are not the user's
    business."""
    import warnings

    q = np.array([10.125] * 9 + [10.0625] * 11)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fit = fit_lognormal(q, np.ones(20, bool), np.arange(20) >= 9)
    assert fit.sigma < 0.01 and fit.median == pytest.approx(10.06, abs=0.01)  # over half failed by 10.06


def test_censored_fit_against_a_slow_grid_search():
    q_obs = [10.3, 12.5, 12.9, 14.1, 17.6, 19.0]
    q_cens = [25.0] * 4
    q = np.array(q_obs + q_cens)
    fit = fit_lognormal(q, np.arange(q.size) < len(q_obs))
    mu, sig = _argmax_slow(q_obs, q_cens, math.log(15.0), 0.5)
    assert fit.mu == pytest.approx(mu, abs=1e-7) and fit.sigma == pytest.approx(sig, abs=1e-7)
    assert fit.loglik == pytest.approx(_loglik_slow(mu, sig, q_obs, q_cens), rel=1e-12)
    # the score vanishes there (central differences of the slow ln L)
    h = 1e-6
    for d in ((h, 0), (0, h)):
        up = _loglik_slow(fit.mu + d[0], fit.sigma + d[1], q_obs, q_cens)
        down = _loglik_slow(fit.mu - d[0], fit.sigma - d[1], q_obs, q_cens)
        assert abs(up - down) / (2 * h) < 1e-5
    assert censored_loglik(fit.mu, fit.sigma, q_obs, q_cens) == pytest.approx(fit.loglik, rel=1e-14)


def test_left_censored_members_against_the_known_sample_and_the_slow_reference():
    """Members that failed as soon as they were loaded (at the first discharge a run sees) are
    left-censored there: the quantile sample of LN(ln 16, 0.2) cut below its 25 % and above its
    80 % quantiles still gives its mu and sigma."""
    from statistics import NormalDist

    n, mu, sigma = 400, math.log(16.0), 0.2
    q = np.array([math.exp(mu + sigma * NormalDist().inv_cdf((i + 0.5) / n)) for i in range(n)])
    lo, hi = float(np.quantile(q, 0.25)), float(np.quantile(q, 0.8))
    left, observed = q <= lo, q <= hi
    fit = fit_lognormal(np.clip(q, lo, hi), observed, left)
    assert fit.mu == pytest.approx(mu, abs=0.003) and fit.sigma == pytest.approx(sigma, rel=0.02)
    assert fit.n_observed == observed.sum()
    # a small case against the slow grid search: two at the first discharge 10.5, four exact, two never
    q_left, q_obs, q_cens = [10.5, 10.5], [11.2, 12.5, 14.1, 17.6], [25.0, 25.0]
    q = np.array(q_left + q_obs + q_cens)
    fit = fit_lognormal(q, np.arange(8) < 6, np.arange(8) < 2)
    m, s = _argmax_slow(q_obs, q_cens, math.log(14.0), 0.5, q_left)
    assert fit.mu == pytest.approx(m, abs=1e-7) and fit.sigma == pytest.approx(s, abs=1e-7)
    assert fit.loglik == pytest.approx(_loglik_slow(m, s, q_obs, q_cens, q_left), rel=1e-12)
    # failed at the first discharge or never: no maximum, no fit
    assert fit_lognormal(np.array([10.5, 25.0]), np.array([True, False]), np.array([True, False])) is None
    with pytest.raises(ValueError, match="left: a left-censored member must be one in which the event happened"):
        fit_lognormal(np.array([10.5, 25.0]), np.array([True, False]), np.array([False, True]))
    ev = event_fragility("first_removal", [10.5, 10.5, 12.0, None], [25.0] * 4, [10.5] * 4, n_boot=200, seed=1)
    assert ev.left.tolist() == [True, True, False, False] and ev.row()["at_first_discharge"] == 2
    assert 0 < ev.boot_left_out < 1  # resamples of one 10.5 and three 25 have no fit, nor a side
    # three of four fail when first loaded, one never: no fit; the median is at 10.5 or below in the
    # resamples where at least half fail there (most), beyond 25 where none does
    ev = event_fragility("first_removal", [10.5, 10.5, 10.5, None], [25.0] * 4, [10.5] * 4, n_boot=400, seed=2)
    assert ev.fit is None and ev.median_band[0] == -math.inf
    from vofdem.fragility import fragility_markdown

    assert "| first removal of any stone | 3 of 4 (3) | 10.50 | no fit | <= 10.50 |" in fragility_markdown({"": [ev]})


def test_one_event_among_censored_members_and_the_degenerate_cases():
    # one event at 12 l/s, three members without it by 25 l/s: a finite fit, median beyond 12
    q, obs = np.array([12.0, 25.0, 25.0, 25.0]), np.array([True, False, False, False])
    fit = fit_lognormal(q, obs)
    mu, sig = _argmax_slow([12.0], [25.0] * 3, math.log(20.0), 0.5)
    assert fit.mu == pytest.approx(mu, abs=1e-6) and fit.sigma == pytest.approx(sig, abs=1e-6)
    assert fit.median > 12.0
    assert fit_lognormal(np.array([25.0, 25.0]), np.array([False, False])) is None  # never happened
    step = fit_lognormal(np.array([10.25] * 3), np.ones(3, bool))  # all at once: sigma = 0
    assert step.sigma == 0.0 and step.median == pytest.approx(10.25)
    assert list(step.cdf([10.0, 10.25, 11.0])) == [0.0, 1.0, 1.0]
    with pytest.raises(ValueError, match="q: every discharge must be finite and positive"):
        fit_lognormal(np.array([1.0, -2.0]), np.ones(2, bool))


def test_kaplan_meier_by_hand():
    # 10, 12, 12 happen; 15 censored; 20 happens; 25 censored. At risk 6, 5, (15 leaves), 2:
    # S = 5/6, 5/6 * 3/5 = 1/2, 1/2 * 1/2 = 1/4
    q = np.array([10.0, 12.0, 12.0, 15.0, 20.0, 25.0])
    obs = np.array([True, True, True, False, True, False])
    qs, F = kaplan_meier(q, obs)
    assert qs.tolist() == [10.0, 12.0, 20.0]
    assert F == pytest.approx([1 / 6, 1 / 2, 3 / 4], abs=1e-15)
    assert empirical_median(q, obs) == 12.0
    # one censoring discharge above every event: the plain fraction, censored members counted
    qs, F = kaplan_meier(np.array([11.0, 14.0, 25.0, 25.0]), np.array([True, True, False, False]))
    assert F == pytest.approx([0.25, 0.5], abs=1e-15)
    assert empirical_median(np.array([11.0, 25.0, 25.0]), np.array([True, False, False])) is None


def test_event_fragility_and_its_seeded_bootstrap():
    q_event = [12.0, None, 13.0, 15.5, None, 14.2, 16.8, 12.7]
    q_end = [25.0] * len(q_event)
    a = event_fragility("stage1", q_event, q_end, n_boot=300, seed=7)
    b = event_fragility("stage1", q_event, q_end, n_boot=300, seed=7)
    assert a.median_band == b.median_band and a.boot_left_out == 0.0
    assert a.observed.tolist() == [v is not None for v in q_event] and a.censored_at == 25.0
    lo, hi = a.median_band
    assert lo < a.fit.median < hi
    row = a.row()
    assert (row["members"], row["happened"], row["empirical_median_lps"]) == (8, 6, 14.2)
    assert row["fit_q16_lps"] < row["fit_median_lps"] < row["fit_q84_lps"]
    never = event_fragility("stage3", [None, None], [25.0, 25.0], n_boot=50)
    assert never.fit is None and never.median_band == (math.inf, math.inf) and never.boot_left_out == 0.0


def test_the_legend_keeps_to_the_figure_width():
    from matplotlib.figure import Figure

    fig = Figure(figsize=(9.0, 6.4))
    short = ["reference", "grid", "ramp", "cfl"]
    # 9 in at 8 pt: about 147 characters a row, so labels of 60 characters (68 with the handle) take 2
    long_ = ["x" * 60] * 5
    assert legend_columns(fig, short, 3) == 3
    assert legend_columns(fig, long_, 3) == 2
    assert legend_columns(fig, ["x" * 200], 3) == 1
    assert legend_columns(fig, [], 3) == 1
