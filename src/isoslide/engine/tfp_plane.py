r"""A triple friction pendulum in the plane whose friction rises with speed: circular friction and restrainers.

The bearing is :mod:`isoslide.engine.tfp_flow`'s (surfaces indexed 0..3 bottom to top: surface 1 of
radius ``L2``, the inner surfaces 2 and 3 of radius ``L1``, surface 4 of radius ``L3``, each with the
law of Constantinou, Mokha and Reinhorn (1990) of its own sliding speed), with every quantity a
vector of the plane.  Per unit normal-force factor, surface ``i`` has its displacement ``u_i``
(``x = sum u_i``, the slab's displacement over the ground), the slope ``s_i`` of the load's path on it
(``s_0 = k_0 u_0``, ``s_1 = s_0 + k_1 u_1``, ``s_3 = k_3 u_3``, ``s_2 = s_3 + k_2 u_2``, ``k_i = M_b g /
L_i``: an inner surface rides on its outer surface's plate) and its reaction ``q_i = F - s_i`` under the
bearing force ``F``.  Friction is isotropic (circular), so a surface

* sticks (``u_i' = 0``) while ``|q_i| <= Q_slow,i`` (true stick at its breakaway level);
* slides beyond it along its reaction at the speed its law gives, ``u_i' = V_i(|q_i|) q_i/|q_i|``,
  ``V_i(q) = -ln((Q_fast,i - q)/(Q_fast,i - Q_slow,i))/a_i``;
* resting on its restrainer (a circle ``|u_i| = d_i``) and pushed outward (``q_i . o_i >= 0``,
  ``o_i = u_i/|u_i|``), takes the push on the restrainer and slides round the rim under the tangential
  part ``q_t = q_i . t_i`` (``t_i`` the rim's tangent): ``u_i' = V_i(|q_t|) sign(q_t) t_i``.

Each surface's velocity is the gradient of a convex potential of its reaction (:func:`_surface`), so
while the slab moves at ``x'`` the force is the unique minimiser of ``sum_i phi_i(F - s_i) - x' . F``,
the root of ``sum_i u_i'(F) = x'`` (:func:`force`, Newton's method kept descending on that
potential): no choice of a sliding set, and two surfaces sliding at once (the inner pair of equal
laws, a surface and the one it rides on) share the slab's velocity through their laws.  As along a
line, the split relaxes fast once the surfaces slide fast, and the system is integrated by the
implicit Radau IIA method (:func:`scipy.integrate.solve_ivp`) at :mod:`~isoslide.engine.tfp_flow`'s
tolerances.  A slab at rest is held while the force that holds it lies in every surface's stick set
(the disk ``|q_i| <= Q_slow,i``, swept outward on a restrainer): the common stick set ``S``.  It breaks
away when that force leaves ``S``, in the direction of the surfaces' speeds under it.  A moving slab
whose speed falls below :data:`STOP_SPEED`, or whose velocity turns across its direction at the
start of the phase, has stopped; there the interfaces at rest choose their modes together.

The building and the contents are the planar kernel's (:mod:`isoslide.engine.planar_kernel`: any
floor, storeys, Coulomb or Stribeck contents sliding in the plane, vertical motion through the
normal-force factor), whose right-hand side takes the bearing force through the hysteretic slots of
its state: ``nz F`` for a moving slab, the holding force of a held one.  The integrated state is
that state with the four surface displacements (``(4, 2)``) appended.  Events end each integration:
the slab's and the contents' stops and breakaways, a surface reaching its restrainer (it is set on
it) or leaving it, and the excitation's breakpoints.  An inner surface reaching its restrainer is
the bearing's displacement capacity (the run stops with the ``capacity`` flag).

Settlement.  As along a line, a surface whose reaction lies between its slow and fast levels creeps
at the law's small speed and may never stop in finite time, so a slab that creeps after the
excitation is never held.  A run is settled once, after the excitation, the slab is held, the
contents stuck, and the held building's modal bound keeps both the contents' demand within their
limit and the force that holds the slab within the disk about zero that ``S`` contains (so nothing
can move again); a run whose slab still creeps at the horizon ends there, unsettled.

Units: time ``T_p``, lengths ``a_p T_p^2``, forces ``M_b a_p`` (per unit normal-force factor), speeds
``a_p T_p``; the rates ``a`` in ``1/(a_p T_p)``.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from scipy.integrate import solve_ivp

from .. import jit_cache
from . import building_kernel as bk
from . import planar_kernel as pk
from .tfp_flow import (ATOL_FACTOR, GAP_FLOOR, H_MAX, MAX_PHASES, RTOL_FACTOR, RTOL_FLOOR, Surfaces, _jacobian,
                       _law_speed, phase_end, stage)
from .tfp_flow import _slopes as _chain

STOP_SPEED = 1e-10
"""A slide whose speed falls below this (units of ``a_p T_p``) has stopped (as in the planar kernel)."""
TURN_STOP = 1e-8
"""A slide whose velocity turns across its direction at the start of the phase has stopped there when its
speed is below this (units of ``a_p T_p``)."""
START_SPEED = 1e-20
"""The slab's speed (units of ``a_p T_p``) below which the force is taken at this speed along the
direction the slab starts in: the edge of ``S`` it leaves from (the limit of the root as ``x' -> 0``)."""
W_IMPLICIT = 1e-7
"""While the slab or a sliding block is slower than this (units of ``a_p T_p``) the phase is stepped
explicitly (DOP853): their friction turns with their velocity, whose direction at the start of a slide
the implicit method's trial states cannot resolve; past it, the implicit method (Radau) steps the
bearing's stiff split."""
RIM = 1e-6
"""A surface within ``RIM d_i`` of its restrainer rests on it (and is set there); it has left it once
``|u_i| < (1 - 2 RIM) d_i``.  Sliding round the rim keeps ``|u_i|`` exactly in the model and to the
integrator's error in the steps, far within this band."""
HELD = 1e-12
"""Round-off (relative to the largest slow strength) allowed to a holding force outside ``S``."""
NEWTON_ITERATIONS = 100
"""Most Newton iterations of :func:`force`."""
INNER = (1, 2)
"""The inner surfaces: one on its restrainer is the bearing's displacement capacity."""

INT_RESULTS = pk.INT_RESULTS + ("stage_max", "capacity")
"""The integer results of :func:`run`, in order: the planar kernel's, the peak regime and the capacity flag."""
FLOAT_RESULTS = pk.FLOAT_RESULTS
"""The float results of :func:`run`, in order (the planar kernel's)."""


@njit(cache=True)
def _slopes(T, u, sl):
    """Slopes ``s_i`` ((4, 2)) of the surfaces at the displacements ``u`` ((4, 2)); ``T`` the laws' table.

    Each component is the line's chain (:func:`isoslide.engine.tfp_flow._slopes`).
    """
    for c in range(2):
        _chain(T, u[:, c], sl[:, c])


@njit(cache=True)
def _law_potential(gap, span, rate):
    """``int_{Q_slow}^{Q_fast - gap} V(q) dq``: the potential whose derivative is the law's speed.

    ``(g ln(g/span) - g + span)/a`` with ``g = gap``, summed as its series in ``1 - g/span`` near the
    slow level (where the closed form cancels), continued with the law's linear continuation below
    ``GAP_FLOOR span`` (:func:`isoslide.engine.tfp_flow._law_speed`).
    """
    g0 = GAP_FLOOR * span
    g = max(gap, g0)
    x = 1.0 - g / span
    if x < 0.1:
        total = 0.0
        term = x
        for k in range(2, 40):
            term *= x
            total += term / (k * (k - 1))
            if term < 1e-18 * total:
                break
        val = span * total / rate
    else:
        val = (g * math.log(g / span) - g + span) / rate
    if gap < g0:
        w = g0 - gap
        val += (-math.log(GAP_FLOOR) * w + 0.5 * w * w / g0) / rate
    return val


@njit(cache=True)
def _surface(T, i, rim, ox, oy, qx, qy, v, J):
    """Surface ``i``'s velocity under its reaction ``q`` (into ``v``), its Jacobian added to ``J``; returns its potential.

    ``rim``: resting on its restrainer of outward direction ``o``.  Zero in its stick set.
    """
    fast, slow, a = T[1, i], T[2, i], T[3, i]
    span = fast - slow
    v[0] = 0.0
    v[1] = 0.0
    if rim and qx * ox + qy * oy >= 0.0:
        tx, ty = -oy, ox
        qt = qx * tx + qy * ty
        r = abs(qt)
        if r <= slow:
            return 0.0
        gap = fast - r
        s = _law_speed(gap, span, a)
        if qt < 0.0:
            s = -s
        v[0] = s * tx
        v[1] = s * ty
        d = 1.0 / (a * max(gap, GAP_FLOOR * span))
        J[0, 0] += d * tx * tx
        J[0, 1] += d * tx * ty
        J[1, 0] += d * tx * ty
        J[1, 1] += d * ty * ty
        return _law_potential(gap, span, a)
    r = math.hypot(qx, qy)
    if r <= slow:
        return 0.0
    gap = fast - r
    s = _law_speed(gap, span, a)
    nx = qx / r
    ny = qy / r
    v[0] = s * nx
    v[1] = s * ny
    d = 1.0 / (a * max(gap, GAP_FLOOR * span))
    c = s / r
    J[0, 0] += d * nx * nx + c * (1.0 - nx * nx)
    J[0, 1] += (d - c) * nx * ny
    J[1, 0] += (d - c) * nx * ny
    J[1, 1] += d * ny * ny + c * (1.0 - ny * ny)
    return _law_potential(gap, span, a)


@njit(cache=True)
def _outward(u, rim, o):
    """Outward directions ``o`` ((4, 2)) of the surfaces on their restrainers (zero for the others)."""
    for i in range(4):
        o[i, 0] = 0.0
        o[i, 1] = 0.0
        if rim[i]:
            r = math.hypot(u[i, 0], u[i, 1])
            if r > 0.0:
                o[i, 0] = u[i, 0] / r
                o[i, 1] = u[i, 1] / r


@njit(cache=True)
def _flow(T, rim, o, sl, fx, fy, vs, J):
    """Every surface's velocity under the force ``(fx, fy)`` (into ``vs`` (4, 2)), their sum's Jacobian ``J``; returns the potential."""
    J[:, :] = 0.0
    v = np.empty(2)
    phi = 0.0
    for i in range(4):
        phi += _surface(T, i, rim[i], o[i, 0], o[i, 1], fx - sl[i, 0], fy - sl[i, 1], v, J)
        vs[i, 0] = v[0]
        vs[i, 1] = v[1]
    return phi


@njit(cache=True)
def _load(rim, ox, oy, qx, qy):
    """The part of a surface's reaction ``q`` its friction carries: ``|q|``, or ``|q . t|`` on its restrainer pushed outward."""
    if rim and qx * ox + qy * oy >= 0.0:
        return abs(-qx * oy + qy * ox)
    return math.hypot(qx, qy)


@njit(cache=True)
def _gap(T, i, rim, ox, oy, qx, qy):
    """How far surface ``i``'s reaction ``q`` lies inside its fast level (the law's ``Q_fast - |q|``, :func:`_load`)."""
    return T[1, i] - _load(rim, ox, oy, qx, qy)


@njit(cache=True)
def _keeps_room(T, rim, o, sl, fx, fy, nx, ny):
    """Whether the force moving from ``f`` to ``n`` keeps every surface a tenth of its room to its fast level.

    Newton's step from the gentle side of the laws would otherwise land next to a fast level, where
    the law is so steep that the next steps fall below the force's round-off.
    """
    for i in range(4):
        g0 = _gap(T, i, rim[i], o[i, 0], o[i, 1], fx - sl[i, 0], fy - sl[i, 1])
        g1 = _gap(T, i, rim[i], o[i, 0], o[i, 1], nx - sl[i, 0], ny - sl[i, 1])
        if g1 < 0.1 * min(max(g0, 0.0), T[1, i] - T[2, i]):
            return False
    return True


@njit(cache=True)
def _inside(T, rim, o, sl, fx, fy, room):
    """``f`` when every surface's reaction there lies inside its fast level; else a point where each has ``room`` of its span.

    The point comes from projections of ``f`` on the most violated surface's set of reactions within
    ``Q_fast - room (Q_fast - Q_slow)`` (at most 400), which reach the sets' intersection when it
    is not empty (a trial state of the integrator may have none: the last point is returned).
    """
    if _all_gaps(T, rim, o, sl, fx, fy):
        return fx, fy
    for _ in range(400):
        worst = 0.0
        arg = -1
        for i in range(4):
            lim = T[1, i] - room * (T[1, i] - T[2, i])
            over = T[1, i] - _gap(T, i, rim[i], o[i, 0], o[i, 1], fx - sl[i, 0], fy - sl[i, 1]) - lim
            if over > worst:
                worst = over
                arg = i
        if arg < 0:
            break
        lim = T[1, arg] - room * (T[1, arg] - T[2, arg])
        qx = fx - sl[arg, 0]
        qy = fy - sl[arg, 1]
        if rim[arg] and qx * o[arg, 0] + qy * o[arg, 1] >= 0.0:
            tx, ty = -o[arg, 1], o[arg, 0]
            qt = qx * tx + qy * ty
            cut = qt - (lim if qt > 0.0 else -lim)
            fx -= cut * tx
            fy -= cut * ty
        else:
            r = math.hypot(qx, qy)
            fx = sl[arg, 0] + qx * lim / r
            fy = sl[arg, 1] + qy * lim / r
    return fx, fy


@njit(cache=True)
def _start(T, rim, o, sl, fx, fy):
    """A start for Newton's iteration: ``f`` itself when every surface has room there.

    Else :func:`_inside` for rooms of a half down to a millionth of the surfaces' spans (the sets of
    larger rooms may not meet).
    """
    for room in (0.5, 0.1, 1e-2, 1e-3, 1e-6):
        if _all_gaps(T, rim, o, sl, fx, fy):
            break
        fx, fy = _inside(T, rim, o, sl, fx, fy, room)
    return fx, fy


@njit(cache=True)
def _all_gaps(T, rim, o, sl, fx, fy):
    """Whether every surface's reaction at ``f`` lies inside its fast level."""
    for i in range(4):
        if _gap(T, i, rim[i], o[i, 0], o[i, 1], fx - sl[i, 0], fy - sl[i, 1]) <= 0.0:
            return False
    return True


@njit(cache=True)
def _residual(vs, xdx, xdy):
    """``sum_i u_i' - x'`` and the round-off scale of that sum."""
    rx = vs[0, 0] + vs[1, 0] + vs[2, 0] + vs[3, 0] - xdx
    ry = vs[0, 1] + vs[1, 1] + vs[2, 1] + vs[3, 1] - xdy
    size = abs(xdx) + abs(xdy)
    for i in range(4):
        size += abs(vs[i, 0]) + abs(vs[i, 1])
    return rx, ry, size


@njit(cache=True)
def _newton(T, rim, o, sl, xdx, xdy, fx, fy, F):
    """Newton's iteration of :func:`_force` from ``f`` (into ``F``); returns whether it reached round-off.

    Where a surface's reaction nears its fast level (a tenth of its span or closer) off its restrainer,
    its law is steep across its circle and gentle along it, so the root lies in a thin curved valley;
    there the step is taken in polar coordinates about that surface's slope (its reaction's length and
    angle), which follows the circle instead of leaving it along its tangent.
    """
    vs = np.empty((4, 2))
    J = np.empty((2, 2))
    scale = 1.0
    for i in range(4):
        scale = max(scale, math.hypot(sl[i, 0], sl[i, 1]) + T[1, i])
    phi = _flow(T, rim, o, sl, fx, fy, vs, J) - xdx * fx - xdy * fy
    rx, ry, size = _residual(vs, xdx, xdy)
    res = math.hypot(rx, ry)
    done = False
    for _ in range(NEWTON_ITERATIONS):
        if res <= 4e-16 * size:
            done = True
            break
        # the steepest surface off its restrainer, if near its fast level
        ref = -1
        least = math.inf
        for i in range(4):
            qx = fx - sl[i, 0]
            qy = fy - sl[i, 1]
            if rim[i] and qx * o[i, 0] + qy * o[i, 1] >= 0.0:
                continue
            g = _gap(T, i, rim[i], o[i, 0], o[i, 1], qx, qy)
            if g < 0.1 * (T[1, i] - T[2, i]) and g < least:
                least = g
                ref = i
        mu = 1e-12 * (J[0, 0] + J[1, 1])
        if ref >= 0:
            qx = fx - sl[ref, 0]
            qy = fy - sl[ref, 1]
            rho = math.hypot(qx, qy)
            ex, ey = qx / rho, qy / rho
            # columns: dF/drho = e, dF/dtheta = rho t
            a = J[0, 0] * ex + J[0, 1] * ey
            c = J[1, 0] * ex + J[1, 1] * ey
            b = rho * (-J[0, 0] * ey + J[0, 1] * ex)
            d = rho * (-J[1, 0] * ey + J[1, 1] * ex)
            det = a * d - b * c
            if det != 0.0 and math.isfinite(det):
                drho = -(d * rx - b * ry) / det
                dth = -(-c * rx + a * ry) / det
            else:
                ref = -1
        if ref < 0:
            a, b, c, d = J[0, 0] + mu, J[0, 1], J[1, 0], J[1, 1] + mu
            det = a * d - b * c
            if det > 0.0 and math.isfinite(det):
                px = -(d * rx - b * ry) / det
                py = -(-c * rx + a * ry) / det
            else:
                # no surface moves: along the residual, as far as the slopes reach (halved below)
                px, py = -rx * scale / res, -ry * scale / res
            if not rx * px + ry * py < 0.0:
                px, py = -rx * scale / res, -ry * scale / res
            step = math.hypot(px, py)
            if step > scale:
                px *= scale / step
                py *= scale / step
            slope = rx * px + ry * py
        else:
            if abs(dth) > 0.5:
                drho *= 0.5 / abs(dth)
                dth = 0.5 if dth > 0.0 else -0.5
            slope = -res * res
        t = 1.0
        accepted = False
        nx, ny, trial, tx, ty, tsize, tres = fx, fy, phi, rx, ry, size, res
        for _ in range(80):
            if ref < 0:
                nx = fx + t * px
                ny = fy + t * py
            else:
                r1 = rho + t * drho
                if r1 <= 0.0:
                    t *= 0.5
                    continue
                th = t * dth
                cs, sn = math.cos(th), math.sin(th)
                nx = sl[ref, 0] + r1 * (ex * cs - ey * sn)
                ny = sl[ref, 1] + r1 * (ey * cs + ex * sn)
            if _keeps_room(T, rim, o, sl, fx, fy, nx, ny):
                trial = _flow(T, rim, o, sl, nx, ny, vs, J) - xdx * nx - xdy * ny
                tx, ty, tsize = _residual(vs, xdx, xdy)
                tres = math.hypot(tx, ty)
                if tres < res or (ref < 0 and trial <= phi + 1e-4 * t * slope):
                    accepted = True
                    break
            t *= 0.5
        if not accepted or (nx == fx and ny == fy):
            _flow(T, rim, o, sl, fx, fy, vs, J)
            done = res <= 1e-12 * size
            break
        fx, fy, phi = nx, ny, trial
        rx, ry, size, res = tx, ty, tsize, tres
    F[0] = fx
    F[1] = fy
    return done


@njit(cache=True)
def _force(T, rim, u, xdx, xdy, gx, gy, F, vs):
    """The root ``F`` of ``sum_i u_i'(F) = x'`` (:func:`force`) and the surfaces' velocities there (``vs``, (4, 2)).

    ``(gx, gy)`` is the first guess.  Newton's method on the convex potential ``sum_i phi_i(F - s_i) -
    x' . F`` (:func:`_newton`): a step keeps every surface a tenth of its room to its fast level
    (:func:`_keeps_room`) and is taken whole when it reduces the residual (near the root, where the
    potential's own round-off would stall a descent test), else halved until the potential descends;
    the iteration ends when the residual reaches the round-off of the surfaces' speeds or stops
    decreasing.  A guess at or beyond a fast level (an implicit integrator's trial state) is first
    moved inside (:func:`_start`); an iteration from the guess that stalls short of the root starts
    again from a point with room on every surface (reached from the slopes' mean).

    The unknown is the reaction of the surface nearest its fast level at the guess, ``F - s_j``: a
    surface sliding fast has its speed set by the last digits of its reaction's gap to that level,
    which ``F - s_j`` keeps where ``F`` itself (of the size of the slopes, far larger on a stiff inner
    surface) would lose them.
    """
    sl = np.empty((4, 2))
    o = np.empty((4, 2))
    J = np.empty((2, 2))
    _slopes(T, u, sl)
    _outward(u, rim, o)
    fx = gx if math.isfinite(gx) else 0.0
    fy = gy if math.isfinite(gy) else 0.0
    ref = 0
    least = math.inf
    for i in range(4):
        g = _gap(T, i, rim[i], o[i, 0], o[i, 1], fx - sl[i, 0], fy - sl[i, 1])
        if g < least:
            least = g
            ref = i
    cx = sl[ref, 0]
    cy = sl[ref, 1]
    for i in range(4):
        sl[i, 0] = sl[i, 0] - cx if i != ref else 0.0
        sl[i, 1] = sl[i, 1] - cy if i != ref else 0.0
    fx -= cx
    fy -= cy
    fx, fy = _start(T, rim, o, sl, fx, fy)
    if not _newton(T, rim, o, sl, xdx, xdy, fx, fy, F):
        keep = F.copy()
        fx, fy = _start(T, rim, o, sl, 0.25 * (sl[0, 0] + sl[1, 0] + sl[2, 0] + sl[3, 0]),
                        0.25 * (sl[0, 1] + sl[1, 1] + sl[2, 1] + sl[3, 1]))
        if not _newton(T, rim, o, sl, xdx, xdy, fx, fy, F):
            _flow(T, rim, o, sl, F[0], F[1], vs, J)
            r1 = _residual(vs, xdx, xdy)
            _flow(T, rim, o, sl, keep[0], keep[1], vs, J)
            r0 = _residual(vs, xdx, xdy)
            if math.hypot(r0[0], r0[1]) < math.hypot(r1[0], r1[1]):
                F[0] = keep[0]
                F[1] = keep[1]
    _flow(T, rim, o, sl, F[0], F[1], vs, J)
    F[0] += cx
    F[1] += cy


@njit(cache=True)
def _speeds(T, rim, u, fx, fy, out):
    """Velocities ``out`` ((4, 2)) of the surfaces at ``u`` under the force ``(fx, fy)``."""
    sl = np.empty((4, 2))
    o = np.empty((4, 2))
    J = np.empty((2, 2))
    _slopes(T, u, sl)
    _outward(u, rim, o)
    _flow(T, rim, o, sl, fx, fy, out, J)


@njit(cache=True)
def _excess(T, rim, u, fx, fy):
    """How far the force ``(fx, fy)`` lies outside ``S`` (the largest excess of a surface's stick set; <= 0 inside)."""
    sl = np.empty((4, 2))
    o = np.empty((4, 2))
    _slopes(T, u, sl)
    _outward(u, rim, o)
    worst = -math.inf
    for i in range(4):
        worst = max(worst, _load(rim[i], o[i, 0], o[i, 1], fx - sl[i, 0], fy - sl[i, 1]) - T[2, i])
    return worst


def _grid(u) -> np.ndarray:
    """``u`` as a writable, contiguous (4, 2) float array (the compiled functions' one signature)."""
    a = np.ascontiguousarray(np.asarray(u, dtype=float).reshape(4, 2))
    return a if a.flags.writeable else a.copy()


def force(s: Surfaces, rim, u, xd, guess=(0.0, 0.0)) -> np.ndarray:
    """The bearing force ``F`` (per unit normal-force factor) at the displacements ``u`` ((4, 2)) and the slab's velocity ``xd``.

    ``rim`` marks the surfaces on their restrainers.  The root of ``sum_i u_i'(F) = x'``
    (module docstring); ``guess`` starts Newton's iteration.
    """
    F = np.empty(2)
    _force(s.table, np.asarray(rim, dtype=np.bool_), _grid(u), float(xd[0]), float(xd[1]), float(guess[0]),
           float(guess[1]), F, np.empty((4, 2)))
    return F


def speeds(s: Surfaces, rim, u, F) -> np.ndarray:
    """The surfaces' velocities ``u_i'`` ((4, 2)) at ``u`` under the force ``F`` (module docstring)."""
    out = np.empty((4, 2))
    _speeds(s.table, np.asarray(rim, dtype=np.bool_), _grid(u), float(F[0]), float(F[1]), out)
    return out


def excess(s: Surfaces, rim, u, F) -> float:
    """How far ``F`` lies outside the common stick set ``S`` at ``u`` (negative inside)."""
    return float(_excess(s.table, np.asarray(rim, dtype=np.bool_), _grid(u), float(F[0]), float(F[1])))


def on_rims(s: Surfaces, u) -> np.ndarray:
    """Which surfaces rest on their restrainers (``|u_i| >= (1 - RIM) d_i``)."""
    return np.linalg.norm(_grid(u), axis=1) >= s.limit * (1.0 - RIM)


class _Run:
    """The mutable state of a run between phases."""

    def __init__(self, tau, z):
        self.tau = tau
        self.z = z
        self.bm = 0.0
        self.im = 0.0
        self.e = np.array([1.0, 0.0])
        self.d = np.array([1.0, 0.0])
        self.umax = 0.0
        self.tpeak = tau
        self.angle = math.nan
        self.xmax = 0.0
        self.vmax = 0.0
        self.steps = 0
        self.events = 0
        self.iso_events = 0
        self.slipped = False
        self.moved = False
        self.stage_max = 0
        self.capacity = False
        self.settled = False
        self.rim = np.zeros(4, dtype=np.bool_)
        self.guess = np.zeros(2)


def run(P, ex, breakpoints, tau_start, tau_end, tau_stop, surfaces: Surfaces, rtol, settle, modal, hist_cap=0):
    """Integrate one planar scene on a triple friction pendulum whose friction rises with speed, from rest.

    Parameters
    ----------
    P : ndarray
        The kernel's parameters (:func:`isoslide.engine.building.parameters`, a triple pendulum); not modified.
    ex : tuple
        The excitation in the planar kernel's form (:func:`isoslide.engine.planar.excitation`).
    breakpoints : ndarray
        The excitation's breakpoints (integrations end there).
    tau_start, tau_end, tau_stop : float
        Start, end of the excitation and horizon (units of T_p).
    surfaces : isoslide.engine.tfp_flow.Surfaces
        The surfaces' laws.
    rtol : float
        Target relative error of the contents' peak; Radau runs at
        :data:`~isoslide.engine.tfp_flow.RTOL_FACTOR` of it.
    settle : bool
        Stop at settlement.
    modal : tuple
        The planar modal data ``(Wm, Cm, Vm, Lm, Wh, Ch, Vh, Lh)`` (:attr:`isoslide.engine.system.System.planar_modal`).
    hist_cap : int
        Most history rows (0: none).

    Returns
    -------
    tuple
        ``(ints, floats, hist)`` in the layout :data:`INT_RESULTS`, :data:`FLOAT_RESULTS`; history rows
        ``[tau, y..., bm, im, stage]`` in the planar kernel's layout of a hysteretic bearing, whose
        slots hold the bearing force ``nz F`` (or the force holding the slab).
    """
    Ph = np.array(P, dtype=float)
    Ph[bk.P_KIND] = bk.KIND_BILINEAR     # the planar right-hand side reads the bearing force from these slots
    n = int(P[bk.P_N])
    nb = pk.axis_size(n, True)
    ny = pk.state_size(n, True)
    U = 2 * nb
    na = 2 + 2 * n
    s = surfaces
    T = s.table
    _, _, _, _, Wh, Ch, _, _ = modal
    r_tol = max(RTOL_FLOOR, RTOL_FACTOR * rtol)
    a_tol = ATOL_FACTOR * r_tol
    thr = Ph[bk.P_THR]
    held_tol = HELD * float(s.slow.max())
    bps = sorted({float(t) for t in breakpoints if tau_start < t < tau_stop} | {float(tau_end), float(tau_stop)})
    st = _Run(float(tau_start), np.zeros(ny + 8))
    y = np.zeros(ny)
    out = np.zeros(ny)
    tmp = np.zeros(5 * ny)
    md = np.array([0.0, 1.0, 0.0, 0.0, 1.0, 0.0])
    F = np.empty(2)
    vs = np.empty((4, 2))
    fvs = np.empty((4, 2))
    hist = []

    def modes(bm, im, e, d):
        md[pk.M_BM], md[pk.M_E0], md[pk.M_E1] = bm, e[0], e[1]
        md[pk.M_IM], md[pk.M_I0], md[pk.M_I1] = im, d[0], d[1]
        return md

    def need(t, z, nz):
        """The force (over ``nz``) that holds the slab, the slab held, with the contents in ``md``'s mode."""
        y[:] = z[:ny]
        y[nb - 1] = y[2 * nb - 1] = 0.0
        gx, gy = pk.ground(t, ex)
        fx, fy = pk._bearing_need(md, y, gx, gy, Ph, nz, tmp)
        return np.array([fx, fy]) / nz

    def moving_force(z, d):
        """The force of a moving slab (the edge of ``S`` it leaves from below :data:`START_SPEED`); the surfaces' velocities into ``fvs``."""
        vx, vy = z[1], z[nb + 1]
        if math.hypot(vx, vy) < START_SPEED:
            vx, vy = START_SPEED * d[0], START_SPEED * d[1]
        u = z[ny:].reshape(4, 2)
        if not (np.all(np.isfinite(u)) and math.isfinite(vx) and math.isfinite(vy)):
            fvs[:, :] = math.nan
            return np.full(2, math.nan)
        _force(T, st.rim, _grid(u), vx, vy, st.guess[0], st.guess[1], F, fvs)
        st.guess[:] = F
        return F.copy()

    def evaluate(t, z, bm, im, e, d, dz=None):
        """Right-hand side (into ``dz``) in the modes ``(bm, im)``; returns ``(A_F, F)``."""
        modes(bm, im, e, d)
        nz = bk.normal(t, Ph)[0]
        Fz = need(t, z, nz) if im == 0.0 else moving_force(z, d)
        y[:] = z[:ny]
        y[nb - 1], y[2 * nb - 1] = nz * Fz[0], nz * Fz[1]
        AF = pk.deriv(md, t, y, Ph, ex, out, tmp)
        if dz is not None:
            dz[:ny] = out
            dz[nb - 1] = dz[2 * nb - 1] = 0.0
            if im == 0.0:
                dz[0] = dz[1] = dz[nb] = dz[nb + 1] = 0.0
                dz[ny:] = 0.0
            else:
                dz[ny:] = fvs.ravel()
        return np.array(AF), Fz

    def start_direction(f, u):
        """The direction a slab held by ``f`` at the edge of ``S`` or beyond it starts in: the surfaces' speeds under ``f``."""
        _speeds(T, st.rim, _grid(u), f[0], f[1], vs)
        v = vs.sum(axis=0)
        r = math.hypot(v[0], v[1])
        if r > 0.0:
            return v / r
        # on the edge to round-off: the outward normal of the surface whose stick set binds
        sl = np.empty((4, 2))
        _slopes(T, _grid(u), sl)
        best, arg = -math.inf, 0
        for i in range(4):
            q = f - sl[i]
            m = math.hypot(q[0], q[1]) - s.slow[i]
            if m > best:
                best, arg = m, i
        q = f - sl[arg]
        r = math.hypot(q[0], q[1])
        return q / r if r > 0.0 else st.d.copy()

    def select(free_b, free_i, force_i=False):
        """Modes of the interfaces at rest (fewest slides first), as the planar kernel's ``_select``."""
        z, t = st.z, st.tau
        u = z[ny:].reshape(4, 2)
        nz = bk.normal(t, Ph)[0]
        cands = [(sb, si) for si in ((1,) if force_i else (0, 1)) for sb in (0, 1)]
        cands.sort(key=lambda c: c[0] + c[1])
        for sb, si in cands:
            if (sb and not free_b) or (si and not free_i):
                continue
            bm = (1.0 if sb else 0.0) if free_b else st.bm
            im = (1.0 if si else 0.0) if free_i else st.im
            e, d = st.e.copy(), st.d.copy()
            for _ in range(2):
                if free_i and si:
                    modes(bm, 0.0, e, d)
                    d = start_direction(need(t, z, nz), u)
                if free_b and sb:
                    AF, _ = evaluate(t, z, 0.0, im, e, d)
                    r = math.hypot(AF[0], AF[1])
                    e = -AF / r if r > 0.0 else e
            ok = True
            if free_b and not sb:
                AF, _ = evaluate(t, z, 0.0, im, e, d)
                ok = math.hypot(AF[0], AF[1]) <= thr * nz
            if ok and free_i and not si:
                modes(bm, 0.0, e, d)
                ok = excess(s, st.rim, u, need(t, z, nz)) <= held_tol
            if ok and (sb or si):
                dz = np.zeros(ny + 8)
                evaluate(t, z, bm, im, e, d, dz)
                if sb and free_b and not (dz[U + 2] * e[0] + dz[U + 3] * e[1] > 0.0):
                    ok = False
                if si and free_i and not (dz[1] * d[0] + dz[nb + 1] * d[1] > 0.0):
                    ok = False
            if ok or (sb, si) == cands[-1]:
                st.bm, st.im, st.e, st.d = bm, im, e, d
                return

    def settled_now(z):
        """After the excitation, slab held and contents stuck: nothing moves again (module docstring)."""
        sl = np.empty((4, 2))
        _slopes(T, _grid(z[ny:]), sl)
        room = min(s.slow[i] - math.hypot(*sl[i]) for i in range(4))
        # a rigid superstructure has no states of its own that move (the implicit steps leave round-off in them)
        moving = Ph[bk.P_FLEX] != 0.0 and any(z[a * nb + i] != 0.0 for a in (0, 1) for i in range(2, na))
        if not moving:
            return room >= 0.0
        bx = pk._modal_bound(Wh, Ch, 0, z[:ny], 0, na)
        by = pk._modal_bound(Wh, Ch, 0, z[:ny], nb, na)
        if bx < 0.0 or by < 0.0 or math.hypot(bx, by) > thr:
            return False
        bx = pk._modal_bound(Wh, Ch, 1, z[:ny], 0, na)
        by = pk._modal_bound(Wh, Ch, 1, z[:ny], nb, na)
        return bx >= 0.0 and by >= 0.0 and math.hypot(bx, by) <= room

    def peak(t, z):
        uu = z[U:U + 2]
        r = math.hypot(uu[0], uu[1])
        if r > st.umax:
            st.umax, st.tpeak, st.angle = r, t, math.atan2(uu[1], uu[0])

    free_b = free_i = True
    force_i = False
    for _ in range(MAX_PHASES):
        if st.tau >= tau_stop:
            break
        st.rim = on_rims(s, st.z[ny:])
        if free_b or free_i:
            select(free_b, free_i, force_i)
        free_b = free_i = force_i = False
        bm, im, e, d = st.bm, st.im, st.e.copy(), st.d.copy()
        st.slipped |= bm != 0.0
        st.moved |= im != 0.0
        if st.tau >= tau_end and bm == 0.0 and im == 0.0 and settled_now(st.z):
            st.settled = True
            if settle:
                break
        t0 = st.tau
        t1 = phase_end(t0, bps, tau_end)

        def rhs(t, z, bm=bm, im=im, e=e, d=d):
            dz = np.empty(ny + 8)
            evaluate(t, z, bm, im, e, d, dz)
            return dz

        evs, kinds = [], []

        def add(fun, direction, kind, terminal=True, evs=evs, kinds=kinds):
            fun.terminal = terminal
            fun.direction = direction
            evs.append(fun)
            kinds.append(kind)

        if im == 0.0:
            u0 = _grid(st.z[ny:])

            def breakaway(t, z, bm=bm, e=e, d=d, u0=u0):
                modes(bm, 0.0, e, d)
                return excess(s, st.rim, u0, need(t, z, bk.normal(t, Ph)[0])) - held_tol
            add(breakaway, 1, ("breakaway",))
        else:
            v0 = np.array([st.z[1], st.z[nb + 1]])
            ref = v0 / math.hypot(*v0) if v0.any() else d
            add(lambda t, z: math.hypot(z[1], z[nb + 1]) - STOP_SPEED, -1, ("stop",))
            add(lambda t, z, ref=ref: z[1] * ref[0] + z[nb + 1] * ref[1], -1, ("turn",))
            for i in range(4):
                lim2 = s.limit[i] ** 2
                if st.rim[i]:
                    add(lambda t, z, i=i, lim2=lim2: z[ny + 2 * i] ** 2 + z[ny + 2 * i + 1] ** 2 - lim2 * (1.0 - 2.0 * RIM) ** 2,
                        -1, ("off", i))
                else:
                    add(lambda t, z, i=i, lim2=lim2: z[ny + 2 * i] ** 2 + z[ny + 2 * i + 1] ** 2 - lim2, 1,
                        ("restrainer", i))
        if bm == 0.0:
            def slip(t, z, im=im, e=e, d=d):
                AF, _ = evaluate(t, z, 0.0, im, e, d)
                return math.hypot(AF[0], AF[1]) - thr * bk.normal(t, Ph)[0]
            add(slip, 1, ("slip",))
        else:
            w0 = st.z[U + 2:U + 4].copy()
            wref = w0 / math.hypot(*w0) if w0.any() else e
            add(lambda t, z: math.hypot(z[U + 2], z[U + 3]) - STOP_SPEED, -1, ("stick",))
            add(lambda t, z, wref=wref: z[U + 2] * wref[0] + z[U + 3] * wref[1], -1, ("wturn",))
            add(lambda t, z: z[U] * z[U + 2] + z[U + 1] * z[U + 3], -1, ("peak",), terminal=False)
        # the implicit method once every sliding interface is past W_IMPLICIT (module docstring)
        pairs = [p for p, mode in ((1, im), (U + 2, bm)) if mode != 0.0]
        slow_pairs = [p for p in pairs if math.hypot(st.z[p], st.z[p + (nb if p == 1 else 1)]) < 0.5 * W_IMPLICIT]
        implicit = im != 0.0 and not slow_pairs
        for p in slow_pairs if im != 0.0 else ():
            q = p + (nb if p == 1 else 1)
            add(lambda t, z, p=p, q=q: math.hypot(z[p], z[q]) - W_IMPLICIT, 1, ("off",))
        for p in pairs if implicit else ():
            # slowing down again: back to the explicit steps before the direction turns fast
            q = p + (nb if p == 1 else 1)
            add(lambda t, z, p=p, q=q: math.hypot(z[p], z[q]) - 0.25 * W_IMPLICIT, -1, ("off",))
        if implicit:
            sol = solve_ivp(rhs, (t0, t1), st.z, method="Radau", events=evs, rtol=r_tol, atol=a_tol, max_step=H_MAX,
                            jac=lambda t, z, rhs=rhs, vel=[(p, p + (nb if p == 1 else 1)) for p in pairs]:
                            _jacobian(rhs, t, z, vel))
        else:
            sol = solve_ivp(rhs, (t0, t1), st.z, method="DOP853", events=evs, rtol=r_tol, atol=a_tol, max_step=H_MAX)
        if sol.status < 0:
            raise RuntimeError(f"the integration failed at tau = {sol.t[-1]!r}: {sol.message}")
        st.steps += max(len(sol.t) - 1, 1)
        for j in range(sol.y.shape[1]):
            zj = sol.y[:, j]
            st.vmax = max(st.vmax, math.hypot(zj[U + 2], zj[U + 3]))
            st.xmax = max(st.xmax, math.hypot(zj[0], zj[nb]))
            if bm != 0.0:
                peak(sol.t[j], zj)
            gs = 0
            Fj = None
            if im != 0.0:
                Fj = moving_force(zj, d)
                gs = stage(s, np.linalg.norm(_grid(zj[ny:]), axis=1), np.hypot(fvs[:, 0], fvs[:, 1]))
                st.stage_max = max(st.stage_max, gs)
            if len(hist) < hist_cap:
                row = zj[:ny].copy()
                nz = bk.normal(sol.t[j], Ph)[0]
                if Fj is None:
                    modes(bm, im, e, d)
                    Fj = need(sol.t[j], zj, nz)
                row[nb - 1], row[2 * nb - 1] = nz * Fj[0], nz * Fj[1]
                hist.append(np.concatenate(([sol.t[j]], row, [bm, im, gs])))
        for k, kind in enumerate(kinds):
            if kind[0] == "peak":
                for te, ye in zip(sol.t_events[k], sol.y_events[k], strict=True):
                    peak(te, ye)
        st.tau = float(sol.t[-1])
        st.z = np.array(sol.y[:, -1])
        if sol.status != 1:
            continue
        k = next(j for j, te in enumerate(sol.t_events) if len(te) and kinds[j][0] != "peak")
        kind = kinds[k]
        if kind[0] == "turn":
            # the slab's velocity turned across its direction at the phase's start: a stop if it vanished there
            kind = ("stop",) if math.hypot(st.z[1], st.z[nb + 1]) <= TURN_STOP else ("off",)
        elif kind[0] == "wturn":
            kind = ("stick",) if math.hypot(st.z[U + 2], st.z[U + 3]) <= TURN_STOP else ("off",)
        if kind[0] == "stop":
            v = np.array([st.z[1], st.z[nb + 1]])
            sp = math.hypot(v[0], v[1])
            st.d = v / sp if sp > 0.0 else d
            st.z[1] = st.z[nb + 1] = 0.0
            st.iso_events += 1
            free_i = True
            free_b = st.bm == 0.0
        elif kind[0] == "breakaway":
            st.iso_events += 1
            free_i = force_i = True
            free_b = st.bm == 0.0
        elif kind[0] == "restrainer":
            i = kind[1]
            ui = st.z[ny + 2 * i:ny + 2 * i + 2]
            ui *= s.limit[i] / math.hypot(ui[0], ui[1])
            if i in INNER:
                st.capacity = True
                break
        elif kind[0] == "slip":
            st.events += 1
            AF, _ = evaluate(st.tau, st.z, 0.0, im, e, d)
            r = math.hypot(AF[0], AF[1])
            st.bm, st.e = 1.0, (-AF / r if r > 0.0 else e)
        elif kind[0] == "stick":
            st.events += 1
            st.z[U + 2] = st.z[U + 3] = 0.0
            peak(st.tau, st.z)
            free_b = True
    else:
        raise RuntimeError(f"more than {MAX_PHASES} phases in one run; the last at tau = {st.tau!r}")
    if not st.settled:
        peak(st.tau, st.z)
    uu = st.z[U:U + 2]
    ints = np.array([st.steps, st.events, st.settled, st.slipped, len(hist), 0, st.iso_events, st.moved,
                     st.stage_max, st.capacity], dtype=np.int64)
    floats = np.array([st.umax, st.tpeak, st.angle, math.hypot(uu[0], uu[1]), st.tau, st.vmax, uu[0], uu[1],
                       st.xmax])
    width = 1 + ny + 3
    return ints, floats, np.array(hist).reshape(-1, width) if hist else np.zeros((0, width))


# numba reads the compiled code shipped with the package (isoslide.jit_cache) before compiling any of it
jit_cache.seed(_force)
