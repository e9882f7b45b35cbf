r"""Quasi-static peer of the triple friction pendulum: the four sliding surfaces and their equilibrium.

Written from the mechanics, independently of the closed forms of :mod:`isoslide.model.tfp` (it
reads only the bearing's parameters).  Surfaces are indexed 0..3 bottom to top (surfaces 1..4):
radii ``(L2, L1, L1, L3)``, friction ``(mu2, mu1, mu1, mu3) W``, limits ``(d2, d1, d1, d3)``.

Every surface transmits the same horizontal force ``F``.  Surface ``i`` has its own relative
displacement ``u_i`` (``u = sum u_i``) and transmits the weight times the slope of its normal plus its
reaction ``q_i`` (friction, and the restrainer's push once ``|u_i| = d_i``).  The slide plate on an
outer surface turns with it, so an inner surface's slope adds its plate's::

    q_0 = F - W u_0/L2           q_1 = q_0 - W u_1/L1      (surface 2 rides on surface 1's plate)
    q_3 = F - W u_3/L3           q_2 = q_3 - W u_2/L1      (surface 3 rides on surface 4's plate)

A surface sticks (``u_i`` constant, true stick) while ``|q_i| <= mu_i W``, slides with
``q_i = mu_i W`` along its motion otherwise, and at its restrainer carries any excess pushing
outward.  In the plane ``u_i`` and ``q_i`` are 2-vectors, the friction circular and the restrainers
circles.

:func:`solve_path` drives the bearing along the line by imposed total displacement, event to event:
between events every rate is constant, and at each event the small complementarity problem (which
surfaces slide, in which direction) is solved by trying every combination and keeping the consistent
one, so the vertices of the force-displacement path are exact to round-off.  :func:`solve_planar`
drives it in the plane through given points, each increment solved implicitly (the incremental
problem of each surface is a closed-form return to its friction circle, or a one-dimensional
minimisation on its restrainer circle; the common force by Newton's method), which is exact along a
straight line.  Along a line at most two surfaces slide at a time (Fenz and Constantinou's regimes);
in the plane the reaction of a sliding outer surface keeps its magnitude but turns, so the inner
surface it carries can slide with it and more than two surfaces may slide at once.

Units: lengths m, forces N.
"""

from __future__ import annotations

import itertools
import math
from typing import NamedTuple

import numpy as np
from scipy.optimize import brentq

_CARRIER = {1: 0, 2: 3}
"""The outer surface whose plate carries each inner surface."""


def _surfaces(bearing):
    """Radii, friction strengths (N) and limits of surfaces 1..4 (indices 0..3), and the weight (N)."""
    (L1, L2, L3), (mu1, mu2, mu3), (d1, d2, d3) = bearing.L, bearing.mu, bearing.d
    W = bearing.W
    return (np.array([L2, L1, L1, L3]), W * np.array([mu2, mu1, mu1, mu3]), np.array([d2, d1, d1, d3]), W)


def _stage(moving: tuple, outer_at_stop: bool) -> int:
    """The regime of Fenz and Constantinou from the surfaces that move (0 none, -1 none of the five).

    ``outer_at_stop``: both outer surfaces rest on their restrainers (the inner pair sliding is then V).
    """
    if not moving:
        return 0
    if moving == (1, 2):
        return 5 if outer_at_stop else 1
    return {(0, 2): 2, (0, 3): 3, (1, 3): 4}.get(moving, -1)


class QuasiStaticPath(NamedTuple):
    """A quasi-static path of the bearing.

    ``u`` (m) and ``F`` (N): total displacement and force at each vertex, shape ``(n,)`` along the
    line or ``(n, 2)`` in the plane; ``surfaces`` the displacements of surfaces 1..4 at each vertex,
    ``(n, 4)`` or ``(n, 4, 2)``; ``stage[k]`` the regime (0..5; -1 when the sliding surfaces are none
    of the five regimes') of the stretch ending at vertex ``k``; ``sliding[k]`` which surfaces moved
    in it, ``(n, 4)`` booleans.
    """

    u: np.ndarray
    F: np.ndarray
    stage: np.ndarray
    sliding: np.ndarray
    surfaces: np.ndarray


# ----------------------------------------------------------------------------------------------
# along a line, event to event
# ----------------------------------------------------------------------------------------------

def _reactions(u, F, R, W):
    q = np.empty(4)
    q[0] = F - W * u[0] / R[0]
    q[1] = q[0] - W * u[1] / R[1]
    q[3] = F - W * u[3] / R[3]
    q[2] = q[3] - W * u[2] / R[2]
    return q


def _rates_of_mode(mode, sigma, R, W):
    """Rates ``(dF, du)`` per unit travel ``sigma`` with the surfaces of ``mode`` sliding (None if singular)."""
    S = [i for i in range(4) if mode[i] != 0]
    n = 1 + len(S)
    A = np.zeros((n, n))
    rhs = np.zeros(n)
    for col in range(n):
        dF = 1.0 if col == 0 else 0.0
        du = np.zeros(4)
        if col > 0:
            du[S[col - 1]] = 1.0
        dq = _reactions(du, dF, R, W)    # linear, with zero offset
        for row, i in enumerate(S):
            A[row, col] = dq[i]
        A[n - 1, col] = du.sum()
    rhs[n - 1] = sigma
    if abs(np.linalg.det(A)) < 1e-300:
        return None
    x = np.linalg.solve(A, rhs)
    du = np.zeros(4)
    for k, i in enumerate(S):
        du[i] = x[k + 1]
    return x[0], du


def _mode(u, F, sigma, R, m, d, W, tol_q, tol_u):
    """The consistent sliding mode for motion in direction ``sigma``: ``(dF, du)`` or None."""
    q = _reactions(u, F, R, W)
    options = []
    for i in range(4):
        opts = [0]
        for s in (1, -1):
            if q[i] * s >= m[i] - tol_q and u[i] * s < d[i] - tol_u:
                opts.append(s)
        options.append(opts)
    found = []
    for mode in itertools.product(*options):
        if not any(mode):
            continue
        sol = _rates_of_mode(mode, sigma, R, W)
        if sol is None:
            continue
        dF, du = sol
        dq = _reactions(du, dF, R, W)
        scale = 1e-9 * (1.0 + abs(dF) / W)
        ok = all(du[i] * mode[i] >= -scale for i in range(4) if mode[i])
        for j in range(4):
            if mode[j] == 0:
                for s in options[j][1:]:
                    ok = ok and dq[j] * s <= scale * W
        if ok:
            found.append((dF, du))
    if not found:
        return None
    dF, du = found[0]
    for dF2, du2 in found[1:]:
        if abs(dF2 - dF) > 1e-8 * (W + abs(dF)) or np.max(np.abs(du2 - du)) > 1e-8:
            raise RuntimeError(f"two sliding modes with different rates at u = {u}, F = {F}")
    return dF, du


def solve_path(bearing, targets, max_events: int = 100000) -> QuasiStaticPath:
    """Drive the bearing from rest through the total displacements ``targets`` (m), event to event.

    Parameters
    ----------
    bearing : isoslide.model.tfp.TripleFrictionPendulum
        Its radii, constant friction ``mu``, limits and weight are used.
    targets : sequence of float
        Turning points of the imposed displacement, reached in order along straight stretches.
    max_events : int
        Bound on the number of events.

    Returns
    -------
    QuasiStaticPath
        Every vertex of the path (events and targets), including the vertical stretches where the
        force changes with every surface stuck (``stage`` 0).

    Raises
    ------
    ValueError
        When a target lies beyond the bearing's total travel ``2 d1 + d2 + d3``.
    """
    R, m, d, W = _surfaces(bearing)
    tol_q, tol_u = 1e-10 * W, 1e-12 * float(d.max())
    u, F, U = np.zeros(4), 0.0, 0.0
    rec_u, rec_F, rec_stage, rec_slide, rec_surf = [0.0], [0.0], [0], [np.zeros(4, bool)], [u.copy()]
    events = 0
    for target in targets:
        target = float(target)
        while abs(target - U) > tol_u:
            events += 1
            if events > max_events:
                raise RuntimeError(f"more than max_events = {max_events} events")
            sigma = 1.0 if target > U else -1.0
            mode = _mode(u, F, sigma, R, m, d, W, tol_q, tol_u)
            q = _reactions(u, F, R, W)
            if mode is None:                              # every surface sticks: the force alone moves
                gaps = [m[j] - sigma * q[j] for j in range(4) if u[j] * sigma < d[j] - tol_u]
                if not gaps:
                    raise ValueError(f"target = {target!r} m lies beyond the bearing's total travel "
                                     f"{float(d.sum())!r} m (every surface at its restrainer)")
                F += sigma * max(min(gaps), 0.0)
                moving = np.zeros(4, bool)
                stage = 0
            else:
                dF, du = mode
                dq = _reactions(du, dF, R, W)
                h, snap = abs(target - U), None
                for j in range(4):
                    if abs(du[j]) <= 1e-12:
                        if abs(dq[j]) > 1e-12 * W:
                            s = 1.0 if dq[j] > 0 else -1.0
                            if u[j] * s < d[j] - tol_u:
                                hj = max((s * m[j] - q[j]) / dq[j], 0.0)
                                if hj < h:
                                    h, snap = hj, None
                    else:
                        s = 1.0 if du[j] > 0 else -1.0
                        hj = max((s * d[j] - u[j]) / du[j], 0.0)
                        if hj < h:
                            h, snap = hj, (j, s * d[j])
                u = u + h * du
                F += h * dF
                U = target if h == abs(target - U) and snap is None else U + sigma * h
                if snap is not None:
                    u[snap[0]] = snap[1]
                moving = np.abs(du) > 1e-12
                mid = u - 0.5 * h * du
                at_stop = abs(abs(mid[0]) - d[0]) <= tol_u and abs(abs(mid[3]) - d[3]) <= tol_u
                stage = _stage(tuple(np.flatnonzero(moving)), at_stop)
                if h <= tol_u:
                    continue
            rec_u.append(U)
            rec_F.append(F)
            rec_stage.append(stage)
            rec_slide.append(moving)
            rec_surf.append(u.copy())
    return QuasiStaticPath(np.array(rec_u), np.array(rec_F), np.array(rec_stage), np.array(rec_slide),
                           np.array(rec_surf))


def cycle(bearing, amplitude: float, cycles: int = 1) -> QuasiStaticPath:
    """From rest to ``amplitude`` (m), then ``cycles`` full cycles ``-A``, ``+A`` (:func:`solve_path`)."""
    A = float(amplitude)
    return solve_path(bearing, [A] + [-A, A] * int(cycles))


# ----------------------------------------------------------------------------------------------
# in the plane, implicit increments
# ----------------------------------------------------------------------------------------------

def _rim(q, un, R, W, m, d):
    """Minimiser of ``-q.u + m |u - un|`` on the circle ``|u| = d`` and the tangent ``du/dq``."""
    def point(th):
        return d * np.array([math.cos(th), math.sin(th)])

    def dg(th):
        u = point(th)
        up = np.array([-u[1], u[0]])
        w = u - un
        nw = math.hypot(w[0], w[1])
        return -q @ up + (m * (w @ up) / nw if nw > 0.0 else 0.0)

    def g(th):
        u = point(th)
        return -q @ u + m * math.hypot(*(u - un))

    t = q - W * un / R
    th0 = math.atan2(t[1], t[0])
    grid = th0 + np.linspace(-math.pi, math.pi, 129)[:-1]
    k = int(np.argmin([g(th) for th in grid]))
    step = grid[1] - grid[0]
    a, b = grid[k] - step, grid[k] + step
    th = grid[k]
    if dg(a) < 0.0 < dg(b):
        th = brentq(dg, a, b, xtol=1e-15, rtol=1e-15)
    elif dg(th) != 0.0:
        lo, hi = (a, th) if dg(th) > 0.0 else (th, b)
        if dg(lo) < 0.0 < dg(hi):
            th = brentq(dg, lo, hi, xtol=1e-15, rtol=1e-15)
    u = point(th)
    up = np.array([-u[1], u[0]])
    w = u - un
    nw = math.hypot(w[0], w[1])
    g2 = q @ u
    if nw > 0.0:
        g2 += m * ((up @ up - w @ u) / nw - (w @ up) ** 2 / nw ** 3)
    J = np.outer(up, up) / g2 if g2 > 0.0 else np.zeros((2, 2))
    return u, J


def _surface_step(q, un, R, W, m, d):
    """A surface's displacement after an increment driven by ``q`` from ``un``, and ``du/dq``.

    The increment minimises ``W |u|^2 / (2 R) - q.u + m |u - un|`` over ``|u| <= d`` (backward
    Euler for the pendulum with circular friction and a circular restrainer).
    """
    t = q - W * un / R
    nt = math.hypot(t[0], t[1])
    if nt <= m:
        return un.copy(), np.zeros((2, 2))
    e = t / nt
    u = un + (nt - m) * R / W * e
    if math.hypot(u[0], u[1]) <= d:
        P = np.outer(e, e)
        return u, R / W * (P + (1.0 - m / nt) * (np.eye(2) - P))
    nun = math.hypot(un[0], un[1])
    if nun >= d * (1.0 - 1e-13):
        h = un / nun
        tn = t @ h
        if tn > 0.0 and math.hypot(*(t - tn * h)) <= m:     # held by the restrainer and friction
            return un.copy(), np.zeros((2, 2))
    return _rim(q, un, R, W, m, d)


def _chain(F, un, R, m, d, W):
    """Surface displacements for force ``F`` from the previous state ``un`` (4, 2); total and Jacobian."""
    u = np.empty((4, 2))
    u[0], J0 = _surface_step(F, un[0], R[0], W, m[0], d[0])
    u[3], J3 = _surface_step(F, un[3], R[3], W, m[3], d[3])
    u[1], J1 = _surface_step(F - W * u[0] / R[0], un[1], R[1], W, m[1], d[1])
    u[2], J2 = _surface_step(F - W * u[3] / R[3], un[2], R[2], W, m[2], d[2])
    eye = np.eye(2)
    J = J0 + J1 @ (eye - W / R[0] * J0) + J3 + J2 @ (eye - W / R[3] * J3)
    return u, u.sum(axis=0), J


def _solve_increment(U_t, F, un, R, m, d, W, tol):
    """The force and surface displacements at total displacement ``U_t``.

    Newton's method on the force with a backtracking line search; where every surface sticks
    (no slope) or the line search fails, a bracketed root search along the residual's direction,
    along which the total displacement grows monotonically.
    """
    u, U, J = _chain(F, un, R, m, d, W)
    r = U - U_t
    for _ in range(200):
        nr = math.hypot(r[0], r[1])
        if nr <= tol:
            return F, u
        if np.max(np.abs(J)) * W > 1e-12 * R.max():
            step = -np.linalg.lstsq(J, r, rcond=1e-12)[0]
            alpha = 1.0
            while alpha > 1e-6:
                u2, U2, J2 = _chain(F + alpha * step, un, R, m, d, W)
                r2 = U2 - U_t
                if math.hypot(r2[0], r2[1]) < (1.0 - 1e-4 * alpha) * nr:
                    break
                alpha *= 0.5
            if alpha > 1e-6:
                F, u, J, r = F + alpha * step, u2, J2, r2
                continue
        e = -r / nr

        def along(s, e=e, F=F):
            return (_chain(F + s * e, un, R, m, d, W)[1] - U_t) @ e

        hi = W * nr / R.sum()
        for _ in range(200):
            if along(hi) > 0.0:
                break
            hi *= 2.0
        else:
            raise RuntimeError(f"no force reaches U = {U_t} from F = {F}")
        s = brentq(along, 0.0, hi, xtol=1e-15 * W, rtol=1e-15)
        F = F + s * e
        u, U, J = _chain(F, un, R, m, d, W)
        r = U - U_t
    raise RuntimeError(f"the increment to U = {U_t} did not converge (residual {math.hypot(*r):g} m)")


def solve_planar(bearing, points) -> QuasiStaticPath:
    """Drive the bearing in the plane from rest through the displacements ``points`` (m, shape (n, 2)).

    Each increment between consecutive points is straight and solved implicitly (exact along a
    straight line; along a curve the points should be close).  The first point is the rest position's
    first target (rest is ``(0, 0)``, not included in ``points``).

    Returns
    -------
    QuasiStaticPath
        ``u``, ``F`` of shape ``(n + 1, 2)`` (rest first), ``surfaces`` ``(n + 1, 4, 2)``.

    Raises
    ------
    ValueError
        When a point lies beyond the bearing's total travel ``2 d1 + d2 + d3``.
    """
    R, m, d, W = _surfaces(bearing)
    pts = np.asarray(points, dtype=float).reshape(-1, 2)
    reach = float(d.sum())
    tol = 1e-13 * reach
    F = np.zeros(2)
    un = np.zeros((4, 2))
    rec_u, rec_F, rec_stage, rec_slide, rec_surf = [np.zeros(2)], [F.copy()], [0], [np.zeros(4, bool)], [un]
    for p in pts:
        if math.hypot(p[0], p[1]) > reach * (1.0 + 1e-12):
            raise ValueError(f"point {p.tolist()} lies beyond the bearing's total travel {reach!r} m")
        F, u = _solve_increment(p, F, un, R, m, d, W, tol)
        moving = np.hypot(*(u - un).T) > 1e-12 * reach
        at_stop = all(math.hypot(*u[i]) >= d[i] * (1.0 - 1e-12) and math.hypot(*un[i]) >= d[i] * (1.0 - 1e-12)
                      for i in (0, 3))
        rec_u.append(p.copy())
        rec_F.append(F.copy())
        rec_stage.append(_stage(tuple(np.flatnonzero(moving)), at_stop))
        rec_slide.append(moving)
        rec_surf.append(u)
        un = u
    return QuasiStaticPath(np.array(rec_u), np.array(rec_F), np.array(rec_stage), np.array(rec_slide),
                           np.array(rec_surf))


def line_points(turns, direction: float, n: int = 50) -> np.ndarray:
    """Points along the line at angle ``direction`` (rad) through the turning displacements ``turns`` (m).

    From rest to ``turns[0]``, then to each next turning point, ``n`` equal increments per stretch.
    """
    e = np.array([math.cos(direction), math.sin(direction)])
    s, out = 0.0, []
    for t in turns:
        out.extend(np.linspace(s, t, n + 1)[1:])
        s = t
    return np.outer(out, e)


def orbit_points(radius: float, n: int = 360, cycles: int = 2, start: float = 0.0, clockwise: bool = False,
                 approach: int = 20) -> np.ndarray:
    """From rest straight out to ``radius`` (m) at angle ``start`` (rad), then ``cycles`` turns of the circle.

    ``approach`` increments out, ``n`` per turn.
    """
    out = np.linspace(0.0, radius, approach + 1)[1:]
    first = np.outer(out, [math.cos(start), math.sin(start)])
    sign = -1.0 if clockwise else 1.0
    th = start + sign * 2.0 * math.pi * np.arange(1, n * cycles + 1) / n
    return np.vstack([first, radius * np.column_stack([np.cos(th), np.sin(th)])])


def path_work(path: QuasiStaticPath, first: int = 0, last: int | None = None) -> float:
    """Work (J), the integral of ``F . du``, done on the bearing between vertices ``first`` and ``last`` (trapezoids)."""
    u = path.u[first:last]
    F = path.F[first:last]
    du = np.diff(u, axis=0)
    Fm = 0.5 * (F[1:] + F[:-1])
    return float(np.sum(Fm * du))
