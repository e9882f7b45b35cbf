"""Lognormal fragility curves fitted by maximum likelihood (Baker 2015), with a bootstrap over records.

A fragility curve is ``P(EDP > limit | IM = x) = Phi(ln(x / theta) / beta)``: ``theta`` the median
capacity (IM units), ``beta`` the dispersion (-).  The fit maximises the likelihood of the observed
outcomes, not a least-squares fit of fractions (Baker, J. W. 2015, Earthquake Spectra 31(1),
"Efficient analytical fragility function fitting using dynamic structural analysis"):

* **stripes** (records scaled to levels ``x_j``, ``n_j`` analyses, ``z_j`` exceedances):
  ``L = prod_j C(n_j, z_j) p_j^z_j (1 - p_j)^(n_j - z_j)``, ``p_j = Phi(ln(x_j / theta) / beta)``;
* **per analysis** (a continuous IM of each analysis, e.g. the floor's own peak velocity): one
  Bernoulli term per analysis, a probit regression on ``ln x``.

Both are the probit model ``p = Phi(a + b ln x)`` with ``theta = exp(-a / b)``, ``beta = 1 / b``.
Its log-likelihood is concave in ``(a, b)`` (``ln Phi`` is log-concave), so Newton's method with a
step-halving line search, started from a moment estimate and run on the standardised ``ln x``,
converges to the unique maximum whenever one exists.  It does not exist when the outcomes are
separated by the IM (every analysis below some level survives, every one above it exceeds): the
likelihood then grows without bound as ``beta -> 0``.  :func:`fit_lognormal` detects that before
fitting and says which analyses would identify a curve.

Many fits of the same entries, each entry repeated its own number of times (the bootstrap's
resamples of records), run at once in :func:`fit_weighted`: the same checks and Newton iteration,
vectorised over the fits, each with its own convergence tests and step halving; a fit whose
outcome hinges on round-off is redone by :func:`fit_lognormal` itself.

The module holds science only (no I/O, no configuration defaults): the bootstrap's ``n_boot``,
``level`` and ``seed`` come from ``fragility.bootstrap`` and ``fragility.seed`` in
``config/schema.yaml``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.special import gammaln, log_ndtr, ndtr, ndtri

__all__ = ["BootstrapInterval", "LognormalFit", "bootstrap", "draw_groups", "fit_lognormal", "fit_weighted",
           "probability", "times_drawn"]

_LOG_SQRT_2PI = 0.5 * math.log(2.0 * math.pi)
_MAX_NEWTON = 200
_STEP_TOL = 1e-12   # Newton stops when no (standardised) parameter moves by more than this
_DECREMENT_TOL = 1e-20  # ... or when the predicted gain g.H^-1.g is below this times (1 + |log L|)


@dataclass(frozen=True)
class LognormalFit:
    """A maximum-likelihood lognormal fragility curve ``P = Phi(ln(x / theta) / beta)``.

    Attributes
    ----------
    theta : float
        Median capacity, in the units of the IM it was fitted on (e.g. m/s^2, m/s).
    beta : float
        Lognormal dispersion (standard deviation of ``ln`` capacity), dimensionless, > 0.
    n_analyses : int
        Analyses in the fit (sum of ``n_j`` for stripes).
    n_exceeded : int
        Analyses that exceeded the limit state.
    log_likelihood : float
        Maximised log-likelihood, binomial coefficients ``ln C(n_j, z_j)`` included (zero per
        analysis).
    """

    theta: float
    beta: float
    n_analyses: int
    n_exceeded: int
    log_likelihood: float


@dataclass(frozen=True)
class BootstrapInterval:
    """Percentile bootstrap interval of ``theta`` and ``beta`` (records resampled).

    Attributes
    ----------
    theta_low, theta_high : float
        Bounds of the interval of the median, IM units.
    beta_low, beta_high : float
        Bounds of the interval of the dispersion, dimensionless.
    n_boot : int
        Resamples drawn (failed ones included).
    n_failed : int
        Resamples that could not identify a curve (none or every analysis exceeded, separated
        outcomes, fewer than two IM levels); the bounds are percentiles of the other
        ``n_boot - n_failed`` fits.
    """

    theta_low: float
    theta_high: float
    beta_low: float
    beta_high: float
    n_boot: int
    n_failed: int


# ----------------------------------------------------------------------------------------------
# input checks
# ----------------------------------------------------------------------------------------------

def _shape_text(a: np.ndarray) -> str:
    return f"shape {a.shape}"


def _as_1d(name: str, value) -> np.ndarray:
    arr = np.asarray(value)
    if arr.ndim != 1:
        raise ValueError(f"{name} has {_shape_text(arr)}; allowed: a one-dimensional array")
    if arr.size == 0:
        raise ValueError(f"{name} is empty ({_shape_text(arr)}); allowed: at least 2 values")
    return arr


def _first_bad(arr: np.ndarray, bad: np.ndarray) -> str:
    i = int(np.flatnonzero(bad)[0])
    return f"{arr[i].item()!r} at index {i}"


def _check_im(im) -> np.ndarray:
    x = _as_1d("im", im)
    if not (np.issubdtype(x.dtype, np.number) and not np.issubdtype(x.dtype, np.complexfloating)):
        raise ValueError(f"im has dtype {x.dtype}; allowed: real numbers > 0")
    x = x.astype(float)
    bad = ~np.isfinite(x) | (x <= 0.0)
    if bad.any():
        raise ValueError(f"im = {_first_bad(x, bad)} is out of range; allowed range: 0 < im < inf (finite)")
    return x


def _check_counts(name: str, value, shape: tuple) -> np.ndarray:
    arr = np.asarray(value)
    if arr.shape != shape:
        raise ValueError(f"{name} has {_shape_text(arr)}; allowed: the shape of im, {shape}")
    if arr.dtype == bool or not np.issubdtype(arr.dtype, np.number):
        raise ValueError(f"{name} has dtype {arr.dtype}; allowed: integer counts")
    f = arr.astype(float)
    bad = ~np.isfinite(f) | (f != np.round(f)) | (f < 0)
    if bad.any():
        raise ValueError(f"{name} = {_first_bad(arr, bad)} is out of range; allowed: integer counts >= 0")
    return f


def _prepare(im, exceeded, n) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Checked ``(x, z, n)`` as float arrays: IM levels, exceedances, analyses."""
    x = _check_im(im)
    if n is None:
        e = np.asarray(exceeded)
        if e.shape != x.shape:
            raise ValueError(f"exceeded has {_shape_text(e)}; allowed: the shape of im, {x.shape}")
        if e.dtype != bool:
            ok = np.issubdtype(e.dtype, np.number) and bool(np.all((e == 0) | (e == 1)))
            if not ok:
                raise ValueError(f"exceeded = {e!r} is invalid; allowed with n=None: booleans (one outcome "
                                 "per analysis), or pass the analyses per level as n")
        z = e.astype(float)
        nn = np.ones_like(x)
    else:
        z = _check_counts("exceeded", exceeded, x.shape)
        nn = _check_counts("n", n, x.shape)
        if (nn < 1).any():
            raise ValueError(f"n = {_first_bad(nn.astype(int), nn < 1)} is out of range; allowed: "
                             "integer counts >= 1 (analyses per IM level)")
        over = z > nn
        if over.any():
            i = int(np.flatnonzero(over)[0])
            raise ValueError(f"exceeded = {int(z[i])} > n = {int(nn[i])} at index {i}; allowed range: "
                             "0 <= exceeded <= n")
    return x, z, nn


def _check_identifiable(x: np.ndarray, z: np.ndarray, n: np.ndarray) -> None:
    """ValueError unless the data identify a finite ``theta`` and ``beta > 0``."""
    total, hits = float(n.sum()), float(z.sum())
    levels = np.unique(x)
    if levels.size < 2:
        raise ValueError(f"im has {levels.size} distinct level ({levels[0].item()!r}); allowed: at least 2 "
                         "distinct IM levels (one level cannot identify both theta and beta)")
    if hits == 0:
        raise ValueError(f"exceeded = 0 of {int(total)} analyses; allowed: 0 < exceeded < analyses (no "
                         "analysis exceeded the limit state: add higher IM levels or a lower limit)")
    if hits == total:
        raise ValueError(f"exceeded = {int(hits)} of {int(total)} analyses, all of them; allowed: 0 < exceeded "
                         "< analyses (every analysis exceeded the limit state: add lower IM levels or a "
                         "higher limit)")
    survived = n - z > 0
    hit = z > 0
    lo_surv, hi_surv = float(x[survived].min()), float(x[survived].max())
    lo_hit, hi_hit = float(x[hit].min()), float(x[hit].max())
    if hi_surv <= lo_hit:
        if hi_surv < lo_hit:
            what = (f"every analysis at im <= {hi_surv:g} is below the limit state and every one at "
                    f"im >= {lo_hit:g} exceeds it")
            fix = f"analyses at IM levels between {hi_surv:g} and {lo_hit:g}"
        else:
            what = (f"every analysis at im < {hi_surv:g} is below the limit state, every one at im > "
                    f"{hi_surv:g} exceeds it, and only im = {hi_surv:g} has both outcomes")
            fix = f"analyses at IM levels on either side of {hi_surv:g}"
        raise ValueError(
            f"exceeded is perfectly separated by im: {what}, so the likelihood grows without bound as "
            f"beta -> 0 (a step) and no lognormal curve is identified; allowed: outcomes that overlap in "
            f"im. Fix: {fix} (more stripes there, or more records or friction draws whose outcomes "
            f"differ at the same IM)")
    if hi_hit <= lo_surv:
        raise ValueError(
            f"exceeded is separated by im the wrong way: every analysis at im <= {hi_hit:g} exceeds the limit "
            f"state and every one at im >= {lo_surv:g} is below it; allowed: a fraction exceeded that grows "
            f"with the IM (a fragility curve)")


# ----------------------------------------------------------------------------------------------
# the probit likelihood, its gradient and Hessian
# ----------------------------------------------------------------------------------------------

def _log_terms(z, m, lp, lm):
    """``z ln Phi(eta) + m ln Phi(-eta)`` per entry from ``lp = ln Phi(eta)``, ``lm = ln Phi(-eta)``; zero counts add 0."""
    return np.where(z > 0, z * lp, 0.0) + np.where(m > 0, m * lm, 0.0)


def _loglik_terms(eta: np.ndarray, z: np.ndarray, n: np.ndarray) -> float:
    """``sum z ln Phi(eta) + (n - z) ln Phi(-eta)`` (no binomial coefficients); zero counts add 0."""
    return float(np.sum(_log_terms(z, n - z, log_ndtr(eta), log_ndtr(-eta))))


def _slopes(eta, z, m, lp, lm):
    """First derivative and minus the second derivative of the log-likelihood terms w.r.t. ``eta``.

    ``z``, ``m``: exceedances and survivals; ``lp``, ``lm``: ``ln Phi(eta)``, ``ln Phi(-eta)``.
    """
    log_pdf = -0.5 * eta * eta - _LOG_SQRT_2PI
    r1 = np.exp(log_pdf - lp)     # phi / Phi(eta)
    r0 = np.exp(log_pdf - lm)     # phi / Phi(-eta)
    d1 = z * r1 - m * r0
    w = z * r1 * (eta + r1) + m * r0 * (r0 - eta)   # >= 0: the log-likelihood is concave in eta
    return d1, w


def _derivatives(eta: np.ndarray, z: np.ndarray, n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """First derivative and minus the second derivative of the log-likelihood terms w.r.t. ``eta``."""
    return _slopes(eta, z, n - z, log_ndtr(eta), log_ndtr(-eta))


def _start(t: np.ndarray, z: np.ndarray, n: np.ndarray) -> np.ndarray:
    """Moment estimate of the standardised probit ``(a, b)``.

    A linear-probability fit ``z/n ~ c0 + c1 t`` (weights ``n``) linearised around the mean fraction,
    ``Phi(a + b t) ~ Phi(a) + phi(a) b t``.
    """
    total = n.sum()
    pbar = z.sum() / total
    tm = (n * t).sum() / total
    var = (n * (t - tm) ** 2).sum() / total
    c1 = (n * (t - tm) * (z / n - pbar)).sum() / total / var
    a0 = float(ndtri(np.clip(pbar, 1e-6, 1.0 - 1e-6)))
    dens = math.exp(-0.5 * a0 * a0) / math.sqrt(2.0 * math.pi)
    b0 = float(np.clip(c1 / dens, 0.05, 20.0))
    return np.array([a0 - b0 * tm, b0])


def _newton(t: np.ndarray, z: np.ndarray, n: np.ndarray) -> tuple[np.ndarray, float]:
    """Maximise the probit log-likelihood in ``(a, b)``, ``eta = a + b t``.

    Returns the maximiser and the maximum (binomial coefficients left out).
    """
    p = _start(t, z, n)
    f = _loglik_terms(p[0] + p[1] * t, z, n)
    for _ in range(_MAX_NEWTON):
        eta = p[0] + p[1] * t
        d1, w = _derivatives(eta, z, n)
        g = np.array([d1.sum(), (d1 * t).sum()])
        h = np.array([[w.sum(), (w * t).sum()], [(w * t).sum(), (w * t * t).sum()]])
        step = np.linalg.solve(h, g)
        if float(g @ step) <= _DECREMENT_TOL * (1.0 + abs(f)):
            # converged in the log-likelihood: near-separated data (a very small beta) leave steps
            # of round-off size, ~1e-16 of parameters in the thousands, that the step test never meets
            return p, f
        scale = 1.0
        while True:
            q = p + scale * step
            fq = _loglik_terms(q[0] + q[1] * t, z, n)
            if fq >= f - 1e-12 * abs(f) or scale < 1e-10:
                break
            scale *= 0.5
        p, f = q, fq
        if np.max(np.abs(scale * step)) <= _STEP_TOL * (1.0 + np.max(np.abs(p))):
            return p, f
    raise RuntimeError(f"fit_lognormal: Newton's method did not converge in {_MAX_NEWTON} iterations "
                       f"(last step {scale * step}, parameters {p})")


# ----------------------------------------------------------------------------------------------
# many fits at once (the bootstrap): one Newton iteration over every fit still running
# ----------------------------------------------------------------------------------------------

FITTED, UNIDENTIFIED, NOT_CONVERGED = 0, 1, 2
"""Outcomes of :func:`fit_weighted`: a curve; what :func:`fit_lognormal` rejects with ValueError
(no curve identified, a decreasing fraction, a singular Newton system); its RuntimeError."""
_UNSTABLE = 3   # an outcome that hinges on round-off: the fit is redone one by one

_NEAR_SINGULAR = 1e-8
"""A Newton system whose determinant is below this fraction of the product of its diagonal terms
is near singular (the weights of all but one IM level underflow): whether it turns exactly
singular, and :func:`fit_lognormal` fails, hinges on round-off."""

_FLAT = 1e-8
"""A maximum-likelihood slope ``b`` (of the standardised ``ln x``) below this in magnitude is a flat
fraction exceeded: its sign, and whether :func:`fit_lognormal` fits a curve, hinges on round-off."""

_BATCH_ENTRIES = 1 << 20   # fits of one pass of fit_weighted: at most this many (fit, entry) pairs


def _low(x: np.ndarray, mask: np.ndarray) -> np.ndarray:
    return np.where(mask, x, np.inf).min(axis=-1)


def _high(x: np.ndarray, mask: np.ndarray) -> np.ndarray:
    return np.where(mask, x, -np.inf).max(axis=-1)


def _identifiable(x: np.ndarray, w: np.ndarray, z: np.ndarray, n: np.ndarray) -> np.ndarray:
    """Per fit, whether :func:`_check_identifiable` accepts the entries repeated ``w`` times.

    Two distinct IM levels, some but not all analyses exceeded, outcomes that overlap in the IM in
    the increasing direction (neither separated nor reversed).
    """
    on = w > 0
    hits, total = (w * z).sum(axis=-1), (w * n).sum(axis=-1)
    survived, hit = on & (n - z > 0), on & (z > 0)
    return ((_high(x, on) > _low(x, on)) & (hits > 0) & (hits < total)
            & (_high(x, survived) > _low(x, hit)) & (_high(x, hit) > _low(x, survived)))


def _standardised(x: np.ndarray, w: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(t, centre, spread)``: ``ln x`` standardised with the mean and deviation over the entries repeated ``w`` times."""
    lx = np.log(x)
    total = w.sum(axis=-1, keepdims=True)
    centre = (w * lx).sum(axis=-1, keepdims=True) / total
    spread = np.sqrt((w * (lx - centre) ** 2).sum(axis=-1, keepdims=True) / total)
    return (lx - centre) / spread, centre[:, 0], spread[:, 0]


def _starts(t: np.ndarray, z: np.ndarray, m: np.ndarray) -> np.ndarray:
    """:func:`_start` of every fit, shape ``(fits, 2)``: ``z``, ``m`` exceedances and survivals (weighted)."""
    n = z + m
    total = n.sum(axis=-1)
    pbar = z.sum(axis=-1) / total
    tm = (n * t).sum(axis=-1) / total
    dt = t - tm[:, None]
    var = (n * dt * dt).sum(axis=-1) / total
    c1 = (dt * (z - n * pbar[:, None])).sum(axis=-1) / total / var
    a0 = ndtri(np.clip(pbar, 1e-6, 1.0 - 1e-6))
    dens = np.exp(-0.5 * a0 * a0) / math.sqrt(2.0 * math.pi)
    b0 = np.clip(c1 / dens, 0.05, 20.0)
    return np.stack([a0 - b0 * tm, b0], axis=-1)


class _Running:
    """The fits still iterating: their data, parameters, log-likelihood and ``ln Phi(+-eta)``.

    ``ln Phi(eta)`` is evaluated only where an entry has exceedances and ``ln Phi(-eta)`` only
    where it has survivals (0 elsewhere, where its count is 0): one outcome per analysis, or an
    entry not drawn, needs one of them or none.
    """

    def __init__(self, t, z, m, p):
        self.index = np.arange(t.shape[0])
        self.t, self.z, self.m, self.p = t, z, m, p
        self.hit, self.survived = z > 0, m > 0
        self.f, self.lp, self.lm = self.evaluate(p, slice(None))

    def evaluate(self, p: np.ndarray, rows) -> tuple:
        """Log-likelihood terms, ``ln Phi(eta)`` and ``ln Phi(-eta)`` at parameters ``p`` of the fits ``rows``."""
        eta = p[:, :1] + p[:, 1:] * self.t[rows]
        lp, lm = np.zeros_like(eta), np.zeros_like(eta)
        hit, survived = self.hit[rows], self.survived[rows]
        lp[hit] = log_ndtr(eta[hit])
        lm[survived] = log_ndtr(-eta[survived])
        return _log_terms(self.z[rows], self.m[rows], lp, lm).sum(axis=-1), lp, lm

    def keep(self, rows: np.ndarray) -> None:
        """Go on with the fits ``rows`` only."""
        for name in ("index", "t", "z", "m", "hit", "survived", "p", "f", "lp", "lm"):
            setattr(self, name, getattr(self, name)[rows])


def _newton_steps(r: _Running) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The Newton step of every running fit (closed-form 2x2 solve), its predicted gain and relative determinant.

    The relative determinant is ``det H / (H_aa H_bb)``, 1 minus the squared correlation of ``t``
    under the Hessian's weights: 0 for a singular system.
    """
    eta = r.p[:, :1] + r.p[:, 1:] * r.t
    d1, w = _slopes(eta, r.z, r.m, r.lp, r.lm)
    g0, g1 = d1.sum(axis=-1), (d1 * r.t).sum(axis=-1)
    wt = w * r.t
    h00, h01, h11 = w.sum(axis=-1), wt.sum(axis=-1), (wt * r.t).sum(axis=-1)
    det = h00 * h11 - h01 * h01
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        step = np.stack([(h11 * g0 - h01 * g1) / det, (h00 * g1 - h01 * g0) / det], axis=-1)
        return step, g0 * step[:, 0] + g1 * step[:, 1], det / (h00 * h11)


def _line_search(r: _Running, step: np.ndarray) -> tuple:
    """Step halving of :func:`_newton` for every running fit: ``(scale, q, f, lp, lm)`` accepted."""
    scale = np.ones(step.shape[0])
    q = r.p + step
    f, lp, lm = r.evaluate(q, slice(None))
    short = ~((f >= r.f - 1e-12 * np.abs(r.f)) | (scale < 1e-10))
    while short.any():
        rows = np.flatnonzero(short)
        scale[rows] *= 0.5
        q[rows] = r.p[rows] + scale[rows, None] * step[rows]
        f[rows], lp[rows], lm[rows] = r.evaluate(q[rows], rows)
        short[rows] = ~((f[rows] >= r.f[rows] - 1e-12 * np.abs(r.f[rows])) | (scale[rows] < 1e-10))
    return scale, q, f, lp, lm


def _newton_many(t: np.ndarray, z: np.ndarray, m: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`_newton` of every fit at once, with its own convergence tests and step halving.

    Parameters
    ----------
    t : numpy.ndarray, shape (fits, k)
        Standardised ``ln`` IM.
    z, m : numpy.ndarray, shape (fits, k)
        Exceedances and survivals (weighted counts).

    Returns
    -------
    p : numpy.ndarray, shape (fits, 2)
        The maximisers ``(a, b)``.
    f : numpy.ndarray, shape (fits,)
        The maxima (binomial coefficients left out).
    outcome : numpy.ndarray of int, shape (fits,)
        ``FITTED``, ``NOT_CONVERGED``, or ``_UNSTABLE`` for a near singular or non-finite Newton
        system (``_NEAR_SINGULAR``).
    """
    r = _Running(t, z, m, _starts(t, z, m))
    p_out, f_out = np.full((t.shape[0], 2), np.nan), np.full(t.shape[0], np.nan)
    outcome = np.full(t.shape[0], NOT_CONVERGED, dtype=np.int8)
    for _ in range(_MAX_NEWTON):
        step, gain, det = _newton_steps(r)
        singular = ~(det > _NEAR_SINGULAR) | ~np.isfinite(gain)
        done = ~singular & (gain <= _DECREMENT_TOL * (1.0 + np.abs(r.f)))
        outcome[r.index[singular]] = _UNSTABLE
        p_out[r.index[done]], f_out[r.index[done]], outcome[r.index[done]] = r.p[done], r.f[done], FITTED
        go = np.flatnonzero(~(done | singular))
        r.keep(go)
        step = step[go]
        if not go.size:
            break
        scale, r.p, r.f, r.lp, r.lm = _line_search(r, step)
        moved = np.max(np.abs(scale[:, None] * step), axis=-1)
        done = moved <= _STEP_TOL * (1.0 + np.max(np.abs(r.p), axis=-1))
        p_out[r.index[done]], f_out[r.index[done]], outcome[r.index[done]] = r.p[done], r.f[done], FITTED
        r.keep(np.flatnonzero(~done))
        if not r.index.size:
            break
    return p_out, f_out, outcome


def _compacted(x: np.ndarray, w: np.ndarray, z: np.ndarray, n: np.ndarray) -> tuple:
    """The entries of each fit with ``w > 0`` first, in order, and no more columns than the fit with most of them."""
    order = np.argsort(w == 0.0, axis=-1, kind="stable")
    width = int((w > 0).sum(axis=-1).max())
    if width == w.shape[-1]:
        return x, w, z, n
    return tuple(np.take_along_axis(a, order[:, :width], axis=-1) for a in (x, w, z, n))


def _fit_pass(x: np.ndarray, w: np.ndarray, z: np.ndarray, n: np.ndarray) -> tuple:
    """:func:`fit_weighted` of fits few enough for one pass."""
    x, z, n = (np.broadcast_to(a, w.shape) for a in (x, z, n))
    theta, beta, ll = (np.full(w.shape[0], np.nan) for _ in range(3))
    outcome = np.full(w.shape[0], UNIDENTIFIED, dtype=np.int8)
    rows = np.flatnonzero(_identifiable(x, w, z, n))
    if not rows.size:
        return theta, beta, ll, outcome
    x, w, z, n = _compacted(x[rows], w[rows], z[rows], n[rows])
    t, centre, spread = _standardised(x, w)
    p, f, fitted = _newton_many(t, w * z, w * (n - z))
    a, b = p[:, 0], p[:, 1]
    fitted[(fitted == FITTED) & (np.abs(b) < _FLAT)] = _UNSTABLE
    fitted[(fitted == FITTED) & ~(b > 0.0)] = UNIDENTIFIED    # a fraction that decreases with the IM
    ok = fitted == FITTED
    outcome[rows] = fitted
    binomial = (w * (gammaln(n + 1.0) - gammaln(z + 1.0) - gammaln(n - z + 1.0))).sum(axis=-1)
    with np.errstate(over="ignore", under="ignore"):
        theta[rows[ok]] = np.exp(centre[ok] - a[ok] * spread[ok] / b[ok])
    beta[rows[ok]] = spread[ok] / b[ok]
    ll[rows[ok]] = f[ok] + binomial[ok]
    return theta, beta, ll, outcome


def _refit(x: np.ndarray, z: np.ndarray, n: np.ndarray) -> tuple:
    """``(theta, beta, log_likelihood, outcome)`` of :func:`_fit`, one fit."""
    try:
        fit = _fit(x, z, n)
    except ValueError:
        return math.nan, math.nan, math.nan, UNIDENTIFIED
    except RuntimeError:
        return math.nan, math.nan, math.nan, NOT_CONVERGED
    return fit.theta, fit.beta, fit.log_likelihood, FITTED


def _repeated(x: np.ndarray, w: np.ndarray, z: np.ndarray, n: np.ndarray):
    """The entries of fit ``i`` repeated ``w[i]`` times, in entry order (``expanded`` of :func:`fit_weighted`)."""
    def expanded(i: int) -> tuple:
        reps = w[i].astype(np.int64)
        return tuple(np.repeat(a if a.ndim == 1 else a[i], reps) for a in (x, z, n))
    return expanded


def _merging(x: np.ndarray, z: np.ndarray, n: np.ndarray):
    """Entries of the same ``(x, z, n)`` in every fit made one: ``(x, z, n, weights)``.

    ``weights(w)`` adds the weights of the entries made one.  The likelihood, its derivatives, the
    standardisation and the checks are sums over entries times their weights, so they keep their
    values (to round-off) on fewer entries.
    """
    if x.ndim == z.ndim == n.ndim == 1:    # entries shared by every fit
        keys, inverse = np.unique(np.stack([x, z, n]), axis=1, return_inverse=True)
        if keys.shape[1] < x.size:
            order = np.argsort(inverse.ravel(), kind="stable")
            starts = np.flatnonzero(np.diff(inverse.ravel()[order], prepend=-1))
            return keys[0], keys[1], keys[2], lambda w: np.add.reduceat(w[:, order], starts, axis=1)
    return x, z, n, lambda w: w


def fit_weighted(x, w, z, n, expanded=None) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Many :func:`fit_lognormal` fits at once, each of the same entries repeated ``w`` times.

    Fit ``i`` is ``fit_lognormal(*expanded(i))``, the entries repeated ``w[i]`` times (an entry
    with ``w = 0`` left out), to round-off: the same checks, start, Newton iteration and
    convergence tests, run on every fit still iterating at once.  A fit whose outcome hinges on
    round-off is redone one by one by :func:`fit_lognormal` on ``expanded(i)``, so that it is the
    outcome :func:`fit_lognormal` gives for those very arrays: a Newton system that comes near
    singular (``_NEAR_SINGULAR``), a slope that ends flat (``_FLAT``), no convergence, or a
    ``theta`` that overflows (``OverflowError``, as :func:`fit_lognormal` raises).  A bootstrap
    resample is a fit whose weights are the times each entry was drawn.

    Parameters
    ----------
    x : numpy.ndarray of float, shape (k,) or (fits, k)
        IM of each entry, > 0 and finite (unchecked).
    w : numpy.ndarray of float, shape (fits, k)
        Times each entry counts in each fit: integers >= 0.
    z, n : numpy.ndarray of float, shape (k,) or (fits, k)
        Exceedances and analyses of each entry (as checked by :func:`fit_lognormal`; ``n`` may be 0
        where ``w`` is 0).
    expanded : callable, optional
        ``expanded(i) -> (x, z, n)``: the arrays fit ``i`` stands for, in the order its entries
        come (e.g. a bootstrap resample's, in the order drawn).  Default: each entry repeated in
        place.

    Returns
    -------
    theta, beta, log_likelihood : numpy.ndarray of float, shape (fits,)
        As :class:`LognormalFit`; NaN where no curve was fitted.
    outcome : numpy.ndarray of int8, shape (fits,)
        ``FITTED`` (0), ``UNIDENTIFIED`` (1: :func:`fit_lognormal` raises ValueError) or
        ``NOT_CONVERGED`` (2: it raises RuntimeError).

    Notes
    -----
    The fits go through in passes of at most ``_BATCH_ENTRIES`` (fit, entry) pairs, in order, so
    the memory stays bounded; the results do not depend on the number of fits asked at once.
    """
    w = np.asarray(w, dtype=float)
    x, z, n = (np.asarray(a, dtype=float) for a in (x, z, n))
    expanded = expanded or _repeated(x, w, z, n)
    x, z, n, merged = _merging(x, z, n)
    per = max(1, _BATCH_ENTRIES // max(1, w.shape[-1]))

    def rows(a: np.ndarray, i: int) -> np.ndarray:
        return a if a.ndim == 1 else a[i:i + per]

    parts = [_fit_pass(rows(x, i), merged(w[i:i + per]), rows(z, i), rows(n, i)) for i in range(0, w.shape[0], per)]
    if not parts:
        return tuple(np.empty(0) for _ in range(3)) + (np.empty(0, dtype=np.int8),)
    theta, beta, ll, outcome = (np.concatenate(col) for col in zip(*parts, strict=True))
    overflow = (outcome == FITTED) & ~np.isfinite(theta)   # fit_lognormal: OverflowError
    for i in np.flatnonzero((outcome == NOT_CONVERGED) | (outcome == _UNSTABLE) | overflow):
        theta[i], beta[i], ll[i], outcome[i] = _refit(*expanded(int(i)))
    return theta, beta, ll, outcome


# ----------------------------------------------------------------------------------------------
# the public functions
# ----------------------------------------------------------------------------------------------

def fit_lognormal(im, exceeded, n=None) -> LognormalFit:
    """Maximum-likelihood lognormal fragility curve (Baker 2015).

    Parameters
    ----------
    im : array_like of float, shape (k,)
        IM of each stripe (``n`` given) or of each analysis (``n=None``), > 0, finite, in any
        unit; ``theta`` comes out in the same unit.  At least two distinct values.
    exceeded : array_like, shape (k,)
        Stripes: analyses that exceeded the limit state at each level, integers
        ``0 <= exceeded <= n``.  Per analysis: booleans (or 0/1).
    n : array_like of int, shape (k,), optional
        Analyses at each level (>= 1).  ``None``: one analysis per entry of ``im``.

    Returns
    -------
    LognormalFit

    Raises
    ------
    ValueError
        Shapes that differ, non-positive or non-finite IMs, counts that are negative, not
        integers or above ``n``; data that identify no curve: fewer than two distinct IM
        levels, none or every analysis exceeded, outcomes perfectly separated by the IM (the
        maximum likelihood is at ``beta -> 0``; the message names the IM range where more
        analyses would identify the curve), or a fraction exceeded that decreases with the IM.
    """
    x, z, nn = _prepare(im, exceeded, n)
    return _fit(x, z, nn)


def _fit(x: np.ndarray, z: np.ndarray, nn: np.ndarray) -> LognormalFit:
    """:func:`fit_lognormal` of checked float arrays (IM, exceedances, analyses)."""
    _check_identifiable(x, z, nn)
    lx = np.log(x)
    centre, spread = float(np.mean(lx)), float(np.std(lx))
    t = (lx - centre) / spread
    (a, b), ll = _newton(t, z, nn)
    if b <= 0.0:
        raise ValueError(f"exceeded decreases with im (maximum-likelihood slope {b:.3g} <= 0 in ln im); "
                         "allowed: a fraction exceeded that grows with the IM (a fragility curve)")
    ll += float(np.sum(gammaln(nn + 1.0) - gammaln(z + 1.0) - gammaln(nn - z + 1.0)))
    return LognormalFit(theta=float(math.exp(centre - a * spread / b)), beta=float(spread / b),
                        n_analyses=int(nn.sum()), n_exceeded=int(z.sum()), log_likelihood=ll)


def probability(x, theta, beta):
    """Probability of exceedance ``Phi(ln(x / theta) / beta)`` of a lognormal fragility curve.

    Parameters
    ----------
    x : array_like of float
        IM values, >= 0 (0 gives 0; ``inf`` gives 1), in the units of ``theta``.
    theta : array_like of float
        Median capacity, > 0 (NaN propagates: a missing curve).
    beta : array_like of float
        Dispersion, > 0 (NaN propagates).

    Returns
    -------
    numpy.ndarray or float
        The broadcast probabilities.

    Raises
    ------
    ValueError
        ``x < 0``, ``theta <= 0`` or ``beta <= 0``.
    """
    x, theta, beta = (np.asarray(v, dtype=float) for v in (x, theta, beta))
    for name, arr, bad, allowed in (("x", x, x < 0, "0 <= x"), ("theta", theta, theta <= 0, "0 < theta"),
                                    ("beta", beta, beta <= 0, "0 < beta")):
        if np.any(bad):
            value = arr[bad].flat[0] if arr.ndim else arr
            raise ValueError(f"{name} = {float(value)!r} is out of range; allowed range: {allowed}")
    with np.errstate(divide="ignore"):
        out = ndtr(np.log(x / theta) / beta)
    return out if out.ndim else float(out)


def draw_groups(size: int, n_boot: int, seed) -> np.ndarray:
    """Groups drawn by each of ``n_boot`` resamples, in the order drawn, shape ``(n_boot, size)``.

    Resample ``i`` draws ``size`` groups with replacement, ``rng.integers(0, size, size=size)``,
    the ``i``-th such draw of ``numpy.random.default_rng(seed)``.
    """
    rng = np.random.default_rng(seed)
    return np.array([rng.integers(0, size, size=size) for _ in range(n_boot)]).reshape(n_boot, size)


def times_drawn(draws: np.ndarray, size: int) -> np.ndarray:
    """Times each of ``size`` groups is drawn in each resample (rows of ``draws``), as floats."""
    return np.array([np.bincount(d, minlength=size) for d in draws], dtype=float).reshape(len(draws), size)


def bootstrap(im, exceeded, groups, n=None, *, n_boot: int, seed: int, level: float) -> BootstrapInterval:
    """Percentile bootstrap interval of ``theta`` and ``beta``, resampling groups (records).

    Each resample draws as many groups as there are, with replacement; all entries of a drawn
    group go in together (as often as it is drawn), and :func:`fit_lognormal` is refitted.

    Parameters
    ----------
    im, exceeded, n
        As for :func:`fit_lognormal`.
    groups : array_like, shape (k,)
        Group (record) of each entry of ``im``; at least two distinct groups.
    n_boot : int
        Resamples, >= 1 (``fragility.bootstrap.n_boot`` in the configuration).
    seed : int
        Seed of ``numpy.random.default_rng``, >= 0: the same seed gives the same interval.
    level : float
        Two-sided confidence level, 0 < level < 1: the bounds are the ``(1 - level)/2`` and
        ``(1 + level)/2`` percentiles (linear interpolation) of the refitted values.

    Returns
    -------
    BootstrapInterval
        ``n_failed`` counts the resamples that identified no curve; the percentiles are those of
        the others.  Failed resamples are mostly separated ones (``beta -> 0``): when ``n_failed``
        is not small against ``(1 - level)/2 * n_boot``, the lower bound of ``beta`` is too high.

    Raises
    ------
    ValueError
        Invalid data (as :func:`fit_lognormal`), ``groups`` of another shape or with fewer than two
        groups, ``n_boot``, ``seed`` or ``level`` out of range, or no resample that identifies a
        curve.
    """
    x, z, nn = _prepare(im, exceeded, n)
    g = np.asarray(groups)
    if g.shape != x.shape:
        raise ValueError(f"groups has {_shape_text(g)}; allowed: the shape of im, {x.shape}")
    labels, code = np.unique(g, return_inverse=True)
    if labels.size < 2:
        raise ValueError(f"groups has {labels.size} distinct value ({labels[0].item()!r}); allowed: at least 2 "
                         "groups (records) to resample")
    if isinstance(n_boot, bool) or not isinstance(n_boot, (int, np.integer)) or n_boot < 1:
        raise ValueError(f"n_boot = {n_boot!r} is out of range; allowed: integers >= 1")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ValueError(f"seed = {seed!r} is out of range; allowed: integers >= 0")
    if not (isinstance(level, (int, float, np.floating)) and 0.0 < float(level) < 1.0):
        raise ValueError(f"level = {level!r} is out of range; allowed range: 0 < level < 1")
    draws = draw_groups(labels.size, int(n_boot), seed)
    members = [np.flatnonzero(code == i) for i in range(labels.size)]

    def expanded(i: int) -> tuple:
        idx = np.concatenate([members[g] for g in draws[i]])
        return x[idx], z[idx], nn[idx]

    theta, beta, _, outcome = fit_weighted(x, times_drawn(draws, labels.size)[:, code], z, nn, expanded)
    if (outcome == NOT_CONVERGED).any():
        raise RuntimeError(f"bootstrap: Newton's method did not converge in {_MAX_NEWTON} iterations for "
                           f"{int((outcome == NOT_CONVERGED).sum())} of {n_boot} resamples")
    ok = outcome == FITTED
    thetas, betas, n_failed = theta[ok], beta[ok], int(n_boot) - int(ok.sum())
    if not thetas.size:
        raise ValueError(f"n_boot = {n_boot}: none of the resamples identifies a curve (all {n_failed} failed); "
                         "allowed: data whose record resamples overlap (more records or IM levels)")
    q = [(1.0 - float(level)) / 2.0, (1.0 + float(level)) / 2.0]
    tl, th = np.quantile(thetas, q)
    bl, bh = np.quantile(betas, q)
    return BootstrapInterval(theta_low=float(tl), theta_high=float(th), beta_low=float(bl), beta_high=float(bh),
                             n_boot=int(n_boot), n_failed=int(n_failed))
