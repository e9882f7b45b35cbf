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
the contents acting back on the slab; a fixed base: the ground's).
"""

from __future__ import annotations

import numpy as np

from ..store.history_io import history_table
from ..records import G

__all__ = ["IM_NAMES", "IM_UNITS", "floor_jerk", "floor_peaks", "ground_peaks", "peak_abs",
           "peak_of_integral"]

IM_NAMES = ("pga", "pgv", "pfa", "pfv")
"""Intensity measures: peak ground acceleration and velocity, peak floor acceleration and velocity."""

IM_UNITS = {"pga": "m s-2", "pgv": "m s-1", "pfa": "m s-2", "pfv": "m s-1"}
"""CF units of each intensity measure."""


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
        scaled record, exactly.
    """
    tab = history_table(solution, scene)
    c = tab.columns
    t = c["time"]
    sc = scene.scale
    v_ground = np.asarray(scene.pulse.velocity(t / sc.T_p), dtype=float) * (sc.a_p * sc.T_p)
    a_floor = c["floor_accel"]
    v_floor = v_ground + c["floor_vel"]
    pfv = peak_of_integral(t, v_floor, a_floor)
    if scene.fixed_base:
        return peak_abs(a_floor), pfv
    return peak_of_integral(t, a_floor, floor_jerk(c, scene)), pfv
