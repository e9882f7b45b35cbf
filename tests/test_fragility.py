"""isoslide.studies.fragility: maximum-likelihood lognormal fragility curves and the bootstrap over records."""

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import minimize
from scipy.stats import binom, norm

from isoslide.studies.fragility import BootstrapInterval, LognormalFit, bootstrap, fit_lognormal, probability

THETA, BETA = 0.4, 0.5
LEVELS = np.array([0.1, 0.2, 0.3, 0.45, 0.6, 0.8, 1.1])


def _stripes(rng, n_per_level, levels=LEVELS, theta=THETA, beta=BETA):
    n = np.full(levels.size, n_per_level)
    return levels, rng.binomial(n, probability(levels, theta, beta)), n


def _per_analysis(rng, size, theta=THETA, beta=BETA):
    x = np.exp(rng.normal(math.log(theta), 0.8, size))
    return x, rng.random(size) < probability(x, theta, beta)


def _standard_errors(x, n, theta=THETA, beta=BETA):
    """Standard errors of (ln theta, beta) from the Fisher information of the probit p = Phi(a + b ln x)."""
    lx = np.log(x)
    b = 1.0 / beta
    a = -math.log(theta) * b
    eta = a + b * lx
    w = n * norm.pdf(eta) ** 2 / (norm.cdf(eta) * norm.sf(eta))
    info = np.array([[w.sum(), (w * lx).sum()], [(w * lx).sum(), (w * lx * lx).sum()]])
    jac = np.array([[-1.0 / b, a / b**2], [0.0, -1.0 / b**2]])
    cov = jac @ np.linalg.inv(info) @ jac.T
    return math.sqrt(cov[0, 0]), math.sqrt(cov[1, 1])


def _negative_log_likelihood(params, x, z, n):
    ln_theta, ln_beta = params
    p = norm.cdf((np.log(x) - ln_theta) / math.exp(ln_beta))
    return -float(np.sum(binom.logpmf(z, n, p)))


def _nelder_mead(x, z, n):
    """A generic maximum-likelihood fit: Nelder-Mead on the binomial negative log-likelihood."""
    start = np.array([math.log(np.median(x)), math.log(1.0)])
    res = minimize(_negative_log_likelihood, start, args=(x, z, n), method="Nelder-Mead",
                   options={"xatol": 1e-12, "fatol": 1e-14, "maxiter": 20000, "maxfev": 40000})
    assert res.success, res.message
    return math.exp(res.x[0]), math.exp(res.x[1])


def _probit_irls(x, z, n, iterations=100):
    """A probit GLM written out: Fisher scoring (iteratively reweighted least squares) on ln x."""
    X = np.column_stack([np.ones_like(x), np.log(x)])
    coef = np.array([0.0, 0.1])
    for _ in range(iterations):
        eta = X @ coef
        p, d = norm.cdf(eta), norm.pdf(eta)
        w = n * d**2 / (p * (1.0 - p))
        working = eta + (z / n - p) / d
        new = np.linalg.solve(X.T @ (w[:, None] * X), X.T @ (w * working))
        if np.max(np.abs(new - coef)) < 1e-14:
            coef = new
            break
        coef = new
    a, b = coef
    return math.exp(-a / b), 1.0 / b


# ----------------------------------------------------------------------------------------------
# recovering a known curve
# ----------------------------------------------------------------------------------------------

@pytest.mark.parametrize("seed", range(5))
def test_stripes_recover_the_true_curve_within_four_fisher_standard_errors(seed):
    x, z, n = _stripes(np.random.default_rng(seed), 60)
    fit = fit_lognormal(x, z, n)
    se_ln_theta, se_beta = _standard_errors(x, n)
    assert abs(math.log(fit.theta / THETA)) < 4 * se_ln_theta
    assert abs(fit.beta - BETA) < 4 * se_beta
    assert (fit.n_analyses, fit.n_exceeded) == (int(n.sum()), int(z.sum()))


@pytest.mark.parametrize("seed", range(5))
def test_per_analysis_fit_recovers_the_true_curve_within_four_fisher_standard_errors(seed):
    x, e = _per_analysis(np.random.default_rng(100 + seed), 400)
    fit = fit_lognormal(x, e)
    se_ln_theta, se_beta = _standard_errors(x, np.ones_like(x))
    assert abs(math.log(fit.theta / THETA)) < 4 * se_ln_theta
    assert abs(fit.beta - BETA) < 4 * se_beta
    assert (fit.n_analyses, fit.n_exceeded) == (400, int(e.sum()))


def test_the_scatter_of_repeated_fits_matches_the_fisher_information_and_shrinks_like_one_over_root_n():
    """40 repeated stripe experiments at 50 and at 800 analyses per level: the spread of ln theta and
    beta agrees with the Fisher standard error within 35 % (the sampling error of a standard
    deviation from 40 draws is about 11 %), so it shrinks about 4 times for 16 times the analyses."""
    rng = np.random.default_rng(7)
    spread = {}
    for n_per in (50, 800):
        fits = [fit_lognormal(*_stripes(rng, n_per)) for _ in range(40)]
        ln_theta = np.log([f.theta for f in fits])
        beta = np.array([f.beta for f in fits])
        se = _standard_errors(LEVELS, np.full(LEVELS.size, n_per))
        rms = (math.sqrt(np.mean((ln_theta - math.log(THETA)) ** 2)), math.sqrt(np.mean((beta - BETA) ** 2)))
        for got, want in zip(rms, se, strict=True):
            assert 0.65 < got / want < 1.35, (n_per, got, want)
        spread[n_per] = rms
    for k in range(2):
        assert 2.5 < spread[50][k] / spread[800][k] < 6.0


# ----------------------------------------------------------------------------------------------
# the same maximum as independent fits
# ----------------------------------------------------------------------------------------------

@pytest.mark.parametrize("seed", range(3))
def test_stripes_fit_equals_a_generic_nelder_mead_maximum_likelihood(seed):
    x, z, n = _stripes(np.random.default_rng(20 + seed), 25)
    fit = fit_lognormal(x, z, n)
    theta, beta = _nelder_mead(x, z, n)
    assert fit.theta == pytest.approx(theta, rel=1e-6)
    assert fit.beta == pytest.approx(beta, rel=1e-6)
    assert fit.log_likelihood == pytest.approx(-_negative_log_likelihood(
        [math.log(fit.theta), math.log(fit.beta)], x, z, n), rel=1e-12)


def test_per_analysis_fit_equals_nelder_mead_and_a_written_out_probit_glm():
    x, e = _per_analysis(np.random.default_rng(31), 300)
    fit = fit_lognormal(x, e)
    ones = np.ones_like(x)
    for theta, beta in (_nelder_mead(x, e.astype(float), ones), _probit_irls(x, e.astype(float), ones)):
        assert fit.theta == pytest.approx(theta, rel=1e-6)
        assert fit.beta == pytest.approx(beta, rel=1e-6)
    theta, beta = _probit_irls(x, e.astype(float), ones)
    assert fit.theta == pytest.approx(theta, rel=1e-9)   # two Newton-type iterations to convergence
    assert fit.beta == pytest.approx(beta, rel=1e-9)


def test_stripes_equal_the_per_analysis_fit_of_their_outcomes_up_to_the_binomial_coefficients():
    x, z, n = _stripes(np.random.default_rng(41), 12)
    stripes = fit_lognormal(x, z, n)
    xs = np.repeat(x, n)
    outcomes = np.concatenate([np.arange(k) < zk for k, zk in zip(n, z, strict=True)])
    single = fit_lognormal(xs, outcomes)
    assert stripes.theta == pytest.approx(single.theta, rel=1e-10)
    assert stripes.beta == pytest.approx(single.beta, rel=1e-10)
    log_binom = float(np.sum([math.log(math.comb(int(a), int(b))) for a, b in zip(n, z, strict=True)]))
    assert stripes.log_likelihood == pytest.approx(single.log_likelihood + log_binom, rel=1e-12)


def test_repeated_levels_pool_like_one_stripe():
    x, z, n = _stripes(np.random.default_rng(43), 20)
    pooled = fit_lognormal(x, z, n)
    half = n // 2
    z_a = np.minimum(z, half)
    split = fit_lognormal(np.concatenate([x, x]), np.concatenate([z_a, z - z_a]), np.concatenate([half, n - half]))
    assert split.theta == pytest.approx(pooled.theta, rel=1e-10)
    assert split.beta == pytest.approx(pooled.beta, rel=1e-10)


@pytest.mark.parametrize("c", [9.80665, 1 / 3.6, 100.0])
def test_im_units_scale_theta_and_leave_beta_and_the_likelihood_unchanged(c):
    x, z, n = _stripes(np.random.default_rng(51), 30)
    base, scaled = fit_lognormal(x, z, n), fit_lognormal(c * x, z, n)
    assert scaled.theta == pytest.approx(c * base.theta, rel=1e-9)
    assert scaled.beta == pytest.approx(base.beta, rel=1e-9)
    assert scaled.log_likelihood == pytest.approx(base.log_likelihood, rel=1e-12)
    xa, e = _per_analysis(np.random.default_rng(52), 200)
    base, scaled = fit_lognormal(xa, e), fit_lognormal(c * xa, e)
    assert scaled.theta == pytest.approx(c * base.theta, rel=1e-9)
    assert scaled.beta == pytest.approx(base.beta, rel=1e-9)


def test_a_steep_curve_with_little_overlap_still_converges_to_the_generic_maximum():
    """Outcomes overlapping at two neighbouring levels only (beta small): the fit is the finite maximum."""
    x = np.array([0.2, 0.3, 0.4, 0.5])
    z, n = np.array([0, 2, 8, 10]), np.array([10, 10, 10, 10])
    fit = fit_lognormal(x, z, n)
    theta, beta = _nelder_mead(x, z, n)
    assert fit.theta == pytest.approx(theta, rel=1e-6)
    assert fit.beta == pytest.approx(beta, rel=1e-5)
    assert fit.beta < 0.2


def test_nearly_separated_outcomes_converge_to_a_maximum_no_generic_search_improves():
    """240 sliding outcomes (PFA in m/s^2; 17 exceed) that overlap in a narrow band only, so the maximum
    sits at a probit slope in the thousands: the fit returns (round-off-sized Newton steps end at a
    vanishing predicted gain) and Nelder-Mead started at its answer finds no higher likelihood."""
    data = np.loadtxt(Path(__file__).parent / "data" / "fragility_nearly_separated.csv", delimiter=",",
                      skiprows=1)
    x, exceeded = data[:, 0], data[:, 1].astype(bool)
    fit = fit_lognormal(x, exceeded)
    ones = np.ones_like(x)
    z = exceeded.astype(float)
    start = [math.log(fit.theta), math.log(fit.beta)]
    best = _negative_log_likelihood(start, x, z, ones)
    assert -best == pytest.approx(fit.log_likelihood, abs=1e-9)
    res = minimize(_negative_log_likelihood, start, args=(x, z, ones), method="Nelder-Mead",
                   options={"xatol": 1e-14, "fatol": 1e-15, "maxiter": 20000})
    assert res.fun >= best - 1e-9


def test_the_result_types_are_frozen():
    fit = fit_lognormal(*_stripes(np.random.default_rng(1), 20))
    assert isinstance(fit, LognormalFit)
    with pytest.raises(AttributeError):
        fit.theta = 1.0


# ----------------------------------------------------------------------------------------------
# probability
# ----------------------------------------------------------------------------------------------

def test_probability_is_the_lognormal_cdf_and_broadcasts():
    assert probability(THETA, THETA, BETA) == 0.5
    assert probability(THETA * math.exp(BETA), THETA, BETA) == pytest.approx(norm.cdf(1.0), rel=1e-14)
    assert probability(0.0, THETA, BETA) == 0.0
    assert probability(np.inf, THETA, BETA) == 1.0
    x = np.array([0.1, 0.4, 1.0])
    got = probability(x[:, None], np.array([0.3, 0.5]), np.array([0.4, 0.6]))
    want = norm.cdf(np.log(x[:, None] / np.array([0.3, 0.5])) / np.array([0.4, 0.6]))
    assert got.shape == (3, 2)
    np.testing.assert_allclose(got, want, rtol=1e-14)
    assert np.isnan(probability(0.3, np.nan, 0.5))


@pytest.mark.parametrize("args, name", [((-0.1, 0.4, 0.5), "x"), ((0.1, 0.0, 0.5), "theta"),
                                        ((0.1, 0.4, -0.5), "beta"), ((np.array([0.1, 0.2]), 0.4, [0.5, 0.0]), "beta")])
def test_probability_rejects_out_of_range_arguments(args, name):
    with pytest.raises(ValueError, match=rf"^{name} = .* allowed range"):
        probability(*args)


# ----------------------------------------------------------------------------------------------
# errors
# ----------------------------------------------------------------------------------------------

L3 = np.array([0.1, 0.2, 0.3])


@pytest.mark.parametrize("im, exceeded, n, pattern", [
    (L3, [0, 0, 0], [5, 5, 5], r"exceeded = 0 of 15 analyses.*add higher IM levels"),
    (L3, [5, 5, 5], [5, 5, 5], r"exceeded = 15 of 15 analyses, all of them.*add lower IM levels"),
    (L3, [0, 5, 5], [5, 5, 5], r"perfectly separated.*im <= 0\.1 .*im >= 0\.2 .*beta -> 0.*between 0\.1 and 0\.2"),
    (L3, [0, 2, 5], [5, 5, 5], r"perfectly separated.*only im = 0\.2 has both outcomes.*either side of 0\.2"),
    (L3, [5, 0, 0], [5, 5, 5], r"separated by im the wrong way"),
    (L3, [4, 3, 1], [5, 5, 5], r"exceeded decreases with im"),
    (np.array([0.2, 0.2]), [1, 3], [5, 5], r"im has 1 distinct level \(0\.2\).*at least 2 distinct"),
    (np.array([0.1, 0.0, 0.3]), [0, 1, 2], [5, 5, 5], r"^im = 0\.0 at index 1 is out of range; allowed range: 0 < im"),
    (np.array([0.1, -1.0, 0.3]), [0, 1, 2], [5, 5, 5], r"^im = -1\.0 at index 1 is out of range"),
    (np.array([0.1, np.nan, 0.3]), [0, 1, 2], [5, 5, 5], r"^im = nan at index 1 is out of range"),
    (np.array([0.1, np.inf, 0.3]), [0, 1, 2], [5, 5, 5], r"^im = inf at index 1 is out of range"),
    (np.array(["a", "b"]), [0, 1], [5, 5], r"^im has dtype <U1; allowed: real numbers > 0"),
    (L3, [0, 6, 2], [5, 5, 5], r"^exceeded = 6 > n = 5 at index 1; allowed range: 0 <= exceeded <= n"),
    (L3, [0, 1, 2], [5, 0, 5], r"^n = 0 at index 1 is out of range; allowed: integer counts >= 1"),
    (L3, [0, -1, 2], [5, 5, 5], r"^exceeded = -1 at index 1 is out of range; allowed: integer counts >= 0"),
    (L3, [0, 1.5, 2], [5, 5, 5], r"^exceeded = 1\.5 at index 1 is out of range"),
    (L3, [0, 1], [5, 5, 5], r"^exceeded has shape \(2,\); allowed: the shape of im, \(3,\)"),
    (L3, [0, 1, 2], [5, 5], r"^n has shape \(2,\); allowed: the shape of im, \(3,\)"),
    (L3.reshape(3, 1), [0, 1, 2], [5, 5, 5], r"^im has shape \(3, 1\); allowed: a one-dimensional array"),
    (np.array([]), [], [], r"^im is empty"),
    (L3, [True, False, True], [5, 5, 5], r"^exceeded has dtype bool; allowed: integer counts"),
    (L3, [0, 1, 2], None, r"^exceeded = .* allowed with n=None: booleans"),
    (L3, [True, False], None, r"^exceeded has shape \(2,\); allowed: the shape of im"),
])
def test_fit_lognormal_rejects_data_that_identify_no_curve(im, exceeded, n, pattern):
    with pytest.raises(ValueError, match=pattern):
        fit_lognormal(im, np.asarray(exceeded), None if n is None else np.asarray(n))


def test_per_analysis_separation_names_the_gap_to_fill():
    x = np.array([0.1, 0.15, 0.2, 0.35, 0.5])
    with pytest.raises(ValueError, match=r"im <= 0\.2 .*im >= 0\.35 .*between 0\.2 and 0\.35"):
        fit_lognormal(x, np.array([False, False, False, True, True]))


# ----------------------------------------------------------------------------------------------
# bootstrap over records
# ----------------------------------------------------------------------------------------------

def _records(rng, n_records, sigma_record=0.3, sigma_within=0.4, draws=5, levels=LEVELS):
    """Stripe analyses of records with their own capacity shift: exceeded when ln x > ln theta +
    sigma_record eta_record + sigma_within eps; marginally lognormal with
    beta = hypot(sigma_record, sigma_within)."""
    eta = rng.normal(size=n_records)
    rec = np.repeat(np.arange(n_records), levels.size * draws)
    x = np.tile(np.repeat(levels, draws), n_records)
    cap = math.log(THETA) + sigma_record * eta[rec] + sigma_within * rng.normal(size=x.size)
    return x, np.log(x) > cap, rec


def test_bootstrap_is_deterministic_for_a_seed_and_brackets_the_fit():
    x, e, rec = _records(np.random.default_rng(61), 10)
    a = bootstrap(x, e, rec, n_boot=50, seed=3, level=0.9)
    assert a == bootstrap(x, e, rec, n_boot=50, seed=3, level=0.9)
    assert a != bootstrap(x, e, rec, n_boot=50, seed=4, level=0.9)
    assert isinstance(a, BootstrapInterval) and (a.n_boot, a.n_failed) == (50, 0)
    fit = fit_lognormal(x, e)
    assert a.theta_low < fit.theta < a.theta_high
    assert a.beta_low < fit.beta < a.beta_high
    wide = bootstrap(x, e, rec, n_boot=50, seed=3, level=0.99)
    assert wide.theta_low <= a.theta_low and wide.theta_high >= a.theta_high


def test_bootstrap_of_stripe_counts_per_record_equals_that_of_their_analyses():
    """Counts per (record, level) resample like the analyses behind them: the same fits."""
    x, e, rec = _records(np.random.default_rng(62), 8)
    key = rec * LEVELS.size + np.searchsorted(LEVELS, x)
    rows = np.unique(key)
    z = np.array([e[key == k].sum() for k in rows])
    n = np.array([(key == k).sum() for k in rows])
    counts = bootstrap(LEVELS[rows % LEVELS.size], z, rows // LEVELS.size, n, n_boot=40, seed=5, level=0.8)
    single = bootstrap(x, e, rec, n_boot=40, seed=5, level=0.8)
    for f in ("theta_low", "theta_high", "beta_low", "beta_high"):
        assert getattr(counts, f) == pytest.approx(getattr(single, f), rel=1e-9)


def test_bootstrap_counts_the_resamples_that_identify_no_curve():
    """Records "a" and "b" alone are separated (a step between im 0.2 and 0.3); only record "c" has
    outcomes that overlap in im.  A resample without "c" fails, which happens with probability
    (2/3)^3 = 8/27: n_failed is that share of 1500 resamples within 4 binomial standard deviations."""
    x = np.array([0.1, 0.2, 0.3, 0.1, 0.2, 0.3, 0.1, 0.2, 0.3, 0.3])
    e = np.array([0, 0, 1, 0, 0, 1, 0, 1, 1, 0], dtype=bool)
    groups = np.array(["a"] * 3 + ["b"] * 3 + ["c"] * 4)
    for drawn in (["c"], ["a", "c"], ["b", "b", "c"]):       # every resample holding "c" is identified
        idx = np.concatenate([np.flatnonzero(groups == g) for g in drawn])
        fit_lognormal(x[idx], e[idx])
    with pytest.raises(ValueError, match="perfectly separated"):
        fit_lognormal(x[:6], e[:6])
    res = bootstrap(x, e, groups, n_boot=1500, seed=9, level=0.9)
    p = 8 / 27
    assert abs(res.n_failed - 1500 * p) < 4 * math.sqrt(1500 * p * (1 - p))
    assert res.n_boot == 1500


@pytest.mark.parametrize("kwargs, pattern", [
    ({"n_boot": 0, "seed": 1, "level": 0.9}, r"^n_boot = 0 is out of range; allowed: integers >= 1"),
    ({"n_boot": 2.5, "seed": 1, "level": 0.9}, r"^n_boot = 2\.5 is out of range"),
    ({"n_boot": 5, "seed": -1, "level": 0.9}, r"^seed = -1 is out of range; allowed: integers >= 0"),
    ({"n_boot": 5, "seed": 1, "level": 1.0}, r"^level = 1\.0 is out of range; allowed range: 0 < level < 1"),
    ({"n_boot": 5, "seed": 1, "level": 0.0}, r"^level = 0\.0 is out of range"),
])
def test_bootstrap_rejects_settings_out_of_range(kwargs, pattern):
    x, e, rec = _records(np.random.default_rng(63), 4)
    with pytest.raises(ValueError, match=pattern):
        bootstrap(x, e, rec, **kwargs)


def test_bootstrap_rejects_groups_of_another_shape_or_a_single_group():
    x, e, rec = _records(np.random.default_rng(64), 4)
    with pytest.raises(ValueError, match=r"^groups has shape \(3,\); allowed: the shape of im"):
        bootstrap(x, e, rec[:3], n_boot=5, seed=1, level=0.9)
    with pytest.raises(ValueError, match=r"^groups has 1 distinct value \(0\); allowed: at least 2 groups"):
        bootstrap(x, e, np.zeros_like(rec), n_boot=5, seed=1, level=0.9)


def test_bootstrap_says_so_when_no_resample_identifies_a_curve():
    x = np.array([0.1, 0.2, 0.1, 0.2])
    e = np.array([False, True, False, True])
    with pytest.raises(ValueError, match=r"none of the resamples identifies a curve \(all 20 failed\)"):
        bootstrap(x, e, np.array([0, 0, 1, 1]), n_boot=20, seed=1, level=0.9)


def _coverage(groups_of, experiments=60, n_records=12, n_boot=100):
    rng = np.random.default_rng(2026)
    beta_true = math.hypot(0.3, 0.4)
    hits = np.zeros(2)
    for k in range(experiments):
        x, e, rec = _records(rng, n_records)
        b = bootstrap(x, e, groups_of(rec), n_boot=n_boot, seed=k, level=0.9)
        hits += [b.theta_low <= THETA <= b.theta_high, b.beta_low <= beta_true <= b.beta_high]
    return hits / experiments


@pytest.mark.slow
def test_record_bootstrap_covers_the_truth_about_as_often_as_its_level_and_the_analysis_bootstrap_does_not():
    """60 experiments of 12 records with a record-to-record capacity shift (sigma 0.3 next to 0.4
    within a record): the 90 % interval from resampling records contains the true theta and beta
    in 75-99 % of them; resampling single analyses ignores that records cluster and covers theta
    clearly less often."""
    records = _coverage(lambda rec: rec)
    analyses = _coverage(lambda rec: np.arange(rec.size))
    assert np.all((records >= 0.75) & (records <= 0.99)), records
    assert analyses[0] < records[0] - 0.15, (analyses, records)
