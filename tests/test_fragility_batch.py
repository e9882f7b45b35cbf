"""isoslide.studies.fragility: many fits at once (fit_weighted) and the bootstrap built on it, against
fit_lognormal fit by fit."""

import math

import numpy as np
import pytest

from isoslide.studies.fragility import (FITTED, NOT_CONVERGED, UNIDENTIFIED, bootstrap, draw_groups, fit_lognormal,
                                        fit_weighted, probability, times_drawn)

RTOL = 1e-10

RAISES = {UNIDENTIFIED: ValueError, NOT_CONVERGED: RuntimeError}
"""The error fit_lognormal raises where fit_weighted reports each failed outcome."""


def _overflows(x, z, n):
    """fit_lognormal of ``(x, z, n)`` overflows (not another of its failures)."""
    try:
        fit_lognormal(x, z, n)
    except OverflowError:
        return True
    except (ValueError, RuntimeError):   # no curve, or no convergence: a failure of another kind
        pass
    return False


def _dataset(rng, kind):
    """``(x, z, n)`` of one random dataset: stripes, per analysis, or nearly separated per analysis."""
    theta = math.exp(rng.normal(0.0, 0.5))
    if kind == "stripes":
        x = theta * np.exp(np.linspace(-1.0, 1.0, rng.integers(2, 9)) * rng.uniform(0.3, 1.2))
        n = rng.integers(1, 8, x.size).astype(float)
        z = rng.binomial(n.astype(int), probability(x, theta, rng.uniform(0.1, 0.8))).astype(float)
        return x, z, n
    beta = rng.uniform(0.005, 0.05) if kind == "near" else rng.uniform(0.1, 0.8)
    x = theta * np.exp(rng.normal(0.0, 0.6, rng.integers(4, 60)))
    z = (rng.random(x.size) < probability(x, theta, beta)).astype(float)
    return x, z, np.ones(x.size)


def _repeated(x, w, z, n, i):
    idx = np.repeat(np.arange(x.size), w[i].astype(int))
    return x[idx], z[idx], n[idx]


def _assert_same_fits(got, x, w, z, n):
    """Each fit of ``got`` (fit_weighted) is fit_lognormal of its entries repeated ``w`` times: the
    same curve where it fits one, its error where it fails (and NaN for the curve)."""
    for i in range(w.shape[0]):
        entries = _repeated(x, w, z, n, i)
        values = [g[i] for g in got[:3]]
        if got[3][i] == FITTED:
            fit = fit_lognormal(*entries)
            np.testing.assert_allclose(values, [fit.theta, fit.beta, fit.log_likelihood], rtol=RTOL)
        else:
            assert got[3][i] in RAISES
            with pytest.raises(RAISES[got[3][i]]):
                fit_lognormal(*entries)
            assert np.isnan(values).all()


@pytest.mark.parametrize("kind", ["stripes", "per analysis", "near"])
def test_weighted_fits_are_fit_lognormal_fit_by_fit(kind):
    rng = np.random.default_rng(7)
    outcomes = set()
    for _ in range(40):
        x, z, n = _dataset(rng, kind)
        w = rng.integers(0, 3, (25, x.size)).astype(float)
        w[0] = 1.0                                   # every entry once: the data themselves
        try:
            got = fit_weighted(x, w, z, n)
        except OverflowError:        # a flat fraction exceeded: theta overflows, as in fit_lognormal
            assert any(_overflows(*_repeated(x, w, z, n, i)) for i in range(w.shape[0]))
            continue
        _assert_same_fits(got, x, w, z, n)
        outcomes |= set(got[3].tolist())
    assert outcomes == {FITTED, UNIDENTIFIED}       # fits and failures both met


def test_each_way_a_fit_fails_is_the_failure_of_fit_lognormal():
    x = np.array([1.0, 2.0, 3.0, 4.0])
    cases = {
        "one level": ([1, 0, 0, 0], [1, 0, 1, 0]),
        "none exceeded": ([1, 1, 1, 1], [0, 0, 0, 0]),
        "all exceeded": ([1, 1, 1, 1], [1, 1, 1, 1]),
        "separated": ([1, 1, 1, 1], [0, 0, 1, 1]),
        "separated at one level": ([1, 2, 1, 1], [0, 0.5, 1, 1]),
        "decreasing": ([1, 1, 1, 1], [1, 1, 0, 0]),
        "decreasing, overlapping": ([1, 1, 1, 1], [1, 0, 1, 0]),
        "overlapping": ([1, 1, 1, 1], [0, 1, 0, 1]),
    }
    w = np.array([c[0] for c in cases.values()], dtype=float)
    n = np.full(x.size, 2.0)
    for i, (name, (_, f)) in enumerate(cases.items()):
        z = np.asarray(f) * n
        got = fit_weighted(x, w[i:i + 1], z, n)
        _assert_same_fits(got, x, w[i:i + 1], z, n)
        assert (got[3][0] == FITTED) == (name == "overlapping"), name


def test_a_flat_fraction_fails_as_fit_lognormal_fails():
    """The slope is zero but for round-off: fit_lognormal's outcome (here an overflowing theta) is kept."""
    x, z, n = np.array([1.0, 2.0, 3.0]), np.array([3.0, 3.0, 3.0]), np.array([7.0, 7.0, 7.0])
    with pytest.raises(OverflowError):
        fit_lognormal(x, z, n)
    with pytest.raises(OverflowError):
        fit_weighted(x, np.ones((2, 3)), z, n)


def test_per_fit_im_and_counts_and_a_fit_of_nothing():
    rng = np.random.default_rng(3)
    x = np.exp(rng.normal(0.0, 0.6, (4, 30)))
    z = (rng.random(x.shape) < probability(x, 1.0, 0.4)).astype(float)
    n = np.ones(x.shape)
    w = rng.integers(0, 3, x.shape).astype(float)
    w[-1] = 0.0
    got = fit_weighted(x, w, z, n)
    for i in range(w.shape[0]):
        _assert_same_fits(tuple(g[i:i + 1] for g in got), x[i], w[i:i + 1], z[i], n[i])
    assert got[3][-1] == UNIDENTIFIED


def test_the_fits_do_not_depend_on_the_batch_and_repeat_to_the_bit():
    rng = np.random.default_rng(11)
    x, z, n = _dataset(rng, "per analysis")
    w = rng.integers(0, 4, (30, x.size)).astype(float)
    all_at_once = fit_weighted(x, w, z, n)
    for a, b in zip(all_at_once, fit_weighted(x, w, z, n), strict=True):
        assert a.tobytes() == b.tobytes()
    one_by_one = [fit_weighted(x, w[i:i + 1], z, n) for i in range(w.shape[0])]
    for k in range(4):
        np.testing.assert_allclose(all_at_once[k], np.concatenate([o[k] for o in one_by_one]), rtol=1e-13)


def _bootstrap_loop(im, exceeded, groups, n, *, n_boot, seed, level):
    """The bootstrap written out: one fit_lognormal per resample of the groups, in the order drawn."""
    x = np.asarray(im, dtype=float)
    z = np.asarray(exceeded, dtype=float)
    nn = np.ones(x.size) if n is None else np.asarray(n, dtype=float)
    labels, code = np.unique(np.asarray(groups), return_inverse=True)
    members = [np.flatnonzero(code == i) for i in range(labels.size)]
    rng = np.random.default_rng(seed)
    thetas, betas, n_failed = [], [], 0
    for _ in range(n_boot):
        idx = np.concatenate([members[i] for i in rng.integers(0, labels.size, size=labels.size)])
        try:
            fit = fit_lognormal(x[idx], z[idx], nn[idx])
        except ValueError:
            n_failed += 1
            continue
        thetas.append(fit.theta)
        betas.append(fit.beta)
    q = [(1.0 - level) / 2.0, (1.0 + level) / 2.0]
    return (*np.quantile(thetas, q), *np.quantile(betas, q), n_failed)


def _grouped(rng, kind):
    """A dataset with its records: stripes per record, or per analysis with a record of each."""
    if kind == "stripes":
        levels = np.array([0.2, 0.4, 0.6, 0.9, 1.3])
        n_rec = rng.integers(3, 9)
        x = np.tile(levels, n_rec)
        n = rng.integers(1, 4, x.size).astype(float)
        z = rng.binomial(n.astype(int), probability(x, 0.6, rng.uniform(0.2, 0.6))).astype(float)
        return x, z, np.repeat(np.arange(n_rec), levels.size), n
    beta = rng.uniform(0.01, 0.05) if kind == "near" else rng.uniform(0.2, 0.6)
    x = np.exp(rng.normal(0.0, 0.5, rng.integers(10, 60)))
    z = rng.random(x.size) < probability(x, 1.0, beta)
    return x, z, rng.integers(0, rng.integers(3, 10), x.size).astype(str), None


@pytest.mark.parametrize("kind", ["stripes", "per analysis", "near"])
def test_bootstrap_is_the_loop_over_fit_lognormal(kind):
    rng = np.random.default_rng(5)
    failed = 0
    for trial in range(12):
        x, z, groups, n = _grouped(rng, kind)
        try:
            want = _bootstrap_loop(x, z, groups, n, n_boot=60, seed=trial, level=0.9)
        except (ValueError, IndexError):   # no resample identifies a curve: the bootstrap refuses too
            with pytest.raises(ValueError, match="none of the resamples"):
                bootstrap(x, z, groups, n, n_boot=60, seed=trial, level=0.9)
            continue
        got = bootstrap(x, z, groups, n, n_boot=60, seed=trial, level=0.9)
        assert got.n_failed == want[4] and got.n_boot == 60
        np.testing.assert_allclose([got.theta_low, got.theta_high, got.beta_low, got.beta_high], want[:4],
                                   rtol=RTOL)
        failed += got.n_failed
    assert failed > 0


def test_draws_are_the_resamples_in_order_and_counted():
    rng = np.random.default_rng(9)
    draws = draw_groups(5, 3, 9)
    np.testing.assert_array_equal(draws, [rng.integers(0, 5, size=5) for _ in range(3)])
    counts = times_drawn(draws, 5)
    assert counts.shape == (3, 5) and np.all(counts.sum(axis=1) == 5)
    np.testing.assert_array_equal(counts[1], np.bincount(draws[1], minlength=5))
