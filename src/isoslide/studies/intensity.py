"""Intensity measures of a ground motion and of the floor it drives: PGA, PGV, PFA, PFV.

A sampled record is linear between its samples (:func:`isoslide.pulses.sampled`), so its
velocity is piecewise quadratic; the peaks here are those of that motion, not just of the
samples:

* :func:`peak_abs` -- the largest ``|a|`` of a piecewise-linear acceleration is at a sample;
* :func:`peak_of_integral` -- the largest ``|f|`` of a history known with its rate at rows: at
  a row, or inside an interval where the rate changes sign, at the extremum of the cubic
  Hermite interpolant (exact for a record's velocity, which is quadratic between samples).

A sampled history alone underestimates a peak between its rows by ``O(h^2)``; with the rate the
error is ``O(h^4)``.  The floor acceleration of an isolated slab is taken with its rate
(:func:`floor_jerk`, from the slab's equation of motion) for that reason.

:func:`ground_peaks` gives PGA [m/s^2] and PGV [m/s] of a record; :func:`floor_peaks` the peak
absolute acceleration and velocity of the floor the contents stand on, from the history of a
solve (isolated slab: ``a_g + x_b''`` and ``v_g + x_b'`` of the coupled solve, the friction of
the contents acting back on the slab; a fixed base: the ground's); :func:`planar_floor_peaks` the
same for a floor moving in the plane, the peak lengths of its absolute acceleration and velocity
vectors over the history rows of a planar solve.

Intensity measures of a pair of horizontal components (``a_x``, ``a_y`` on one time axis), by
the orientation-independent definition of Boore (2010): the component along the direction at
angle ``theta`` is ``a_theta(t) = a_x(t) cos(theta) + a_y(t) sin(theta)``; its peak is taken for
every ``theta`` of :data:`ROTD_ANGLES` (0, 1, ..., 179 degrees) and RotDnn is the
``nn``-th percentile of those peaks (RotD50 the median, RotD100 the largest).  Vectorised over the
angles with numpy (:func:`rotated_peaks`):

* :func:`pair_peaks` -- RotDnn of PGA and PGV, the velocity's peak between samples exact
  (:func:`rotated_velocity_peaks`);
* :func:`pair_sa` -- RotDnn of the pseudo-spectral acceleration ``omega^2 max |d_theta|`` of a
  linear oscillator (:func:`oscillator_displacement`, exact for an acceleration linear between
  samples), the response to ``a_theta`` being ``d_x cos(theta) + d_y sin(theta)``.

Boore, D. M. (2010): Orientation-independent, nongeometric-mean measures of seismic intensity
from two horizontal components of motion, Bulletin of the Seismological Society of America
100(4), 1830-1835.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.linalg import expm
from scipy.signal import lfilter

from ..records import G
from ..engine.planar import floor_motion
from ..store.history_io import history_table

__all__ = ["IM_NAMES", "IM_UNITS", "ROTD_ANGLES", "align_pair", "floor_jerk", "floor_peaks", "ground_peaks",
           "oscillator_displacement", "pair_peaks", "pair_sa", "peak_abs", "peak_of_integral", "planar_floor_peaks",
           "rotated_peaks", "rotated_velocity_peaks", "rotd"]

IM_NAMES = ("pga", "pgv", "pfa", "pfv")
"""Intensity measures: peak ground acceleration and velocity, peak floor acceleration and velocity."""

IM_UNITS = {"pga": "m s-2", "pgv": "m s-1", "pfa": "m s-2", "pfv": "m s-1"}
"""CF units of each intensity measure."""

ROTD_ANGLES = np.arange(180.0)
"""Rotation angles of RotDnn, degrees (0, 1, ..., 179; Boore 2010)."""


def peak_abs(values) -> float:
    """``max |values|`` (the peak of a piecewise-linear history: at a row)."""
    return float(np.max(np.abs(np.asarray(values, dtype=float))))


def peak_of_integral(t, f, rate) -> float:
    """Largest ``|f|`` of a smooth history known with its derivative at the rows.

    Between two rows ``f`` is taken as the cubic Hermite interpolant of the values and
    derivatives at both ends; where ``rate`` changes sign in an interval, the interior extremum
    of that cubic (a root of its quadratic derivative) is a candidate peak.

    Parameters
    ----------
    t : array_like
        Row times (non-decreasing; repeated times, e.g. at a transition, are skipped), any unit.
    f : array_like
        ``f`` at the rows (e.g. velocity, m/s).
    rate : array_like
        ``df/dt`` at the rows (e.g. acceleration, m/s^2).

    Returns
    -------
    float
        ``max |f|`` over the rows and those interior extrema: exact when ``f`` is a polynomial
        of degree at most 3 between rows (a record's velocity: quadratic), else an error of
        fourth order in the row spacing.
    """
    t = np.asarray(t, dtype=float)
    f = np.asarray(f, dtype=float)
    r = np.asarray(rate, dtype=float)
    best = peak_abs(f)
    h_all = np.diff(t)
    cross = (r[:-1] * r[1:] < 0.0) & (h_all > 0.0)
    if not np.any(cross):
        return best
    h = h_all[cross]
    f0, f1, d0, d1 = f[:-1][cross], f[1:][cross], h * r[:-1][cross], h * r[1:][cross]
    # f on s = (t - t_i) / h in [0, 1]; df/ds = A s^2 + B s + C changes sign in (0, 1)
    A = 6.0 * (f0 - f1) + 3.0 * (d0 + d1)
    B = 6.0 * (f1 - f0) - 4.0 * d0 - 2.0 * d1
    C = d0
    with np.errstate(divide="ignore", invalid="ignore"):
        disc = np.sqrt(np.maximum(B * B - 4.0 * A * C, 0.0))
        q = -0.5 * (B + np.copysign(disc, B))
        roots = (q / A, C / q, -C / B)
    vals = []
    for s in roots:
        s = np.where(np.isfinite(s) & (s > 0.0) & (s < 1.0), s, np.nan)
        h00, h10 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s
        h01, h11 = -2 * s**3 + 3 * s**2, s**3 - s**2
        vals.append(np.abs(h00 * f0 + h10 * d0 + h01 * f1 + h11 * d1))
    v = np.concatenate(vals)
    v = v[np.isfinite(v)]
    return max(best, float(v.max())) if v.size else best


def ground_peaks(accel_g, dt: float) -> tuple[float, float]:
    """PGA [m/s^2] and PGV [m/s] of a record sampled at ``dt``, linear between samples.

    Parameters
    ----------
    accel_g : array_like
        Ground acceleration, g (as :attr:`isoslide.records.Record.accel`).
    dt : float
        Sampling interval, s.

    Returns
    -------
    (float, float)
        PGA = ``max |a|`` (at a sample) and PGV = the largest ``|v|`` of the exact integral
        from rest (:func:`peak_of_integral`, exact; at least :attr:`Record.pgv`, which looks at
        the samples only).
    """
    a = np.asarray(accel_g, dtype=float) * G
    v = np.concatenate([[0.0], np.cumsum(0.5 * (a[1:] + a[:-1]) * dt)])
    t = dt * np.arange(a.size)
    return peak_abs(a), peak_of_integral(t, v, a)


def floor_jerk(columns: dict, scene) -> np.ndarray:
    """Rate of change of the absolute floor acceleration at the history rows, m/s^3 (isolated slab).

    From the slab's equation of motion: ``a_f = -(c x' + k x) / M`` while the contents stick
    (``M = M_b + m_ec``) and ``-(c x' + k x) / M_b`` plus a constant Coulomb reaction while they
    slide, so ``a_f' = -(2 xi_b w x'' + w^2 x') / (1 + m_ec/M_b while stuck)`` with
    ``x'' = a_f - a_g`` (Coulomb contents: the friction reaction is constant within a slip).

    Parameters
    ----------
    columns : dict
        :attr:`HistoryTable.columns` in SI units (``floor_accel``, ``ground_accel``, ``floor_vel``,
        ``phase``).
    scene : isoslide.Scene
        The scene solved (``Pi3 > 0``, built with :meth:`Scene.from_physical`).
    """
    w = 2.0 * np.pi / (scene.pi3 * scene.scale.T_p)
    xdd = columns["floor_accel"] - columns["ground_accel"]
    stuck = np.asarray(columns["phase"]) == 0
    return -(2.0 * scene.pi4 * w * xdd + w * w * columns["floor_vel"]) / np.where(stuck, 1.0 + scene.pi8, 1.0)


def floor_peaks(solution, scene) -> tuple[float, float]:
    """PFA [m/s^2] and PFV [m/s]: peak absolute acceleration and velocity of the contents' floor.

    Parameters
    ----------
    solution : isoslide.Solution
        ``isoslide.solve(scene, history=True)`` of a scene built with
        :meth:`isoslide.Scene.from_physical`.
    scene : isoslide.Scene
        The scene solved.

    Returns
    -------
    (float, float)
        From the history rows (every sample and substep of the record, every stick/slip
        transition; :func:`isoslide.store.history_io.history_table`), each by :func:`peak_of_integral`:
        PFV of ``v_g + x_b'`` with the floor acceleration as its rate, PFA of ``a_g + x_b''``
        with :func:`floor_jerk` as its rate (cubic Hermite between rows: an error of fourth
        order in the row spacing).  On a fixed base the floor is the ground: PFA = PGA and PFV = PGV of the
        scaled record, exactly; so it is on a sliding bearing that held throughout (the solver's
        ``bearing-stuck`` reduction, ``solution.facets.isolator == "fixed-base"``), PFA then the
        largest ``|a_g|`` at the rows.
    """
    tab = history_table(solution, scene)
    c = tab.columns
    t = c["time"]
    sc = scene.scale
    v_ground = np.asarray(scene.pulse.velocity(t / sc.T_p), dtype=float) * (sc.a_p * sc.T_p)
    a_floor = c["floor_accel"]
    v_floor = v_ground + c["floor_vel"]
    pfv = peak_of_integral(t, v_floor, a_floor)
    if scene.fixed_base or solution.facets.isolator == "fixed-base":
        return peak_abs(a_floor), pfv
    return peak_of_integral(t, a_floor, floor_jerk(c, scene)), pfv


def planar_floor_peaks(solution, scene) -> tuple[float, float]:
    """PFA [m/s^2] and PFV [m/s] of a floor moving in the plane: the peaks of the vectors' lengths.

    ``solution`` and ``scene`` as for :func:`floor_peaks`, the scene having run in the plane
    (``solution.facets.contact == "plane"``).

    Returns
    -------
    (float, float)
        ``max |a_F|`` and ``max |v_g + v_F|`` over the history rows (every sample of a record, every
        step and every stick/slip transition), ``a_F`` the floor's absolute acceleration
        (:func:`isoslide.engine.planar.floor_motion`) and ``v_g + v_F`` its absolute velocity
        (:meth:`isoslide.Scene.ground_velocity` plus the floor's relative to the ground).  On a fixed
        base the floor is the ground: the peak lengths of the ground's vectors.
    """
    motion = floor_motion(scene, solution.history)
    sc = scene.scale
    vgx, vgy = scene.ground_velocity(solution.history.tau)
    pfa = float(np.max(np.hypot(motion[:, 0], motion[:, 1]))) * sc.a_p
    pfv = float(np.max(np.hypot(vgx + motion[:, 2], vgy + motion[:, 3]))) * sc.a_p * sc.T_p
    return pfa, pfv


# ----------------------------------------------------------------------------------------------
# intensity measures of a pair of horizontal components (RotDnn, Boore 2010)
# ----------------------------------------------------------------------------------------------

def _directions(angles_deg) -> tuple[np.ndarray, np.ndarray]:
    a = np.radians(ROTD_ANGLES if angles_deg is None else np.asarray(angles_deg, dtype=float))
    return np.cos(a), np.sin(a)


def rotated_peaks(x, y, angles_deg=None) -> np.ndarray:
    """``max_t |x(t) cos(theta) + y(t) sin(theta)|`` for every angle ``theta``.

    Parameters
    ----------
    x, y : array_like, shape (n,)
        The two components at the same rows (any unit, e.g. m/s^2).
    angles_deg : array_like, optional
        Angles ``theta``, degrees; default :data:`ROTD_ANGLES`.

    Returns
    -------
    numpy.ndarray, shape (angles,)
        Peak of the rotated component at each angle, in the unit of ``x`` (at a row: the peak
        of a history linear between rows).
    """
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    if x.shape != y.shape or x.ndim != 1:
        raise ValueError(f"x has shape {x.shape} and y {y.shape}; allowed: two 1-D arrays of one length")
    c, s = _directions(angles_deg)
    return np.max(np.abs(np.outer(x, c) + np.outer(y, s)), axis=0)


def rotd(peaks, percentile: float = 50.0) -> float:
    """RotDnn: the ``percentile``-th percentile of the peaks over the rotation angles.

    Parameters
    ----------
    peaks : array_like
        :func:`rotated_peaks` (or :func:`rotated_velocity_peaks`) over :data:`ROTD_ANGLES`.
    percentile : float
        ``nn`` in [0, 100]: 50 the median (RotD50), 100 the largest (RotD100), linear
        interpolation between order statistics (``numpy.percentile``).
    """
    if not 0.0 <= float(percentile) <= 100.0:
        raise ValueError(f"percentile = {percentile!r} is out of range; allowed range: 0 <= percentile <= 100")
    return float(np.percentile(np.asarray(peaks, dtype=float), float(percentile)))


def _velocity(a: np.ndarray, dt: float) -> np.ndarray:
    """Velocity from rest of an acceleration linear between samples (exact at the samples)."""
    return np.concatenate([[0.0], np.cumsum(0.5 * (a[1:] + a[:-1]) * dt)])


def rotated_velocity_peaks(ax, ay, dt: float, angles_deg=None) -> np.ndarray:
    """Peak ``|v_theta|`` of the rotated velocity for every angle, exact between samples.

    The velocity of an acceleration linear between samples is quadratic there: besides the
    samples, its peak can lie where ``a_theta`` changes sign inside an interval, at
    ``v_i + h a_i s / 2`` with ``s = a_i / (a_i - a_(i+1))`` (the same peak as
    :func:`ground_peaks` gives for one component).

    Parameters
    ----------
    ax, ay : array_like, shape (n,)
        Accelerations of the two components, m/s^2, from rest at the first sample.
    dt : float
        Sampling interval, s.
    angles_deg : array_like, optional
        Angles, degrees; default :data:`ROTD_ANGLES`.

    Returns
    -------
    numpy.ndarray, shape (angles,)
        Peak velocity, m/s, at each angle.
    """
    ax, ay = np.asarray(ax, dtype=float), np.asarray(ay, dtype=float)
    if ax.shape != ay.shape or ax.ndim != 1:
        raise ValueError(f"ax has shape {ax.shape} and ay {ay.shape}; allowed: two 1-D arrays of one length")
    c, s = _directions(angles_deg)
    a = np.outer(ax, c) + np.outer(ay, s)
    v = np.outer(_velocity(ax, dt), c) + np.outer(_velocity(ay, dt), s)
    best = np.max(np.abs(v), axis=0)
    a0, a1 = a[:-1], a[1:]
    cross = a0 * a1 < 0.0
    if np.any(cross):
        with np.errstate(divide="ignore", invalid="ignore"):
            inner = np.where(cross, np.abs(v[:-1] + 0.5 * dt * a0 * (a0 / (a0 - a1))), 0.0)
        best = np.maximum(best, np.max(inner, axis=0))
    return best


def align_pair(x, y, dt: float, t0_x: float = 0.0, t0_y: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Two components on one time axis: zero before and after each (a record is zero outside).

    Parameters
    ----------
    x, y : array_like
        Samples of each component (any unit), each at ``dt``.
    dt : float
        Common sampling interval, s.
    t0_x, t0_y : float
        Time of each component's first sample, s; they must differ by a whole number of samples
        (to 1e-6 of ``dt``).

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        Both of one length, starting at ``min(t0_x, t0_y)``.
    """
    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    shift = (t0_y - t0_x) / dt
    k = int(round(shift))
    if abs(shift - k) > 1e-6:
        raise ValueError(f"t0_y - t0_x = {t0_y - t0_x!r} s is {shift!r} samples; allowed: a whole number of "
                         f"samples of dt = {dt!r} s")
    ox, oy = max(0, -k), max(0, k)     # offsets of each on the common axis
    n = max(ox + x.size, oy + y.size)
    out = np.zeros((2, n))
    out[0, ox:ox + x.size] = x
    out[1, oy:oy + y.size] = y
    return out[0], out[1]


def pair_peaks(ax, ay, dt: float, percentile: float = 50.0) -> tuple[float, float]:
    """RotDnn of the peak ground acceleration and velocity of a pair.

    Parameters
    ----------
    ax, ay : array_like, shape (n,)
        Accelerations, m/s^2, on one time axis (:func:`align_pair`), from rest.
    dt : float
        Sampling interval, s.
    percentile : float
        ``nn`` (50: RotD50).

    Returns
    -------
    (float, float)
        PGA [m/s^2] (peaks at the samples) and PGV [m/s] (exact between samples).
    """
    return (rotd(rotated_peaks(ax, ay), percentile),
            rotd(rotated_velocity_peaks(ax, ay, dt), percentile))


def _oscillator_filter(dt: float, period: float, damping: float) -> tuple[np.ndarray, np.ndarray]:
    """``(b, a)`` of ``scipy.signal.lfilter``: the exact recursion of ``d'' + 2 z w d' + w^2 d = -a_g``.

    The state ``q = (d, d')`` obeys ``q_(k+1) = A q_k + b0 a_k + b1 a_(k+1)`` for a ground
    acceleration linear over each step (the matrix exponential of the augmented system, as
    ``scipy.signal.lsim`` builds it); its transfer function to ``d`` is
    ``e1^T adj(zI - A) (b0 + b1 z) / det(zI - A)``.
    """
    w = 2.0 * math.pi / period
    A = np.array([[0.0, 1.0], [-w * w, -2.0 * damping * w]])
    B = np.array([[0.0], [-1.0]])
    M = np.zeros((4, 4))
    M[:2, :2], M[:2, 2:3], M[2, 3] = A * dt, B * dt, 1.0
    E = expm(M)
    Ad, g0, g1 = E[:2, :2], E[:2, 2], E[:2, 3]     # q(dt) = Ad q + g0 a_0 + g1 (a_1 - a_0)
    b0, b1 = g0 - g1, g1
    a11, a12, a22 = Ad[0, 0], Ad[0, 1], Ad[1, 1]
    num = np.array([b1[0], b0[0] - a22 * b1[0] + a12 * b1[1], -a22 * b0[0] + a12 * b0[1]])
    den = np.array([1.0, -(a11 + a22), a11 * a22 - a12 * Ad[1, 0]])
    return num, den


def oscillator_displacement(accel, dt: float, period: float, damping: float = 0.05,
                            free_periods: float = 1.0) -> np.ndarray:
    """Relative displacement of a linear oscillator under a ground acceleration, m, at the samples.

    Exact for an acceleration linear between samples that starts from zero (a recorded ground
    motion; a first sample that is not zero is reached by a ramp over the step before it), with
    the oscillator at rest.  The record is followed by ``free_periods`` periods of zeros, so a
    peak in the free vibration after it is found.

    Parameters
    ----------
    accel : array_like, shape (n,) or (n, m)
        Ground acceleration, m/s^2 (columns: several records on one time axis).
    dt : float
        Sampling interval, s.
    period : float
        Natural period, s (> 0).
    damping : float
        Damping ratio (>= 0, < 1).
    free_periods : float
        Periods of free vibration appended (>= 0).

    Returns
    -------
    numpy.ndarray
        Displacement at every sample of the padded record, m (shape ``(n + pad, ...)``).
    """
    if not (math.isfinite(period) and period > 0.0):
        raise ValueError(f"period = {period!r} is out of range; allowed range: 0 < period < inf")
    if not 0.0 <= damping < 1.0:
        raise ValueError(f"damping = {damping!r} is out of range; allowed range: 0 <= damping < 1")
    a = np.asarray(accel, dtype=float)
    pad = int(math.ceil(free_periods * period / dt))
    a = np.concatenate([np.zeros((1,) + a.shape[1:]), a, np.zeros((pad,) + a.shape[1:])])
    num, den = _oscillator_filter(dt, period, damping)
    return lfilter(num, den, a, axis=0)[1:]


def pair_sa(ax, ay, dt: float, period: float, damping: float = 0.05, percentile: float = 50.0) -> float:
    """RotDnn of the pseudo-spectral acceleration of a pair at one period, m/s^2.

    ``Sa(theta) = omega^2 max_t |d_x(t) cos(theta) + d_y(t) sin(theta)|`` with ``d_x``, ``d_y``
    the oscillator's responses to each component (:func:`oscillator_displacement`; the response
    to the rotated component, by linearity), peaks at the samples.

    Parameters
    ----------
    ax, ay : array_like, shape (n,)
        Accelerations, m/s^2, on one time axis (:func:`align_pair`).
    dt : float
        Sampling interval, s.
    period : float
        Oscillator period, s.
    damping : float
        Damping ratio (0.05 is the usual 5 %).
    percentile : float
        ``nn`` (50: RotD50).
    """
    d = oscillator_displacement(np.column_stack([ax, ay]), dt, period, damping)
    w = 2.0 * math.pi / period
    return w * w * rotd(rotated_peaks(d[:, 0], d[:, 1]), percentile)
