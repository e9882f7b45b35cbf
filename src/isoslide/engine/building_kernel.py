"""Compiled event-driven kernel of the general building (numba).

The general building of :mod:`isoslide.engine.building` (the paper's Fig. 1-a): a slab
on a hysteretic isolator, a rigid superstructure or a flexible one of ``n``
floors, and sliding contents on the slab (floor 0) or on floor ``k`` of the
superstructure.  Units: time ``T_p``, lengths ``a_p T_p^2``, accelerations
``a_p``, masses ``M_b``, forces ``M_b a_p``; primes are ``d/dtau``.

State ``y = [x, x', xs_1 .. xs_n, xs_1' .. xs_n', u, u', fh]`` (length
``2 n + 5``, :func:`state_size`): slab displacement relative to the ground,
the floors' displacements relative to the slab, block displacement relative to
its floor, and the hysteretic isolator force (a state of the bilinear bearing
only).  Two modes: the block's ``bm`` (0 stuck, +-1 sliding in that direction)
and the isolator's ``im`` (0 stuck sliding bearing or elastic bilinear
bearing, +-1 sliding or yielding).  Model parameters ``P`` (indices ``P_*``,
then the floor masses and the superstructure's fixed-base stiffness and
damping matrices from ``P_ARRAYS`` on) are set by
:func:`isoslide.engine.building.parameters`.

Forces: isolator ``F = kd x + cb x' + fh``, storey forces on the floors
``G = Ks xs + Cs xs'`` (fixed-base matrices, floors relative to the slab) and
their sum on the slab ``S = sum_j G_j``, friction of the block on its floor
``R`` (the block gets ``-R``)::

    slab            mb Ab = -F + S + [R on the base]
    floor j         m_j A_j = -G_j + [R on floor j]
    block           m (A_F + u'') = -R

with absolute accelerations ``Ab = p + x''``, ``A_j = Ab + xs_j''`` and the
floor's ``A_F``.  Every mode gives the accelerations explicitly
(:func:`_accels`): the mass matrix is diagonal.  A stuck block has
``R = -m A_F`` and stays stuck while ``|A_F| <= thr``; a sliding one
``R = m s phi(|u'|)``.  With one floor this is the slab and one
superstructure mass of the paper's Fig. 1-a, step for step.  A stuck sliding bearing holds the slab
(``x' = x'' = 0``) with the force ``fh = -mb p - kd x + S + [R on the base]``
while ``|fh| <= q``, and slides with ``fh = q sgn(x')``.  A bilinear bearing's
``fh`` follows ``fh' = ke x'`` until ``|fh| = q`` and stays at ``+-q`` until
``x'`` changes sign.

Transitions (every one located to ~1e-13 T_p by safeguarded Newton on the step
length, re-stepping from the accepted point): a stuck interface breaks away
when its demand reaches its limit (the demand's interior peaks are found as
roots of its rate); a sliding one stops when its speed returns to zero; a
bilinear bearing yields at ``|fh| = q`` and unloads when ``x'`` changes sign.
Breakaways and yielding keep every force continuous.  When a sliding interface
stops, the force on the other jumps, so the modes of the interfaces at rest are
chosen together (:func:`_select_modes`, in the order of
:func:`isoslide.engine.modes.candidates`): the first consistent combination in
the order all stuck, block stuck, bearing stuck, none stuck, where consistent
means every stuck interface's needed force is within its limit and every
sliding one accelerates in its own direction.

Settlement (:func:`_settled`): after the pulse, with the block stuck and the
isolator stuck or elastic, the free system is linear.  With at most one floor its energy ``E``
about its equilibrium cannot grow; every demand ``d = d0 + c.y`` obeys
``|d| <= |d0| + sqrt(2 E c' P^-1 c)`` (``P`` the energy's quadratic form).
Its modes give a second bound, ``|d| <= |d0| + sum_k |c.v_k| |a_k|`` (modal
coordinates ``a_k``, eigenvalues with ``Re lambda_k <= 0``), much sharper when
one mode dominates (a stiff superstructure's energy makes the first bound
large while hardly moving the floor); with several floors the modal bound
alone is used.  Once a bound puts every demand within its limit nothing can
slip or yield again.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .. import jit_cache
from ..model.friction import stribeck
from . import free_phase
from .modes import candidates
from .kernel import (ROOT_AT_TRIAL, ROOT_OPEN, C, NS, _hermite_max, _left_limit, _next_breakpoint, _next_step,
                     _step_factor, _step_target, bracket_open, bracket_step, copy_state, doubling_error,
                     end_state, hermite_root, scaled_error, stage_state)
from ..pulses import accel_at, jerk_at

Y_X, Y_XD, Y_XS = range(3)
"""Fixed state indices: slab displacement and velocity, the first floor's displacement."""

(P_MB, P_MST, P_M, P_KD, P_CB, P_KS, P_CS, P_Q, P_KE, P_THR, P_PI2, P_PI6, P_PI7, P_COULOMB, P_ROOF,
 P_KIND, P_FLEX, P_N, P_FLOOR, P_ZAMP, P_ZCODE, P_QS, P_QA, P_ZOFF, P_TFP, P_FHI, P_FLO, P_XNEXT,
 P_ROCK, P_RG, P_RK, P_RR, P_RE, P_REPS, P_RMUS, P_RMUK, P_HOLD) = range(37)
P_ARRAYS = 37
"""Start of the arrays in the model parameters: floor masses ``(n,)``, then ``Ks`` and ``Cs``
``(n, n)`` row by row, then a triple friction pendulum's surfaces (:data:`TFP_SIZE` values from
``P_TFP``; ``P_TFP = 0`` for any other isolator), then the vertical pulse's parameters (from
``P_ZOFF``); ``P_N`` holds ``n``, ``P_FLOOR`` the contents' floor (0 the slab), ``P_ZAMP`` the
vertical amplitude ``Pi17`` (0: no vertical motion) and ``P_ZCODE`` the vertical pulse's shape code
(:mod:`isoslide.pulses`).  ``P_Q`` is the isolator's strength (a sliding bearing's at high speed),
``P_QS`` its breakaway strength (``P_Q`` unless a sliding bearing's friction rises with speed) and
``P_QA`` the rate ``Pi23`` of that rise (0: constant).  ``P_KE`` is a bilinear bearing's elastic
stiffness; for a triple friction pendulum :func:`run` keeps, in its own copy of ``P``, the tangent
stiffness of the surfaces sliding (``P_KE``), the band ``[P_FLO, P_FHI]`` of the force that holds
the slab still and the displacement ``P_XNEXT`` at which the sliding surfaces change.  A block that can rock
(:mod:`isoslide.model.rocking`) has ``P_ROCK = tan(alpha) = Pi18`` (0: contents that only slide),
``P_RG = g/a_p``, ``P_RK = 3/(4 R)`` and ``P_RR = R`` (``R`` in units ``a_p T_p^2``), the restitution
``P_RE``, the cascade's end angle ``P_REPS`` (rad) and its static and kinetic friction coefficients
``P_RMUS``, ``P_RMUK``.  ``P_HOLD`` is the floor's demand the block at rest holds (units of a_p,
before the normal-force factor): its static friction ``P_THR``, or the uplift level ``g tan(alpha) /
a_p`` of a block that tips before it can slide (``mu_s > tan(alpha)``)."""

TFP_SIZE = 12
"""Values of a triple friction pendulum in the model parameters: per surface (1 to 4, bottom to
top) the stiffness ``k_i = M_b g / L_i`` (units ``M_b / T_p^2``), the friction strength
``mu_i M_b g`` (units ``M_b a_p``) and the displacement limit ``d_i`` (units ``a_p T_p^2``)."""


def n_parameters(n: int, n_z: int = 0, n_t: int = 0) -> int:
    """Length of the model-parameter array of ``n`` floors, ``n_t`` bearing values, ``n_z`` vertical ones."""
    return P_ARRAYS + n + 2 * n * n + n_t + n_z


def state_size(n: int) -> int:
    """Length of the state vector of a building of ``n`` floors."""
    return 2 * n + 7


def history_width(n: int) -> int:
    """Columns of a history row of a building of ``n`` floors."""
    return state_size(n) + 4

KIND_LINEAR, KIND_BILINEAR, KIND_SLIDING, KIND_FIXED, KIND_TFP = range(5)
"""Isolator kinds (``P[P_KIND]``): linear, bilinear bearing, sliding bearing, fixed base, triple
friction pendulum."""

INT_RESULTS = ("steps", "events", "settled", "slipped", "hist", "iso_events", "iso_moved", "rejected", "stage_max",
               "capacity", "overturned", "modes", "contact", "impacts")
"""The integer results of :func:`run`, in order (their indices are ``R_*``).  ``modes`` is the set of
the block's modes visited (bit ``1 << k`` for :data:`BLOCK_MODES` ``[k]``), ``contact`` a loss of the
block's contact (:data:`CONTACT_LOSSES`; 0: none) and ``impacts`` the rocking block's impacts."""
(R_STEPS, R_EVENTS, R_SETTLED, R_SLIPPED, R_HIST, R_ISO_EVENTS, R_ISO_MOVED, R_REJECTED, R_STAGE_MAX,
 R_CAPACITY, R_OVERTURNED, R_MODES, R_CONTACT, R_IMPACTS) = range(14)
N_R = len(INT_RESULTS)
FLOAT_RESULTS = ("umax", "tpeak", "ures", "tend", "xmax", "vmax", "upeak", "thmax", "tcontact")
"""The float results of :func:`run`, in order (their indices are ``F_*``): ``thmax`` the block's peak
``|theta|`` (rad), ``tcontact`` the time of a loss of contact."""
F_UMAX, F_TPEAK, F_URES, F_TEND, F_XMAX, F_VMAX, F_UPEAK, F_THMAX, F_TCONTACT = range(9)
N_F = len(FLOAT_RESULTS)
BLOCK_MODES = ("rest", "slide", "rock", "slide-rock")
"""The block's modes, in the order of the bits of the ``modes`` result."""

MAX_STALLED = 1000
"""Events in a row without time passing after which a rocking block's modes count as unresolved."""

CONTACT_LOSSES = ("", "flight", "impact", "indeterminate")
"""Losses of the rocking block's contact (the ``contact`` result): none, the vertical contact force
would turn negative below the tipping angle, an impact with no consistent impulse, the slide-rock
equations without a consistent solution (Painleve), or modes that change for ever without time
passing (:data:`MAX_STALLED` events)."""

# history columns: [tau, x, x', xs_1..n, xs_1'..n', theta, theta', u, u', fh, bm, im, stage] (see history_columns)
H_TAU, H_X, H_XD, H_XS = range(4)


def history_columns(n: int) -> dict:
    """Column of each quantity in a history row of a building of ``n`` floors.

    ``xs`` and ``xsd`` are the first columns of the floors' displacements and velocities (``n``
    each); ``theta``, ``thetad`` the rocking block's tilt (rad) and its rate; ``fh`` is the
    isolator's hysteretic force (the holding force of a held slab), ``phase`` and ``iso_phase`` the
    block's (:func:`block_mode`) and the isolator's modes, ``stage`` a triple friction pendulum's
    regime (:func:`tfp_stage`; 0 for any other isolator).
    """
    ny = state_size(n)
    return {"tau": H_TAU, "x": H_X, "xd": H_XD, "xs": H_XS, "xsd": H_XS + n, "theta": 3 + 2 * n,
            "thetad": 4 + 2 * n, "u": 5 + 2 * n, "ud": 6 + 2 * n, "fh": ny, "phase": ny + 1, "iso_phase": ny + 2,
            "stage": ny + 3}

# event kinds
EV_BLOCK, EV_BEAR, EV_YIELD, EV_BSPEED, EV_ISPEED, EV_BPEAK, EV_IPEAK, EV_XD, EV_TFP, EV_IMPACT, EV_OVER, EV_PIVOT, \
    EV_APEX, EV_FLIGHT = range(14)


_stribeck = njit(cache=True)(stribeck)
jit_cache.seed(_stribeck)


@njit(cache=True, _nrt=False, inline="always")
def friction(v, P):
    """Friction level ``phi(|v|)`` (units of a_p) and its derivative ``d phi / d|v|``."""
    thr = P[P_THR]
    if P[P_COULOMB] == 1.0:
        return thr, 0.0
    return _stribeck(v, thr, P[P_PI2], P[P_PI6], P[P_PI7], 1.0)


@njit(cache=True, _nrt=False, inline="always")
def bearing_level(w, P):
    """A sliding bearing's friction level at the speed ``w`` along its sliding direction, and ``d/dw``.

    ``q(w) = q - (q - q_s) exp(-a w)`` with the strength ``q = P_Q`` at high speed, the breakaway
    strength ``q_s = P_QS`` and the rate ``a = P_QA`` (units ``M_b a_p``, before the normal-force
    factor); ``a = 0`` is the constant ``q``.  A sliding slab has ``w = s x' = |x'|``; a Runge-Kutta
    stage past its stop (``w < 0``) sees the smooth continuation of the law (its exponent capped at
    50), so that the step that reaches the stop is not spoilt by the kink of ``q(|x'|)`` at rest.
    """
    a = P[P_QA]
    if a == 0.0:
        return P[P_Q], 0.0
    e = (P[P_Q] - P[P_QS]) * math.exp(min(-a * w, 50.0))
    return P[P_Q] - e, a * e


@njit(cache=True, _nrt=False, inline="always")
def _held(im, P):
    """True while the slab is held to the ground (stuck sliding bearing or triple pendulum, or a fixed base)."""
    kind = P[P_KIND]
    return kind == KIND_FIXED or ((kind == KIND_SLIDING or kind == KIND_TFP) and im == 0.0)


@njit(cache=True, _nrt=False, inline="always")
def _sticks(P):
    """True for an isolator that holds the slab with true stick (a sliding bearing or a triple pendulum)."""
    return P[P_KIND] == KIND_SLIDING or P[P_KIND] == KIND_TFP


@njit(cache=True, _nrt=False)
def hold_limit(sig, P):
    """Largest ``sig fh`` a held slab's bearing gives before it slides in ``sig`` (units ``M_b a_p``, per unit ``nz``).

    A sliding bearing's breakaway strength ``q_s`` both ways; a triple pendulum's band edge
    ``F_hi`` (``sig = 1``) or ``-F_lo`` (``sig = -1``) at its surfaces' present displacements
    (:func:`tfp_band`).
    """
    if P[P_KIND] == KIND_TFP:
        return P[P_FHI] if sig > 0.0 else -P[P_FLO]
    return P[P_QS]


@njit(cache=True, _nrt=False)
def _excess(fh, nz, P):
    """How far the force ``fh`` that holds the slab lies outside the stick band (positive: it slides)."""
    return max(fh - hold_limit(1.0, P) * nz, -fh - hold_limit(-1.0, P) * nz)


@njit(cache=True, _nrt=False)
def _push(fh, nz, P):
    """Direction in which a held slab slides when ``fh`` lies outside its band: towards the nearer-exceeded edge."""
    return 1.0 if fh - hold_limit(1.0, P) * nz > -fh - hold_limit(-1.0, P) * nz else -1.0


# --- the triple friction pendulum's surfaces ---------------------------------------


@njit(cache=True)
def _tfp_slopes(u, P, out):
    """``F - q_i`` of the four surfaces at the displacements ``u`` (units ``M_b a_p``, per unit ``nz``).

    The weight times the slope of surface ``i``'s normal where the load passes: ``k_1 u_1``,
    ``k_1 u_1 + k_2 u_2``, ``k_4 u_4 + k_3 u_3``, ``k_4 u_4`` (surfaces 2 and 3 ride on the plates of
    1 and 4), with ``k_i = M_b g / L_i``; ``q_i`` is surface ``i``'s friction (and restrainer) reaction.
    """
    o = int(P[P_TFP])
    s0 = P[o] * u[0]
    s3 = P[o + 3] * u[3]
    out[0] = s0
    out[1] = s0 + P[o + 1] * u[1]
    out[2] = s3 + P[o + 2] * u[2]
    out[3] = s3


@njit(cache=True)
def _at_stop(i, sig, u, P):
    """True when surface ``i`` rests on its restrainer on the side ``sig``."""
    d = P[int(P[P_TFP]) + 8 + i]
    return sig * u[i] >= d * (1.0 - 1e-12)


@njit(cache=True)
def tfp_band(u, P):
    """``(F_lo, F_hi)``: the bearing force (per unit ``nz``) within which every surface sticks at ``u``.

    ``F_hi`` is the least ``F - q_i + mu_i W`` over the surfaces free to move forward (not on their
    restrainer), ``F_lo`` the greatest ``F - q_i - mu_i W`` over those free to move back; ``inf``
    where none is.
    """
    o = int(P[P_TFP])
    sl = np.empty(4)
    _tfp_slopes(u, P, sl)
    lo = -math.inf
    hi = math.inf
    for i in range(4):
        if not _at_stop(i, 1.0, u, P):
            hi = min(hi, sl[i] + P[o + 4 + i])
        if not _at_stop(i, -1.0, u, P):
            lo = max(lo, sl[i] - P[o + 4 + i])
    return lo, hi


@njit(cache=True)
def tfp_mode(sig, u, F, P, r):
    """Tangent stiffness of the bearing moving in ``sig`` from ``(u, F)``; ``r`` receives ``du_i/dx``.

    Along each chain (surfaces 1 and 2 on the bottom plate, 4 and 3 on the top one) the outer
    surface slides when its reaction is at its friction limit ``sig mu_i W`` and it is off its
    restrainer, else the inner one when it is: the reaction of an inner surface is its outer
    surface's minus ``k u``, so while the outer one slides (its reaction pinned) the inner one's stays
    where it is, and an inner surface sliding alone would push a stuck outer one at its limit beyond
    it.  Each sliding surface takes the share ``K / k_i`` of the motion, ``K = 1 / sum(1/k_i)`` over
    the sliding ones; ``inf`` when no surface can move (every chain locked).
    """
    o = int(P[P_TFP])
    sl = np.empty(4)
    _tfp_slopes(u, P, sl)
    scale = F if F > 0.0 else -F
    for i in range(4):
        r[i] = 0.0
        scale = max(scale, P[o + 4 + i])
    tol = 1e-9 * scale
    pick = np.full(2, -1)
    for c in range(2):
        outer = 0 if c == 0 else 3
        inner = 1 if c == 0 else 2
        for i in (outer, inner):
            if sig * (F - sl[i]) >= P[o + 4 + i] - tol and not _at_stop(i, sig, u, P):
                pick[c] = i
                break
    comp = 0.0
    for c in range(2):
        if pick[c] >= 0:
            comp += 1.0 / P[o + pick[c]]
    if comp == 0.0:
        return math.inf
    K = 1.0 / comp
    for c in range(2):
        if pick[c] >= 0:
            r[pick[c]] = K / P[o + pick[c]]
    return K


@njit(cache=True)
def tfp_reach(sig, u, F, K, r, P):
    """Distance ``|dx|`` the bearing moves in ``sig`` before its set of sliding surfaces changes.

    A sliding surface reaches its restrainer (``sig u_i`` up to ``d_i``), or a stuck one free to
    move reaches its friction limit (its reaction's rate per unit ``|dx|``: ``K - k_1 r_1`` on
    surface 1, that minus ``k_2 r_2`` on surface 2, and likewise from surface 4).
    """
    o = int(P[P_TFP])
    sl = np.empty(4)
    _tfp_slopes(u, P, sl)
    # a sliding outer surface's reaction is pinned: its rate, and its inner surface's, are exactly 0
    # (``K - k r`` would leave round-off that could fire an inner surface resting on its limit at once)
    dq0 = 0.0 if r[0] > 0.0 else K - P[o] * r[0]
    dq3 = 0.0 if r[3] > 0.0 else K - P[o + 3] * r[3]
    rates = (dq0, dq0 - P[o + 1] * r[1], dq3 - P[o + 2] * r[2], dq3)
    best = math.inf
    for i in range(4):
        if r[i] > 0.0:
            best = min(best, max(P[o + 8 + i] - sig * u[i], 0.0) / r[i])
        elif rates[i] > 0.0 and not _at_stop(i, sig, u, P):
            best = min(best, max(P[o + 4 + i] - sig * (F - sl[i]), 0.0) / rates[i])
    return best


@njit(cache=True)
def tfp_stage(r, u, P):
    """Fenz and Constantinou's regime of the sliding surfaces ``r > 0``: 0 none, 1..5 I..V, -1 another set.

    I: the inner pair (2, 3), V when both outer surfaces rest on their restrainers; II: 1 and 3;
    III: 1 and 4; IV: 2 and 4.
    """
    a = -1
    b = -1
    for i in range(4):
        if r[i] > 0.0:
            if a < 0:
                a = i
            else:
                b = i
    if a < 0:
        return 0
    if a == 1 and b == 2:
        both = (_at_stop(0, 1.0, u, P) or _at_stop(0, -1.0, u, P)) and (_at_stop(3, 1.0, u, P)
                                                                          or _at_stop(3, -1.0, u, P))
        return 5 if both else 1
    if a == 0 and b == 2:
        return 2
    if a == 0 and b == 3:
        return 3
    if a == 1 and b == 3:
        return 4
    return -1


@njit(cache=True)
def tfp_moved(u0, r, dx, P, u):
    """The surfaces' displacements ``u = u0 + r dx``, snapped onto a restrainer reached to round-off."""
    o = int(P[P_TFP])
    for i in range(4):
        u[i] = u0[i] + r[i] * dx
        d = P[o + 8 + i]
        if abs(u[i]) > d * (1.0 - 1e-10):
            u[i] = d if u[i] > 0.0 else -d


@njit(cache=True, _nrt=False, inline="always")
def normal(tau, P):
    """Normal force over its static value, ``1 + Pi17 p_z(tau)``, and its tau-rate (1, 0 without vertical motion).

    The whole building moves vertically with the ground, so the contents' and a sliding bearing's
    normal forces carry the same factor; friction forces, stick limits and a friction pendulum's
    restoring stiffness scale with it.
    """
    amp = P[P_ZAMP]
    if amp == 0.0:
        return 1.0, 0.0
    zp = P[int(P[P_ZOFF]):]
    code = int(P[P_ZCODE])
    return 1.0 + amp * accel_at(code, zp, tau), amp * jerk_at(code, zp, tau)


@njit(cache=True, _nrt=False, inline="always")
def _pendulum(P):
    """1 for a sliding bearing (a friction pendulum's stiffness scales with its normal force), else 0."""
    return 1.0 if P[P_KIND] == KIND_SLIDING else 0.0


@njit(cache=True, _nrt=False, inline="always")
def _stiffness(nz, P):
    """Isolator stiffness under the normal-force factor ``nz`` (a friction pendulum's scales with it)."""
    return P[P_KD] * nz if P[P_KIND] == KIND_SLIDING else P[P_KD]


@njit(cache=True, _nrt=False, inline="always")
def _hysteretic(im, nz, y, P):
    """Hysteretic isolator force of a moving slab.

    Bilinear bearing: the state; sliding bearing: ``q(|x'|) nz im``; triple pendulum: the state
    ``F`` times ``nz``.
    """
    kind = P[P_KIND]
    if kind == KIND_BILINEAR:
        return y[y.shape[0] - 1]
    if kind == KIND_TFP:
        return y[y.shape[0] - 1] * nz
    if kind == KIND_SLIDING:
        return bearing_level(im * y[Y_XD], P)[0] * nz * im
    return 0.0


@njit(cache=True, _nrt=False, inline="always")
def _storey_force(j, zp, zv, P):
    """Force of the superstructure on floor ``j`` (0-based), negated: ``G_j = (Ks zp + Cs zv)_j``.

    ``zp``, ``zv``: the floors' displacements and velocities relative to the slab (or their rates:
    ``G`` is linear in them).
    """
    n = int(P[P_N])
    ks = P_ARRAYS + n + j * n
    cs = ks + n * n
    acc = 0.0
    for k in range(n):
        acc += P[ks + k] * zp[k]
    for k in range(n):
        acc += P[cs + k] * zv[k]
    return acc


@njit(cache=True, _nrt=False)
def _base_shear(zp, zv, P):
    """Force of the superstructure on the slab, ``S = sum_j G_j`` (linear in ``zp, zv``)."""
    acc = 0.0
    for j in range(int(P[P_N])):
        acc += _storey_force(j, zp, zv, P)
    return acc


@njit(cache=True, inline="always")
def corner(bm):
    """The rocking block's pivot corner ``s`` (+-1) in the block mode ``bm``; 0 while it is flat.

    A block mode is ``bm = sigma + 4 s``: ``sigma`` (:func:`base_slide`) the sliding direction of
    its base (0 stuck) and ``s`` the corner it rocks on (0 flat), so ``0`` is rest, ``+-1`` a slide,
    ``+-4`` rocking and the others slide-rock.
    """
    return 1.0 if bm > 1.5 else (-1.0 if bm < -1.5 else 0.0)


@njit(cache=True, inline="always")
def base_slide(bm):
    """The sliding direction ``sigma`` of the block's base (its pivot while it rocks) in the mode ``bm``."""
    return bm - 4.0 * corner(bm)


@njit(cache=True)
def block_mode(bm):
    """Index in :data:`BLOCK_MODES` of the block mode ``bm``."""
    if corner(bm) == 0.0:
        return 0 if bm == 0.0 else 1
    return 2 if base_slide(bm) == 0.0 else 3


@njit(cache=True, inline="always")
def _tilt(bm, y, P):
    """``(s, psi, psi', d)``: the pivot corner, the tilt on it and its rate, ``d = alpha - psi``."""
    n = int(P[P_N])
    s = corner(bm)
    psi = s * y[Y_XS + 2 * n]
    return s, psi, s * y[Y_XS + 2 * n + 1], math.atan(P[P_ROCK]) - psi


@njit(cache=True, _nrt=False, inline="always")
def _block_load(bm, nz, y, P):
    """How the block of mode ``bm`` loads its floor: ``(a1, f, ac)``.

    The floor receives ``f - m a1 A_F`` from the block (``A_F`` its absolute acceleration, units of
    a_p): a block at rest adds its mass (``a1 = 1``), a sliding one its friction ``f``; a rocking one
    pushes with ``-m H``, linear in ``A_F`` (``H = A_F (1 - 3/4 cos^2 d) - 3/4 s Gam sin d cos d + s R
    sin d psi'^2`` per unit mass, ``Gam = g nz``); a slide-rocking one with ``-m H = m mu_k V sigma``,
    explicit, ``ac`` being then the absolute acceleration of its sliding corner (Shenton and Jones
    1991; :mod:`isoslide.peers.slide_rock`); a sliding one's ``ac`` is its friction per unit mass.
    """
    m = P[P_M]
    c = corner(bm)
    if c == 0.0:
        if bm == 0.0:
            return 1.0, 0.0, 0.0
        ph, _ = friction(y[y.shape[0] - 2], P)
        ph *= nz
        return 0.0, m * bm * ph, bm * ph
    s, psi, psd, d = _tilt(bm, y, P)
    gam = P[P_RG] * nz
    sd = math.sin(d)
    cd = math.cos(d)
    R = P[P_RR]
    sig = base_slide(bm)
    if sig == 0.0:
        return 1.0 - 0.75 * cd * cd, -m * (-0.75 * s * gam * sd * cd + s * R * sd * psd * psd), 0.0
    mu = P[P_RMUK]
    cc = s * cd + mu * sig * sd
    ac = (0.75 * cc * gam * sd - R * psd * psd * (s * sd - mu * sig * cd) - mu * sig * gam) / (1.0 - 0.75 * cc * s * cd)
    psdd = -P[P_RK] * (gam * sd + s * ac * cd)
    V = gam + R * (sd * psdd - cd * psd * psd)
    return 0.0, m * mu * V * sig, ac


@njit(cache=True, _nrt=False)
def _accels(bm, im, p, nz, y, P, A):
    """Accelerations of a mode: ``(Ab, A_F, u'', fh, R, theta'')``; the floors' into ``A``.

    ``Ab`` absolute slab acceleration, ``A[j]`` floor ``j + 1``'s absolute acceleration, ``A_F``
    the contents' floor's, ``u''`` the block's relative acceleration, ``fh`` the hysteretic isolator
    force (for a held slab, the force that holds it), ``R`` the force of the block on its floor
    (:func:`_block_load`) and ``theta''`` the rocking block's angular acceleration; ``nz`` is the
    normal-force factor (:func:`normal`).
    """
    n = int(P[P_N])
    m = P[P_M]
    mb = P[P_MB]
    roof = P[P_ROOF] != 0.0
    flex = P[P_FLEX] != 0.0
    fl = int(P[P_FLOOR]) - 1
    zp = y[Y_XS:Y_XS + n]
    zv = y[Y_XS + n:Y_XS + 2 * n]
    a1, f, ac = _block_load(bm, nz, y, P)
    S = 0.0
    for j in range(n):
        if flex:
            G = _storey_force(j, zp, zv, P)
            S += G
            mj = P[P_ARRAYS + j]
            if roof and j == fl:
                A[j] = (-G + f) / (mj + m * a1)
            else:
                A[j] = -G / mj
    if _held(im, P):
        Ab = p
        fh = 0.0
    else:
        fh = _hysteretic(im, nz, y, P)
        F = _stiffness(nz, P) * y[Y_X] + P[P_CB] * y[Y_XD] + fh
        if roof:
            Ab = (-F + S) / mb
        else:
            Ab = (-F + S + f) / (mb + m * a1)
    if not flex:
        for j in range(n):
            A[j] = Ab
    AF = A[fl] if roof else Ab
    R = f - m * a1 * AF
    if _held(im, P):
        fh = -mb * p - _stiffness(nz, P) * y[Y_X] + S + (0.0 if roof else R)
    c = corner(bm)
    if c == 0.0:
        udd = 0.0 if bm == 0.0 else -AF - ac
        return Ab, AF, udd, fh, R, 0.0
    s, psi, psd, d = _tilt(bm, y, P)
    a = AF if base_slide(bm) == 0.0 else ac
    psdd = -P[P_RK] * (P[P_RG] * nz * math.sin(d) + s * a * math.cos(d))
    return Ab, AF, a - AF, fh, R, s * psdd


_accels_inline = njit(cache=True, _nrt=False, inline="always")(getattr(_accels, "py_func", _accels))
""":func:`_accels` compiled into its caller (the right-hand side's hot path)."""


@njit(cache=True, _nrt=False)
def contact(bm, nz, y, AF, ac, P):
    """The rocking block's contact force per unit mass ``(H, V)`` at its pivot (units of a_p).

    ``AF`` the floor's absolute acceleration, ``ac`` the pivot's (``AF`` while it sticks).
    """
    s, psi, psd, d = _tilt(bm, y, P)
    gam = P[P_RG] * nz
    sd = math.sin(d)
    cd = math.cos(d)
    R = P[P_RR]
    psdd = -P[P_RK] * (gam * sd + s * ac * cd)
    return ac + s * R * (cd * psdd + sd * psd * psd), gam + R * (sd * psdd - cd * psd * psd)


@njit(cache=True, _nrt=False)
def deriv(bm, im, tau, y, P, code, params, out):
    """Right-hand side of the mode ``(bm, im)`` at ``(tau, y)``, written into ``out``."""
    n = int(P[P_N])
    ny = y.shape[0]
    p = accel_at(code, params, tau)
    nz, _ = normal(tau, P)
    A = out[Y_XS + n:Y_XS + 2 * n]
    Ab, AF, udd, fh, R, thdd = _accels_inline(bm, im, p, nz, y, P, A)
    if _held(im, P):
        out[Y_X] = 0.0
        out[Y_XD] = 0.0
    else:
        out[Y_X] = y[Y_XD]
        out[Y_XD] = Ab - p
    for j in range(n):
        out[Y_XS + j] = y[Y_XS + n + j]
        out[Y_XS + n + j] = A[j] - Ab
    out[Y_XS + 2 * n] = y[Y_XS + 2 * n + 1]
    out[Y_XS + 2 * n + 1] = thdd
    out[ny - 3] = y[ny - 2]
    out[ny - 2] = udd
    kind = P[P_KIND]
    out[ny - 1] = P[P_KE] * y[Y_XD] if ((kind == KIND_BILINEAR and im == 0.0) or (kind == KIND_TFP and im != 0.0)) \
        else 0.0


@njit(cache=True, _nrt=False)
def _floor_stuck(im, x, xd, zp, zv, fh, p, kd, P):
    """Floor acceleration ``A_F`` of a stuck block (units of a_p), with the isolator stiffness ``kd``.

    Linear and homogeneous in ``(x, x', zp, zv, fh, p)`` (``zp``, ``zv`` the floors' displacements
    and velocities relative to the slab): given their rates it returns the rate (a stiffness that
    varies with the normal force adds its rate's term to ``fh``).
    """
    m = P[P_M]
    if P[P_ROOF] != 0.0:
        fl = int(P[P_FLOOR]) - 1
        return -_storey_force(fl, zp, zv, P) / (P[P_ARRAYS + fl] + m)
    if _held(im, P):
        return p
    S = _base_shear(zp, zv, P) if P[P_FLEX] != 0.0 else 0.0
    return (-(kd * x + P[P_CB] * xd + fh) + S) / (P[P_MB] + m)


@njit(cache=True, _nrt=False)
def _bearing_need(bm, x, zp, zv, p, rs, kd, P):
    """Force (units of M_b a_p) that holds a stuck sliding bearing's slab to the ground.

    ``rs = m bm phi`` is the sliding block's friction force, ``kd`` the pendulum's stiffness; linear
    and homogeneous in ``(x, zp, zv, p, rs)``: given their rates it returns the rate.
    """
    S = _base_shear(zp, zv, P) if P[P_FLEX] != 0.0 else 0.0
    r = 0.0
    if P[P_ROOF] == 0.0:
        r = rs if bm != 0.0 else -P[P_M] * p
    return -P[P_MB] * p - kd * x + S + r


@njit(cache=True, _nrt=False)
def _event(kind, sig, bm, im, tau, y, P, code, params, work):
    """Value and tau-rate ``(g, dg)`` of the event function ``kind`` at ``(tau, y)``.

    EV_BLOCK  ``sig A_F - thr`` (stuck block)      EV_BEAR  ``sig fh_need - q_s`` (stuck bearing)
    EV_YIELD  ``sig fh - q`` (elastic bilinear)    EV_BSPEED ``bm u'``   EV_ISPEED ``im x'``
    EV_BPEAK, EV_IPEAK: the rates of EV_BLOCK and EV_BEAR (derivative not given: NaN).
    EV_XD     ``sig x'`` (the rate of an elastic bilinear bearing's ``sig fh``, over ``ke``)
    EV_TFP    ``im (x - P_XNEXT)``: a moving triple pendulum's sliding surfaces change
    EV_IMPACT ``psi`` (the rocking block reaches the floor)   EV_OVER ``pi/2 - psi`` (it overturns)
    EV_PIVOT  ``mu_s V - |H|`` (the rocking block's pivot slips; rate not given: NaN)
    EV_APEX   ``psi'`` (the tilt's extremes)
    EV_FLIGHT ``V`` below the tipping angle, positive above it (the rocking block would leave the floor)

    ``work`` receives the right-hand side at ``(tau, y)`` for the kinds that read it
    (:func:`_event_at`).
    """
    if kind != EV_YIELD and kind != EV_TFP and kind != EV_PIVOT and kind != EV_FLIGHT:
        deriv(bm, im, tau, y, P, code, params, work)
    return _event_at(kind, sig, bm, im, tau, y, P, code, params, work)


@njit(cache=True, _nrt=False)
def _event_at(kind, sig, bm, im, tau, y, P, code, params, d):
    """:func:`_event` with the right-hand side at ``(tau, y)`` given in ``d``.

    Every kind reads ``d`` but EV_YIELD, EV_TFP, EV_PIVOT and EV_FLIGHT; the last two write the
    floors' accelerations into it.
    """
    work = d
    n = int(P[P_N])
    ny = y.shape[0]
    ud = ny - 2
    fhi = ny - 1
    if kind == EV_XD:
        return sig * y[Y_XD], sig * work[Y_XD]
    if kind == EV_TFP:
        return im * (y[Y_X] - P[P_XNEXT]), im * y[Y_XD]
    if kind == EV_BSPEED:
        sl = base_slide(bm)
        return sl * y[ud], sl * work[ud]
    if kind == EV_IMPACT or kind == EV_OVER or kind == EV_APEX:
        s = corner(bm)
        th = Y_XS + 2 * n
        if kind == EV_IMPACT:
            return s * y[th], s * work[th]
        if kind == EV_OVER:
            return 0.5 * math.pi - s * y[th], -s * work[th]
        return s * y[th + 1], s * work[th + 1]
    if kind == EV_PIVOT or kind == EV_FLIGHT:
        nz, _ = normal(tau, P)
        A = d[Y_XS + n:Y_XS + 2 * n]    # scratch: these kinds do not read the right-hand side
        a = _accels(bm, im, accel_at(code, params, tau), nz, y, P, A)
        H, V = contact(bm, nz, y, a[1], a[1] + a[2], P)
        if kind == EV_FLIGHT:
            return (V if corner(bm) * y[Y_XS + 2 * n] < math.atan(P[P_ROCK]) else 1.0 + abs(V)), math.nan
        return P[P_RMUS] * V - abs(H), math.nan
    if kind == EV_ISPEED:
        return im * y[Y_XD], im * work[Y_XD]
    if kind == EV_YIELD:
        return sig * y[fhi] - P[P_Q], sig * P[P_KE] * y[Y_XD]
    p = accel_at(code, params, tau)
    pd = jerk_at(code, params, tau)
    nz, dnz = normal(tau, P)
    kd = _stiffness(nz, P)
    dkd = P[P_KD] * dnz * _pendulum(P)
    zp = y[Y_XS:Y_XS + n]
    zv = y[Y_XS + n:Y_XS + 2 * n]
    za = work[Y_XS + n:Y_XS + 2 * n]
    if kind == EV_BLOCK or kind == EV_BPEAK:
        fh = _hysteretic(im, nz, y, P)
        if P[P_KIND] == KIND_TFP:
            dfh = work[fhi] * nz + y[fhi] * dnz
        else:
            lev, dlev = bearing_level(im * y[Y_XD], P)
            # a sliding bearing's fh = q(|x'|) nz im: its rate adds q' |x'|' nz im = q' x'' nz while sliding
            dfh = work[fhi] + dkd * y[Y_X] + (lev * dnz * im + dlev * work[Y_XD] * nz * im * im) * _pendulum(P)
        g = sig * _floor_stuck(im, y[Y_X], y[Y_XD], zp, zv, fh, p, kd, P) - P[P_HOLD] * nz
        dg = sig * _floor_stuck(im, y[Y_XD], work[Y_XD], zv, za, dfh, pd, kd, P) - P[P_HOLD] * dnz
        if kind == EV_BPEAK:
            return dg, math.nan
        return g, dg
    # EV_BEAR / EV_IPEAK
    rs = 0.0
    rsd = 0.0
    bf = bm
    if corner(bm) != 0.0:
        # a rocking block's force on the held slab (its rate not given: NaN)
        a1, f, _ = _block_load(bm, nz, y, P)
        rs = f - P[P_M] * a1 * p
        rsd = math.nan
        bf = 1.0
    elif bm != 0.0:
        ph, dph = friction(y[ud], P)
        rs = P[P_M] * bm * ph * nz
        rsd = P[P_M] * (dph * work[ud] * nz + bm * ph * dnz)
    lim = hold_limit(sig, P)
    g = sig * _bearing_need(bf, y[Y_X], zp, zv, p, rs, kd, P) - lim * nz
    dg = sig * (_bearing_need(bf, 0.0, zv, za, pd, rsd, kd, P) - dkd * y[Y_X]) - lim * dnz
    if kind == EV_IPEAK:
        return dg, math.nan
    return g, dg


# --- one Runge-Kutta step ---------------------------------------------------


@njit(cache=True, _nrt=False)
def rk_step(bm, im, tau, y, h, P, code, params, atol, rtol, K, ynew):
    """One DOP853 step of length ``h`` from ``(tau, y)`` into ``ynew``; returns the error norm.

    ``K`` (``(NS + 1, len(y))``) receives the stages, row ``NS`` the right-hand side at the step end;
    stages at the step end see the pulse's left limit.  ``ynew`` (never ``y`` itself) holds each
    stage's state until the step's end state is written into it.
    """
    t_left = _left_limit(tau + h)
    ny = y.shape[0]
    ys = ynew
    deriv(bm, im, tau, y, P, code, params, K[0])
    for st in range(1, NS):
        stage_state(y, h, K, st, ys)
        ts = t_left if C[st] == 1.0 else tau + C[st] * h
        deriv(bm, im, ts, ys, P, code, params, K[st])
    end_state(y, h, K, ynew)
    deriv(bm, im, t_left, ynew, P, code, params, K[NS])
    return scaled_error(K, y, ynew, h, atol, rtol, ny - 3, ny - 1)


@njit(cache=True)
def verify(bm, im, tau, y, h, ycand, P, code, params, atol, rtol, K):
    """Richardson check of one step: scaled error of ``ycand`` against two half steps."""
    ny = y.shape[0]
    ya = np.empty(ny)
    yb = np.empty(ny)
    rk_step(bm, im, tau, y, 0.5 * h, P, code, params, atol, rtol, K, ya)
    rk_step(bm, im, tau + 0.5 * h, ya, 0.5 * h, P, code, params, atol, rtol, K, yb)
    return doubling_error(y, yb, ycand, atol, rtol, ny - 3, ny - 1)


# --- events -------------------------------------------------------------------


@njit(cache=True, _nrt=False)
def locate(kind, sig, bm, im, tau, y, ha, ga, hb, gb, h0, check, P, code, params, atol, rtol, K, yout, work,
           cnt):
    """Find ``h`` in ``(ha, hb]`` where the event ``kind`` vanishes (``ga``, ``gb`` of opposite sign).

    Safeguarded Newton from ``h0`` (Illinois regula falsi without a derivative), each trial
    re-stepping from the accepted point; stops when the correction is below 1e-13 (relative to
    ``max(1, |tau|)``).  ``yout`` receives the state at the root; returns the step length and the
    error estimate of that step (step doubling added when ``check``).
    """
    lo, glo, hi, ghi, side, tol, h = bracket_open(tau, h0, ha, ga, hb, gb)
    err = 0.0
    state = ROOT_OPEN
    for _it in range(100):
        err = rk_step(bm, im, tau, y, h, P, code, params, atol, rtol, K, yout)
        cnt[0] += 1
        g, dg = _event(kind, sig, bm, im, tau + h, yout, P, code, params, work)
        state, h, lo, glo, hi, ghi, side = bracket_step(h, g, dg, lo, glo, hi, ghi, side, tol)
        if state != ROOT_OPEN:
            break
    on_res = state == ROOT_AT_TRIAL
    res = h if on_res else hi
    if not on_res:
        err = rk_step(bm, im, tau, y, res, P, code, params, atol, rtol, K, yout)
        cnt[0] += 1
    if check and err <= 1.0:
        err = max(err, verify(bm, im, tau, y, res, yout, P, code, params, atol, rtol, K))
        cnt[0] += 2
    return res, err


@njit(cache=True, _nrt=False)
def _demand_event(kind, peak, limit, sig, bm, im, tau, y, y1, h, t_end, P, code, params, atol, rtol, check, K, ye,
                  work, cnt, d0, d1):
    """First root of a demand event ``kind`` (EV_BLOCK or EV_BEAR, sign ``sig``) in the accepted step.

    Found directly when the step ends above the limit, or past an interior peak of the demand
    (a root of its rate, ``peak`` the kind that evaluates it) whose cubic Hermite estimate comes
    within 1 % of the limit.  ``d0``, ``d1`` hold the right-hand side at the step's ends ``(tau,
    y)`` and ``(t_end, y1)``.  Returns ``(found, hs, herr)``; ``ye`` holds the state there.
    """
    g0, r0 = _event_at(kind, sig, bm, im, tau, y, P, code, params, d0)
    g1, r1 = _event_at(kind, sig, bm, im, t_end, y1, P, code, params, d1)
    if g1 > 0.0:
        if g0 >= 0.0:
            for i in range(y.shape[0]):
                ye[i] = y[i]
            return True, 0.0, 0.0
        h0 = hermite_root(g0, r0, g1, r1, h)
        hs, herr = locate(kind, sig, bm, im, tau, y, 0.0, g0, h, g1, h0, check, P, code, params, atol, rtol,
                          K, ye, work, cnt)
        return True, hs, herr
    if not (r0 > 0.0 and r1 < 0.0):
        return False, 0.0, 0.0
    if _hermite_max(g0, r0, g1, r1, h) < -1e-2 * limit:
        return False, 0.0, 0.0
    hm, herr = locate(peak, sig, bm, im, tau, y, 0.0, r0, h, r1, -1.0, False, P, code, params, atol, rtol,
                      K, ye, work, cnt)
    gm, _ = _event(kind, sig, bm, im, tau + hm, ye, P, code, params, work)
    if gm <= 0.0:
        return False, 0.0, 0.0
    hs, herr = locate(kind, sig, bm, im, tau, y, 0.0, g0, hm, gm, -1.0, check, P, code, params, atol, rtol,
                      K, ye, work, cnt)
    return True, hs, herr


@njit(cache=True, _nrt=False, inline="always")
def _earliest_demand_event(kind, peak, limit, bm, im, tau, y, y1, h, t_end, P, code, params, atol, rtol, check, K,
                           ye, yb, work, cnt, best, best_sig, hbest, herr_best, d0, d1):
    """The earliest of :func:`_demand_event` in both directions, if before the best event so far.

    ``(best, best_sig, hbest, herr_best)`` is the best event so far (kind, sign, step length and
    error estimate; ``yb`` its state); returns it updated.  ``d0``, ``d1``: the right-hand side at
    the step's ends, as for :func:`_demand_event`.
    """
    for sig in (1.0, -1.0):
        found, hs, herr = _demand_event(kind, peak, limit, sig, bm, im, tau, y, y1, h, t_end, P, code, params, atol,
                                        rtol, check, K, ye, work, cnt, d0, d1)
        if found and hs < hbest:
            best, best_sig, hbest, herr_best = kind, sig, hs, herr
            copy_state(yb, ye)
    return best, best_sig, hbest, herr_best


@njit(cache=True, _nrt=False, inline="always")
def _speed_candidate(kind, bm, im, tau, y, y1, h, t_end, just_started, check, P, code, params, atol, rtol, K, ye,
                     work, cnt):
    """:func:`_speed_event` where the speed event ``kind`` is not positive at the step's end ``(t_end, y1)``.

    Returns ``(found, hs, herr)``: ``found`` False (and zeros) while the phase goes on.
    """
    g1, r1 = _event(kind, 0.0, bm, im, t_end, y1, P, code, params, work)
    if g1 > 0.0:
        return False, 0.0, 0.0
    hs, herr = _speed_event(kind, bm, im, tau, y, h, g1, r1, just_started, check, P, code, params, atol, rtol, K, ye,
                            work, cnt)
    return True, hs, herr


@njit(cache=True, _nrt=False)
def _speed_event(kind, bm, im, tau, y, h, g1, r1, just_started, check, P, code, params, atol, rtol, K, ye, work,
                 cnt):
    """End of a sliding (or yielding) phase inside the accepted step: ``g1 <= 0`` (rate ``r1``) at its end.

    When the phase began at the step's start (``just_started``, speed 0) an interior point of
    positive speed is found first by halving; without one the phase ends at once.
    Returns ``(hs, herr)``; ``ye`` holds the state there.
    """
    g0, r0 = _event(kind, 0.0, bm, im, tau, y, P, code, params, work)
    if just_started or g0 <= 0.0:
        hp = h
        gp = g1
        for _k in range(200):
            hp *= 0.5
            rk_step(bm, im, tau, y, hp, P, code, params, atol, rtol, K, ye)
            cnt[0] += 1
            gp, _ = _event(kind, 0.0, bm, im, tau + hp, ye, P, code, params, work)
            if gp > 0.0 or hp < 1e-300:
                break
        if gp > 0.0:
            return locate(kind, 0.0, bm, im, tau, y, hp, gp, h, g1, -1.0, check, P, code, params, atol, rtol,
                          K, ye, work, cnt)
        for i in range(y.shape[0]):
            ye[i] = y[i]
        return 0.0, 0.0
    return locate(kind, 0.0, bm, im, tau, y, 0.0, g0, h, g1, hermite_root(g0, r0, g1, r1, h), check, P, code, params,
                  atol, rtol, K, ye, work, cnt)


# --- modes ----------------------------------------------------------------------


@njit(cache=True)
def _consistent(b, i, free_b, free_i, p, nz, y, P, A):
    """Whether the modes ``(b, i)`` are consistent at a state where the free interfaces are at rest.

    ``nz`` is the normal-force factor (:func:`normal`), ``A`` scratch space for the floors'
    accelerations.
    """
    if free_i and i != 0.0 and P[P_KIND] == KIND_TFP:
        # a triple pendulum starts sliding at its band's edge
        y = y.copy()
        y[y.shape[0] - 1] = P[P_FHI] if i > 0.0 else P[P_FLO]
    Ab, AF, udd, fh, R, thdd = _accels(b, i, p, nz, y, P, A)
    if free_b:
        if b == 0.0:
            if abs(AF) > P[P_HOLD] * nz:
                return False
        elif not b * udd > 0.0:
            return False
    if free_i:
        if i == 0.0:
            if _excess(fh, nz, P) > 0.0:
                return False
        elif not i * (Ab - p) > 0.0:
            return False
    return True


@njit(cache=True)
def _select_modes(bm, im, free_b, free_i, tau, y, P, code, params):
    """Modes of the interfaces at rest (``free_b``: the block, ``free_i``: a sliding bearing).

    The first consistent combination of :func:`isoslide.engine.modes.candidates` (the fewest
    sliding interfaces first); if none is (round-off at a limit), each free interface slides in
    the direction its stuck demand pushes it.
    """
    p = accel_at(code, params, tau)
    nz, _ = normal(tau, P)
    A = np.empty(int(P[P_N]))
    trial = candidates(np.array([free_b, free_i]), np.array([bm, im]))
    for r in range(trial.shape[0]):
        if _consistent(trial[r, 0], trial[r, 1], free_b, free_i, p, nz, y, P, A):
            return trial[r, 0], trial[r, 1]
    b = bm
    i = im
    if free_b:
        AF = _accels(0.0, im if not free_i else 0.0, p, nz, y, P, A)[1]
        b = -1.0 if AF > 0.0 else 1.0
    if free_i:
        fh = _accels(bm if not free_b else 0.0, 0.0, p, nz, y, P, A)[3]
        i = _push(fh, nz, P)
    return b, i


@njit(cache=True)
def _modal_within(W, Cm, y, limits, offsets):
    """Whether every demand's modal bound is within its limit.

    Demand ``j`` of the free linear system is ``sum_k Cm[j, k] a_k exp(lambda_k t)`` with the modal
    coordinates ``a = W y``; as ``Re lambda_k <= 0``, ``|d_j| <= |offsets[j]| + sum_k |Cm[j, k] a_k|``.
    """
    n = W.shape[0]
    if n == 0:
        return False
    a = np.zeros(n, dtype=np.complex128)
    for k in range(n):
        acc = 0.0 + 0.0j
        for i in range(W.shape[1]):
            acc += W[k, i] * y[i]
        a[k] = acc
    for j in range(Cm.shape[0]):
        bound = abs(offsets[j])
        for k in range(n):
            bound += abs(Cm[j, k] * a[k])
        if bound > limits[j]:
            return False
    return True


@njit(cache=True)
def _settled(bm, im, y, P, Wm, Cm, Wh, Ch):
    """True when, after the pulse, nothing can slip or yield again (see the module docstring).

    Either bound proves it: the energy bound, or the modal bound of the free linear system
    (``Wm, Cm`` with the slab moving, ``Wh, Ch`` with it held; see
    :func:`isoslide.engine.building.modal_data`), which is much sharper when one mode dominates.
    """
    if bm != 0.0:
        return False
    kind = P[P_KIND]
    if (_sticks(P) or kind == KIND_BILINEAR) and im != 0.0:
        return False
    limits = np.array([P[P_HOLD], P[P_QS]])
    if _held(im, P):
        if _energy_settled(im, y, P):
            return True
        offset = P[P_KD] * y[Y_X]
        if kind == KIND_TFP:
            offset, limits[1] = held_band(P)
        return _modal_within(Wh, Ch, y, limits, np.array([0.0, offset]))
    if _energy_settled(im, y, P):
        return True
    return _modal_within(Wm, Cm, y, limits, np.zeros(2))


@njit(cache=True)
def held_band(P):
    """A held triple pendulum's band as ``(centre, half-width)``: ``|fh - centre| <= half-width`` keeps it held.

    A band open on one side (every surface on its restrainer that way) is narrowed to the symmetric
    one about zero that it contains.
    """
    hi = P[P_FHI]
    lo = P[P_FLO]
    if math.isinf(hi) or math.isinf(lo):
        return 0.0, max(min(hi, -lo), 0.0)
    return 0.5 * (hi + lo), 0.5 * (hi - lo)


@njit(cache=True)
def _energy_settled(im, y, P):
    """The energy bound of :func:`_settled` (the block stuck, the isolator stuck or elastic).

    Written for at most one floor; with several floors it proves nothing (the modal bound does).
    """
    if P[P_N] > 1.0:
        return False
    kind = P[P_KIND]
    m = P[P_M]
    roof = P[P_ROOF] != 0.0
    flex = P[P_FLEX] != 0.0
    ks = P[P_KS]
    cs = P[P_CS]
    thr = P[P_HOLD]
    xs = y[Y_XS]
    xsd = y[Y_XS + 1]
    if _held(im, P):
        if not flex:
            return True
        mst = P[P_MST] + (m if roof else 0.0)
        energy = 0.5 * mst * xsd * xsd + 0.5 * ks * xs * xs
        smax = math.sqrt(2.0 * energy * (ks + cs * cs / mst))
        if roof and smax / mst > thr:
            return False
        if kind == KIND_SLIDING and abs(P[P_KD] * y[Y_X]) + smax > P[P_QS]:
            return False
        if kind == KIND_TFP and (smax > P[P_FHI] or -smax < P[P_FLO]):
            return False
        return True
    kd = P[P_KD]
    ke = P[P_KE] if kind == KIND_BILINEAR else 0.0
    kk = kd + ke
    x = y[Y_X]
    xd = y[Y_XD]
    d0 = 0.0
    xstar = 0.0
    if kind == KIND_BILINEAR:
        xp = x - y[y.shape[0] - 1] / ke
        xstar = ke * xp / kk
        d0 = ke * (xstar - xp)
    dx = x - xstar
    mslab = P[P_MB] + (0.0 if roof else m)
    mst = P[P_MST] + (m if roof else 0.0)
    energy = 0.5 * kk * dx * dx + 0.5 * mslab * xd * xd
    if flex:
        energy += 0.5 * ks * xs * xs + 0.5 * mst * (xd + xsd) ** 2
    # c' P^-1 c for c = (c_dx, c_xs, c_xd, c_xsd): positions diag(kk, ks), velocities
    # [[mslab + mst, mst], [mst, mst]] with inverse [[1, -1], [-1, (mslab + mst) / mst]] / mslab
    if roof:
        c = (0.0, -ks / mst, 0.0, -cs / mst)
    else:
        den = P[P_MB] + m
        c = (-kk / den, ks / den, -P[P_CB] / den, cs / den)
    q = c[0] * c[0] / kk + c[2] * c[2] / mslab
    if flex:
        q += c[1] * c[1] / ks + (-2.0 * c[2] * c[3] + c[3] * c[3] * (mslab + mst) / mst) / mslab
    if math.sqrt(2.0 * energy * q) > thr:
        return False
    if kind == KIND_BILINEAR and abs(d0) + math.sqrt(2.0 * energy * ke * ke / kk) > P[P_Q]:
        return False
    return True


@njit(cache=True)
def _creep_settled(bm, im, y, P, xmax):
    """True when a sliding bearing whose friction rises with speed provably leaves the block stuck.

    After the pulse (``p = 0``, ``nz = 1``), a rigid superstructure, the block stuck on the slab and
    the bearing sliding in the direction ``s = im``: the slab of mass ``M = mb + m`` obeys
    ``M x'' = -kd x - cb x' - s q(|x'|)``.  About ``x* = -s q_s / kd`` (the edge of the stick band)
    the energy ``E = M x'^2/2 + kd (x - x*)^2/2`` has ``E' = -cb x'^2 - s x' (q(|x'|) - q_s) <= 0``
    while ``s x' > 0``, since ``q >= q_s``.  So while the bearing keeps moving that way,
    ``|x'| <= w = sqrt(2 E / M)``, ``|x - x*| <= sqrt(2 E / kd)`` and the block's demand
    ``|A_F| = |kd (x - x*) + cb x' + s (q - q_s)| / M <= (sqrt(2 E kd) + cb w + (q - q_s)(1 -
    exp(-a w))) / M``.  Where the linearised damping ``cb + (q - q_s) a`` over-damps the
    pendulum, the slab creeps towards ``x*`` with a speed that decays exponentially and never
    reaches zero in finite time; if instead it stops, it stops within ``sqrt(2 E / kd)`` of
    ``x*``, inside the stick band ``|kd x| <= q_s`` when ``sqrt(2 E kd) <= 2 q_s``, and then
    nothing moves again (no force acts on a held slab after the pulse).  Either way the block
    never slips again and ``|x|`` stays within ``(q_s + sqrt(2 E kd)) / kd``; the run settles when
    the demand bound is within the block's limit, the stop lands in the band and that ``|x|``
    bound is within the peak ``xmax`` already reached.
    """
    if bm != 0.0 or im == 0.0 or P[P_QA] == 0.0 or P[P_KIND] != KIND_SLIDING or P[P_FLEX] != 0.0:
        return False
    v = y[Y_XD]
    if im * v <= 0.0:
        return False
    kd = P[P_KD]
    qs = P[P_QS]
    M = P[P_MB] + P[P_M]
    dx = y[Y_X] + im * qs / kd
    energy = 0.5 * M * v * v + 0.5 * kd * dx * dx
    w = math.sqrt(2.0 * energy / M)
    reach = math.sqrt(2.0 * energy * kd)
    demand = (reach + P[P_CB] * w + (P[P_Q] - qs) * (1.0 - math.exp(-P[P_QA] * w))) / M
    return demand <= P[P_HOLD] and reach <= 2.0 * qs and (qs + reach) / kd <= xmax


# --- one scene ------------------------------------------------------------------


@njit(cache=True)
def _tfp_enter(im, y, P, u0, r, x0):
    """Set a triple pendulum's surfaces up for the slab's mode ``im`` at the present point.

    ``u0`` (the surfaces' displacements where the slab was at ``x0``) and ``r`` (their rates in the
    mode that ends) are carried to the slab's displacement ``y[Y_X]``; held (``im = 0``): the stick
    band ``[P_FLO, P_FHI]``; moving: the sliding set (:func:`tfp_mode`), its tangent stiffness
    ``P_KE`` and the displacement ``P_XNEXT`` where the set next changes.  Within a mode the
    surfaces' displacements are linear in ``x``, so they are exact from event to event.

    Returns ``(x0, stage, capacity)``: the new reference point, the regime (:func:`tfp_stage`) and
    whether the bearing has reached its displacement capacity (an inner surface on its restrainer
    in the direction of motion, or no surface able to move that way).
    """
    u = np.empty(4)
    tfp_moved(u0, r, y[Y_X] - x0, P, u)
    for i in range(4):
        u0[i] = u[i]
    x0 = y[Y_X]
    if im == 0.0:
        for i in range(4):
            r[i] = 0.0
        lo, hi = tfp_band(u0, P)
        P[P_FLO] = lo
        P[P_FHI] = hi
        return x0, 0, False
    K = tfp_mode(im, u0, y[y.shape[0] - 1], P, r)
    if math.isinf(K) or _at_stop(1, im, u0, P) or _at_stop(2, im, u0, P):
        return x0, -1, True
    P[P_KE] = K
    P[P_XNEXT] = x0 + im * tfp_reach(im, u0, y[y.shape[0] - 1], K, r, P)
    return x0, tfp_stage(r, u0, P), False



@njit(cache=True)
def _rock_start(s, im, tau, y, P, code, params):
    """Mode of a block that tips onto its corner ``s`` at ``tau``.

    Rock, or slide-rock when friction cannot hold the pivot at once (Shenton 1996), sliding against
    the friction it needs.
    """
    nz, _ = normal(tau, P)
    A = np.empty(int(P[P_N]))
    bm = 4.0 * s
    AF = _accels(bm, im, accel_at(code, params, tau), nz, y, P, A)[1]
    H, V = contact(bm, nz, y, AF, AF, P)
    if abs(H) <= P[P_RMUS] * V:
        return bm
    return bm + (-1.0 if H > 0.0 else 1.0)


@njit(cache=True)
def _contact_loss(bm, im, tau, y, P, code, params):
    """The rocking block's loss of contact at an accepted state (index in :data:`CONTACT_LOSSES`; 0: none).

    Below the tipping angle: flight when the vertical contact force is negative, and, for a pivot
    that starts to slide, no consistent slide-rock (the equations' determinant not positive, or the
    pivot accelerating against its sliding direction).
    """
    s, psi, psd, d = _tilt(bm, y, P)
    if psi >= math.atan(P[P_ROCK]):
        return 0
    nz, _ = normal(tau, P)
    A = np.empty(int(P[P_N]))
    Ab, AF, udd, fh, R, thdd = _accels(bm, im, accel_at(code, params, tau), nz, y, P, A)
    H, V = contact(bm, nz, y, AF, AF + udd, P)
    if V < 0.0:
        return 1
    sig = base_slide(bm)
    if sig != 0.0:
        cc = s * math.cos(d) + P[P_RMUK] * sig * math.sin(d)
        # a pivot starting to slide must not accelerate against its direction (beyond round-off: at the
        # slip threshold its acceleration starts from zero)
        if 1.0 - 0.75 * cc * s * math.cos(d) <= 0.0 or (y[y.shape[0] - 2] == 0.0 and
                                                         sig * udd < -1e-9 * P[P_RG] * nz):
            return 3
    return 0


@njit(cache=True)
def _impact(bm, im, tau, y, P, code, params):
    """The rocking block's impact at ``theta = 0``: its new mode, with ``theta'`` and ``u'`` set in ``y``.

    The other corner ``s' = -s`` strikes and becomes the pivot; the angular momentum about it is
    kept, ``theta'+ = e theta'- - kappa (u'+ - u'-)`` with ``kappa = 3 h/(4 R^2)``, and the impulse
    obeys Coulomb's law: the new pivot sticks (``u'+ = 0``) when that needs ``|J_x| <= mu_s J_y``,
    else it slides with ``J_x = -mu_k sigma J_y`` (:mod:`isoslide.peers.slide_rock`).  The floors'
    velocities are kept (an approximation of order ``Pi8``).  A block that provably cannot tilt
    past ``P_REPS`` again with the floor's present demand comes to rest (or slides flat, with the
    horizontal velocity of its centre of mass).  Returns NaN when no impulse is consistent.
    """
    n = int(P[P_N])
    th = Y_XS + 2 * n
    ud = y.shape[0] - 2
    s = corner(bm)
    s2 = -s
    alpha = math.atan(P[P_ROCK])
    R = P[P_RR]
    b = R * math.sin(alpha)
    h = R * math.cos(alpha)
    kap = 0.75 * h / (R * R)
    e = P[P_RE]
    tdm = y[th + 1]
    udm = y[ud] if base_slide(bm) != 0.0 else 0.0
    y[th] = 0.0
    tdp = e * tdm + kap * udm
    jx = h * tdp - udm - h * tdm
    jy = -s * b * (tdp + tdm)
    nz, _ = normal(tau, P)
    p = accel_at(code, params, tau)
    A = np.empty(n)
    eps = P[P_REPS]
    if abs(jx) <= P[P_RMUS] * jy:
        y[th + 1] = tdp
        y[ud] = 0.0
        AF0 = _accels(0.0, im, p, nz, y, P, A)[1]
        D = P[P_RK] * (P[P_RG] * nz * math.sin(alpha - eps) - abs(AF0) * math.cos(alpha - eps))
        if D > 0.0 and tdp * tdp <= 2.0 * D * eps:
            y[th + 1] = 0.0
            return 0.0
        return 4.0 * s2
    sg = 1.0 if jx < 0.0 else -1.0
    mu = P[P_RMUK]
    a0 = h * e * tdm + h * kap * udm - udm - h * tdm
    b0 = -s * b * ((1.0 + e) * tdm + kap * udm)
    up = -(a0 + mu * sg * b0) / (1.0 - h * kap + mu * sg * s * b * kap)
    tdp = e * tdm - kap * (up - udm)
    if not (up * sg > 0.0 and -s * b * (tdp + tdm) >= 0.0 and s2 * tdp > 0.0):
        return math.nan
    y[th + 1] = 0.0
    y[ud] = up
    bm2 = 4.0 * s2 + sg
    d = -s2 * _accels(bm2, im, p, nz, y, P, A)[5]
    if d > 0.0 and tdp * tdp <= 2.0 * d * eps:
        v = up + h * tdp
        y[ud] = v
        return 0.0 if v == 0.0 else (1.0 if v > 0.0 else -1.0)
    y[th + 1] = tdp
    return bm2


@njit(cache=True)
def _record(hist, nh, hist_cap, tau, y, bm, im, stage, P, code, params):
    """Append ``[tau, x, x', xs.., xs'.., theta, theta', u, u', fh, bm, im, stage]`` to the history while it has room."""
    if nh < hist_cap:
        ny = y.shape[0]
        hist[nh, H_TAU] = tau
        for i in range(ny - 1):
            hist[nh, H_X + i] = y[i]
        A = np.empty(int(P[P_N]))
        hist[nh, ny] = _accels(bm, im, accel_at(code, params, tau), normal(tau, P)[0], y, P, A)[3]
        hist[nh, ny + 1] = bm
        hist[nh, ny + 2] = im
        hist[nh, ny + 3] = stage
        return nh + 1
    return nh


@njit(cache=True)
def run(P, code, params, breakpoints, tau_start, tau_end, tau_stop, h_max_pulse, h_max_free, rtol, atol,
        hist_cap, h_restart, settle, max_steps, Wm, Cm, Vm, Lm, Wh, Ch, Vh, Lh):
    """Integrate one general scene from rest at ``tau_start`` (see the module docstring).

    Arguments as :func:`isoslide.engine.kernel.run` (without ``track_max``), with the model parameters
    ``P`` of :func:`isoslide.engine.building.parameters` and the modal data ``Wm, Cm, Vm, Lm, Wh, Ch,
    Vh, Lh`` of :func:`isoslide.engine.building.modal_data`: the settlement test, and the exact steps
    of the free linear phase after the pulse (:mod:`isoslide.engine.free_phase`), taken wherever
    their bound proves that nothing slips or yields within them (at most ``h_max_free`` long while
    a history is recorded).

    Returns
    -------
    ints : ndarray of int64, shape (N_R,)
        ``R_STEPS`` Runge-Kutta steps of every kind, ``R_EVENTS`` block transitions,
        ``R_SETTLED``, ``R_SLIPPED`` (the block slid), ``R_HIST`` history rows,
        ``R_ISO_EVENTS`` isolator transitions, ``R_ISO_MOVED`` (the bearing slid or yielded),
        ``R_REJECTED`` rejected steps.
    floats : ndarray of float64, shape (N_F,)
        ``F_UMAX`` (= Pi1), ``F_TPEAK``, ``F_URES`` (final u), ``F_TEND``, ``F_XMAX`` largest
        ``|x|`` at step ends and transitions, ``F_VMAX`` largest ``|u'|`` at step ends.
    hist : ndarray, shape (ints[R_HIST], history_width(n))
        Rows ``[tau, x, x', xs_1..n, xs_1'..n', u, u', fh, bm, im]`` (:func:`history_columns`).
    """
    P = P.copy()    # a triple pendulum keeps its present band, stiffness and next change here
    rock_first = P[P_ROCK] > 0.0 and P[P_RMUS] > P[P_ROCK]    # the block tips before it can slide
    thr = P[P_HOLD]
    q = P[P_Q]
    qs = P[P_QS]
    kind = P[P_KIND]
    tfp = kind == KIND_TFP
    nfl = int(P[P_N])
    ny = 2 * nfl + 7
    Y_TH = Y_XS + 2 * nfl
    Y_U = ny - 3
    Y_UD = ny - 2
    Y_FH = ny - 1
    y = np.zeros(ny)
    y1 = np.empty(ny)
    ye = np.empty(ny)
    yb = np.empty(ny)
    K = np.empty((NS + 1, ny))
    work = np.empty(ny)
    d0 = np.empty(ny)
    d1 = np.empty(ny)
    A = np.empty(nfl)
    cnt = np.zeros(1, dtype=np.int64)
    hist = np.empty((hist_cap if hist_cap > 0 else 1, ny + 4))   # history_width(nfl)
    tau = tau_start
    bm = 0.0
    im = 0.0
    b_just = False
    i_just = False
    umax = 0.0
    tpeak = tau_start
    upeak = 0.0
    xmax = 0.0
    vmax = 0.0
    steps = 0
    rejected = 0
    events = 0
    iso_events = 0
    settled = False
    slipped = False
    moved = False
    h = h_restart
    hlast = h_restart
    ib = 0
    stage = 0
    nh = _record(hist, 0, hist_cap, tau, y, bm, im, stage, P, code, params)
    a_x = np.empty(max(Wm.shape[0], Wh.shape[0]), dtype=np.complex128)
    a_y = np.zeros(a_x.shape[0], dtype=np.complex128)
    limits = np.array([thr, qs])
    offsets = np.zeros((2, 2))
    zone = 0.0
    if P[P_COULOMB] == 0.0 and P[P_PI6] > 0.0 and P[P_PI2] < P[P_THR]:
        zone = 30.0 / P[P_PI6]
    check = zone > 0.0
    # a triple pendulum's surfaces: displacements u0 where the slab was at tx0, rates tr in its mode
    tu0 = np.zeros(4)
    tr = np.zeros(4)
    tx0 = 0.0
    tfp_im = 0.0
    stage_max = 0
    capacity = False
    r_just = False     # a rocking phase began at theta = 0 at the accepted point
    stalled = 0
    thmax = 0.0
    overturned = False
    modes = 1
    loss = 0
    tloss = math.nan
    impacts = 0
    alpha = math.atan(P[P_ROCK])
    if tfp:
        tx0, stage, capacity = _tfp_enter(0.0, y, P, tu0, tr, tx0)
    while True:
        if tfp and im != tfp_im:
            if tfp_im == 0.0:
                y[Y_FH] = P[P_FHI] if im > 0.0 else P[P_FLO]
            tx0, stage, capacity = _tfp_enter(im, y, P, tu0, tr, tx0)
            tfp_im = im
            stage_max = max(stage_max, stage)
            if capacity:
                break
        modes |= 1 << block_mode(bm)
        if corner(bm) != 0.0:
            loss = _contact_loss(bm, im, tau, y, P, code, params)
            if loss != 0:
                tloss = tau
                break
        # --- mode checks at the accepted point (round-off past a limit) ---------
        p_now = accel_at(code, params, tau)
        if bm == 0.0 or (_sticks(P) and im == 0.0):
            nz_now, _ = normal(tau, P)
            Ab, AF, udd, fh, R, thdd = _accels(bm, im, p_now, nz_now, y, P, A)
            free_b = bm == 0.0 and abs(AF) > thr * nz_now
            free_i = _sticks(P) and im == 0.0 and _excess(fh, nz_now, P) > 0.0
            if free_b or free_i:
                nb_, ni_ = _select_modes(bm, im, free_b, free_i, tau, y, P, code, params)
                if rock_first and free_b and nb_ != 0.0:
                    nb_ = _rock_start(nb_, ni_, tau, y, P, code, params)
                    r_just = True
                if nb_ != bm:
                    bm, b_just = nb_, True
                    slipped = slipped or base_slide(bm) != 0.0
                    events += 1
                if ni_ != im:
                    im, i_just, moved = ni_, True, True
                    iso_events += 1
                    if tfp:
                        continue
        if kind == KIND_BILINEAR and im == 0.0 and abs(y[Y_FH]) > q:
            im = 1.0 if y[Y_FH] > 0.0 else -1.0
            y[Y_FH] = im * q
            moved = True
            iso_events += 1
        if tau >= tau_end and (_settled(bm, im, y, P, Wm, Cm, Wh, Ch) or _creep_settled(bm, im, y, P, xmax)):
            settled = True
            if settle:
                break
        if tau >= tau_stop or steps + cnt[0] > max_steps:
            break
        # --- the free linear phase: an exact step where its bound proves it safe --------
        if tau >= tau_end and bm == 0.0 and im == 0.0:
            held = _held(im, P)
            W, Cd, V, L = (Wh, Ch, Vh, Lh) if held else (Wm, Cm, Vm, Lm)
            base = 0.0
            if tfp:
                base, limits[1] = held_band(P)
            taken, tau = free_phase.exact_step(W, Cd, V, L, y, -1, held, base, P[P_KD], limits, offsets, a_x, a_y,
                                               tau, tau_stop, h_max_free, hist_cap > 0)
            if taken:
                steps += 1
                xmax = max(xmax, abs(y[Y_X]))
                nh = _record(hist, nh, hist_cap, tau, y, bm, im, stage, P, code, params)
                continue
        # --- step length ---------------------------------------------------------
        ib = _next_breakpoint(breakpoints, ib, tau)
        # after the pulse, steps are held to h_max_free while a demand is watched for its limit
        # (a stuck block, a held or elastic bearing); a sliding block and a linear, sliding or
        # yielding isolator have only speed events, found by sign, as during the pulse
        watch = bm == 0.0 or bm == 4.0 or bm == -4.0 or ((_sticks(P) or kind == KIND_BILINEAR) and im == 0.0)
        hmax = h_max_pulse if tau < tau_end or not watch else h_max_free
        h = min(h, hmax)
        target = _step_target(breakpoints, ib, tau_stop)
        hit_target = False
        if tau + h >= target:
            h = target - tau
            hit_target = True
        # --- attempt until accepted ------------------------------------------------
        while True:
            err = rk_step(bm, im, tau, y, h, P, code, params, atol, rtol, K, y1)
            steps += 1
            if err <= 1.0 and bm != 0.0 and zone > 0.0 and (
                    min(abs(y[Y_UD]), abs(y1[Y_UD])) < zone or y[Y_UD] * y1[Y_UD] <= 0.0):
                err = max(err, verify(bm, im, tau, y, h, y1, P, code, params, atol, rtol, K))
                steps += 2
            if err <= 1.0:
                break
            rejected += 1
            h *= _step_factor(err)
            hit_target = False
        hnext = _next_step(h, err)
        tnew = target if hit_target else tau + h
        t_end_step = _left_limit(tnew)
        # --- events inside the step: the earliest --------------------------------
        best = -1
        best_sig = 0.0
        hbest = math.inf
        herr_best = 0.0
        if bm == 0.0 or (_sticks(P) and im == 0.0):
            # the demands' rates at the step's ends, shared by every demand event
            deriv(bm, im, tau, y, P, code, params, d0)
            deriv(bm, im, t_end_step, y1, P, code, params, d1)
        if bm == 0.0:
            best, best_sig, hbest, herr_best = _earliest_demand_event(
                EV_BLOCK, EV_BPEAK, thr, bm, im, tau, y, y1, h, t_end_step, P, code, params, atol, rtol, check, K,
                ye, yb, work, cnt, best, best_sig, hbest, herr_best, d0, d1)
        else:
            if base_slide(bm) != 0.0:
                found, hs, herr = _speed_candidate(EV_BSPEED, bm, im, tau, y, y1, h, t_end_step, b_just, check, P,
                                                   code, params, atol, rtol, K, ye, work, cnt)
                if found and hs < hbest:
                    best, hbest, herr_best = EV_BSPEED, hs, herr
                    copy_state(yb, ye)
            if corner(bm) != 0.0:
                # the rocking block: impact, overturning and (below the tipping angle) its pivot slipping,
                # also in a step that ends past the tipping angle
                pivot = base_slide(bm) == 0.0 and corner(bm) * y[Y_TH] < alpha
                for ev in (EV_IMPACT, EV_OVER, EV_PIVOT, EV_FLIGHT):
                    if ev == EV_PIVOT and not pivot:
                        continue
                    found, hs, herr = _speed_candidate(ev, bm, im, tau, y, y1, h, t_end_step,
                                                       r_just if ev == EV_IMPACT else b_just, check, P, code, params,
                                                       atol, rtol, K, ye, work, cnt)
                    if ev == EV_PIVOT and found and corner(bm) * ye[Y_TH] >= alpha:
                        found = False
                    if found and hs < hbest:
                        best, hbest, herr_best = ev, hs, herr
                        copy_state(yb, ye)
        if _sticks(P) and im == 0.0:
            best, best_sig, hbest, herr_best = _earliest_demand_event(
                EV_BEAR, EV_IPEAK, qs, bm, im, tau, y, y1, h, t_end_step, P, code, params, atol, rtol, check, K,
                ye, yb, work, cnt, best, best_sig, hbest, herr_best, d0, d1)
        elif kind == KIND_BILINEAR and im == 0.0:
            for sig in (1.0, -1.0):
                g0, r0 = _event(EV_YIELD, sig, bm, im, tau, y, P, code, params, work)
                g1, r1 = _event(EV_YIELD, sig, bm, im, t_end_step, y1, P, code, params, work)
                if g1 > 0.0:
                    if g0 >= 0.0:
                        hs, herr = 0.0, 0.0
                        copy_state(ye, y)
                    else:
                        hs, herr = locate(EV_YIELD, sig, bm, im, tau, y, 0.0, g0, h, g1,
                                          hermite_root(g0, r0, g1, r1, h), check, P, code, params, atol, rtol,
                                          K, ye, work, cnt)
                    if hs < hbest:
                        best, best_sig, hbest, herr_best = EV_YIELD, sig, hs, herr
                        copy_state(yb, ye)
                elif r0 > 0.0 and r1 < 0.0 and _hermite_max(g0, r0, g1, r1, h) >= -1e-2 * q:
                    # an interior peak of sig fh: where x' = 0
                    hm, herr = locate(EV_XD, sig, bm, im, tau, y, 0.0, sig * y[Y_XD], h,
                                      sig * y1[Y_XD], -1.0, False, P, code, params, atol, rtol, K, ye, work, cnt)
                    gm = sig * ye[Y_FH] - q
                    if gm > 0.0:
                        hs, herr = locate(EV_YIELD, sig, bm, im, tau, y, 0.0, g0, hm, gm, -1.0, check, P, code,
                                          params, atol, rtol, K, ye, work, cnt)
                        if hs < hbest:
                            best, best_sig, hbest, herr_best = EV_YIELD, sig, hs, herr
                            copy_state(yb, ye)
        elif _sticks(P) or kind == KIND_BILINEAR:
            found, hs, herr = _speed_candidate(EV_ISPEED, bm, im, tau, y, y1, h, t_end_step, i_just, check, P, code,
                                               params, atol, rtol, K, ye, work, cnt)
            if found and hs < hbest:
                best, hbest, herr_best = EV_ISPEED, hs, herr
                copy_state(yb, ye)
            if tfp:
                g1, r1 = _event(EV_TFP, 0.0, bm, im, t_end_step, y1, P, code, params, work)
                if g1 >= 0.0:
                    g0, r0 = _event(EV_TFP, 0.0, bm, im, tau, y, P, code, params, work)
                    if g0 >= 0.0:
                        hs, herr = 0.0, 0.0
                        copy_state(ye, y)
                    else:
                        hs, herr = locate(EV_TFP, 0.0, bm, im, tau, y, 0.0, g0, h, g1, hermite_root(g0, r0, g1, r1, h),
                                          check, P, code, params, atol, rtol, K, ye, work, cnt)
                    if hs < hbest:
                        best, hbest, herr_best = EV_TFP, hs, herr
                        copy_state(yb, ye)
        if best >= 0:
            if herr_best > 1.0:
                h = 0.5 * hbest
                continue
            # a rocking block's modes that cannot be resolved (events without time passing, for ever)
            stalled = stalled + 1 if hbest == 0.0 and P[P_ROCK] > 0.0 else 0
            if stalled > MAX_STALLED:
                loss, tloss = 3, tau
                break
            if corner(bm) != 0.0 and corner(bm) * y[Y_TH + 1] > 0.0 and corner(bm) * yb[Y_TH + 1] < 0.0:
                # the tilt's peak before the event, inside the step it ends
                locate(EV_APEX, 0.0, bm, im, tau, y, 0.0, corner(bm) * y[Y_TH + 1], hbest,
                       corner(bm) * yb[Y_TH + 1], -1.0, False, P, code, params, atol, rtol, K, ye, work, cnt)
                thmax = max(thmax, abs(ye[Y_TH]))
            tau = tau + hbest
            copy_state(y, yb)
            xmax = max(xmax, abs(y[Y_X]))
            thmax = max(thmax, abs(y[Y_TH]))
            if abs(y[Y_U]) > umax:
                # the contents' peak also where a slide ends otherwise than by stopping (a slide-rocking
                # block's impact, its pivot sticking, its overturning)
                umax, tpeak, upeak = abs(y[Y_U]), tau, y[Y_U]
            short = check
            if best == EV_BLOCK:
                if rock_first:
                    bm, b_just, r_just = _rock_start(-best_sig, im, tau, y, P, code, params), True, True
                    slipped = slipped or base_slide(bm) != 0.0
                else:
                    bm, b_just, slipped = -best_sig, True, True
                events += 1
            elif best == EV_IMPACT:
                impacts += 1
                events += 1
                nb_ = _impact(bm, im, tau, y, P, code, params)
                if nb_ != nb_:
                    loss, tloss = 2, tau
                    nh = _record(hist, nh, hist_cap, tau, y, bm, im, stage, P, code, params)
                    break
                bm, b_just, r_just = nb_, True, True
                slipped = slipped or base_slide(bm) != 0.0
                short = False    # the next excursion is like the last one, e times smaller
            elif best == EV_FLIGHT:
                loss, tloss = 1, tau
                nh = _record(hist, nh, hist_cap, tau, y, bm, im, stage, P, code, params)
                break
            elif best == EV_OVER:
                overturned = True
                y[Y_TH] = corner(bm) * 0.5 * math.pi
                thmax = 0.5 * math.pi
                nh = _record(hist, nh, hist_cap, tau, y, bm, im, stage, P, code, params)
                break
            elif best == EV_PIVOT:
                nz_now, _ = normal(tau, P)
                AF = _accels(bm, im, accel_at(code, params, tau), nz_now, y, P, A)[1]
                H, V = contact(bm, nz_now, y, AF, AF, P)
                bm, b_just, slipped = bm + (-1.0 if H > 0.0 else 1.0), True, True
                events += 1
            elif best == EV_BEAR:
                im, i_just, moved = best_sig, True, True
                y[Y_XD] = 0.0
                iso_events += 1
            elif best == EV_YIELD:
                im, moved = best_sig, True
                y[Y_FH] = best_sig * q
                i_just = False
                iso_events += 1
            elif best == EV_BSPEED and corner(bm) != 0.0:
                # a slide-rocking block's pivot stops: it rocks on if friction holds it, else slides back
                y[Y_UD] = 0.0
                events += 1
                bm = _rock_start(corner(bm), im, tau, y, P, code, params)
                b_just = base_slide(bm) != 0.0
            elif best == EV_BSPEED:
                y[Y_UD] = 0.0
                events += 1
                free_i = _sticks(P) and im == 0.0
                bm, ni_ = _select_modes(bm, im, True, free_i, tau, y, P, code, params)
                if rock_first and bm != 0.0:
                    bm = _rock_start(bm, ni_, tau, y, P, code, params)
                    r_just = True
                b_just = bm != 0.0
                if ni_ != im:
                    im, i_just, moved = ni_, True, True
                    iso_events += 1
                short = check and bm != 0.0
            elif best == EV_TFP:
                iso_events += 1
                tx0, stage, capacity = _tfp_enter(im, y, P, tu0, tr, tx0)
                stage_max = max(stage_max, stage)
                if capacity:
                    nh = _record(hist, nh, hist_cap, tau, y, bm, im, stage, P, code, params)
                    break
                short = False
            else:  # EV_ISPEED
                y[Y_XD] = 0.0
                iso_events += 1
                if tfp:
                    tx0, stage, capacity = _tfp_enter(0.0, y, P, tu0, tr, tx0)
                    tfp_im = 0.0
                if _sticks(P):
                    free_b = bm == 0.0
                    nb_, im = _select_modes(bm, im, free_b, True, tau, y, P, code, params)
                    if rock_first and free_b and nb_ != 0.0:
                        nb_ = _rock_start(nb_, im, tau, y, P, code, params)
                        r_just = True
                    i_just = im != 0.0
                    if nb_ != bm:
                        bm, b_just = nb_, True
                        slipped = slipped or base_slide(bm) != 0.0
                        events += 1
                else:
                    # a yielding bilinear bearing unloads unless x' only touches zero
                    Ab, AF, udd, fh, R, thdd = _accels(bm, im, accel_at(code, params, tau), normal(tau, P)[0], y, P,
                                                       A)
                    if im * (Ab - accel_at(code, params, tau)) > 0.0:
                        i_just = True
                    else:
                        im, i_just = 0.0, False
            h = h_restart if short else max(h_restart, 0.5 * hlast)
            nh = _record(hist, nh, hist_cap, tau, y, bm, im, stage, P, code, params)
            continue
        if corner(bm) != 0.0:
            r_just = False
            # the tilt's peak inside the step: where psi' = 0
            s_ = corner(bm)
            g0 = s_ * y[Y_TH + 1]
            g1 = s_ * y1[Y_TH + 1]
            if g0 > 0.0 and g1 < 0.0:
                locate(EV_APEX, 0.0, bm, im, tau, y, 0.0, g0, h, g1, -1.0, False, P, code, params, atol, rtol,
                       K, ye, work, cnt)
                thmax = max(thmax, abs(ye[Y_TH]))
        if bm != 0.0:
            b_just = False
            if abs(y1[Y_UD]) > vmax:
                vmax = abs(y1[Y_UD])
        if im != 0.0:
            i_just = False
        # --- accept -----------------------------------------------------------------
        tau = tnew
        copy_state(y, y1)
        thmax = max(thmax, abs(y[Y_TH]))
        if base_slide(bm) == 0.0:
            y[Y_UD] = 0.0
        if _held(im, P):
            y[Y_XD] = 0.0
        xmax = max(xmax, abs(y[Y_X]))
        if abs(y[Y_U]) > umax:
            umax, tpeak, upeak = abs(y[Y_U]), tau, y[Y_U]
        hlast = h
        h = hnext
        nh = _record(hist, nh, hist_cap, tau, y, bm, im, stage, P, code, params)
    if not settled and base_slide(bm) != 0.0 and abs(y[Y_U]) > umax:
        umax, tpeak, upeak = abs(y[Y_U]), tau, y[Y_U]
    ints = np.array([steps + cnt[0], events, 1 if settled else 0, 1 if slipped else 0, nh, iso_events,
                     1 if moved else 0, rejected, stage_max, 1 if capacity else 0, 1 if overturned else 0, modes, loss,
                     impacts], dtype=np.int64)
    floats = np.array([umax, tpeak, y[Y_U], tau, xmax, vmax, upeak, thmax, tloss])
    return ints, floats, hist[:nh]


@njit(cache=True)
def affine_rates(bm, P, code, params, idx, ny):
    """``(A, e)``: the rates of the states ``y[idx]`` after any pulse, ``out[idx] = A y[idx] + e``.

    In the block's mode ``bm`` with the isolator elastic or held; built column by column from
    :func:`deriv` (affine in ``y``) at unit states; ``ny`` is the state's length (:func:`state_size`).
    """
    m = idx.shape[0]
    A = np.zeros((m, m))
    e = np.zeros(m)
    y = np.zeros(ny)
    out = np.zeros(ny)
    late = 1e30   # after every pulse and record: p = 0
    deriv(bm, 0.0, late, y, P, code, params, out)
    for i in range(m):
        e[i] = out[idx[i]]
    for j in range(m):
        y[:] = 0.0
        y[idx[j]] = 1.0
        deriv(bm, 0.0, late, y, P, code, params, out)
        for i in range(m):
            A[i, j] = out[idx[i]] - e[i]
    return A, e


@njit(cache=True)
def free_system(P, code, params, held, idx, ny, n_rows):
    """The free linear system after the pulse: ``(A, c)`` with ``z' = A z`` for the moving states ``z = y[idx]``.

    The block is stuck and the isolator stuck (``held``) or elastic; ``A`` is :func:`affine_rates`'s
    (the constant part is zero), and the demands' rows ``c``
    (0: the block's floor acceleration; 1, when ``n_rows = 2``: the bilinear bearing's force, or
    the force holding a sliding bearing) from :func:`_floor_stuck` and :func:`_bearing_need`.
    ``ny`` is the state's length (:func:`state_size`).
    """
    n = int(P[P_N])
    m = idx.shape[0]
    A, _ = affine_rates(0.0, P, code, params, idx, ny)
    c = np.zeros((n_rows, m))
    y = np.zeros(ny)
    for j in range(m):
        y[:] = 0.0
        y[idx[j]] = 1.0
        fh = y[ny - 1] if P[P_KIND] == KIND_BILINEAR else 0.0
        zp = y[Y_XS:Y_XS + n]
        zv = y[Y_XS + n:Y_XS + 2 * n]
        c[0, j] = _floor_stuck(0.0, y[Y_X], y[Y_XD], zp, zv, fh, 0.0, P[P_KD], P)
        if n_rows > 1:
            c[1, j] = _bearing_need(0.0, 0.0, zp, zv, 0.0, 0.0, P[P_KD], P) if held else fh
    return A, c


FREE_MODES_COND = 1e8
"""Largest condition number of the free phase's eigenvectors that :func:`spread_modes` accepts."""


@njit(cache=True)
def spread_modes(lam, V, Winv, cond, grows, c, idx, ny):
    """Modal data of the free linear system of :func:`free_system` (:func:`isoslide.engine.building.modal_data`).

    From the modes ``(lam, V, Winv, cond, grows)`` of its matrix as
    :func:`isoslide.engine.free_phase.decompose` (or ``modes``) gives them, ``c`` its demands' rows
    and ``idx`` its moving states.  Returns ``(W, C, V, L, ok)``: ``A = V diag(L) W`` with the modes
    ordered from the fastest to the slowest (stable order), the modes of a conjugate pair exact
    conjugates, ``W`` and ``V`` spread over the whole state of length ``ny`` (zero columns and rows
    for the states that do not move), ``C = margin c V`` with a relative margin for the round-off of
    the decomposition; ``ok`` False (and empty arrays) where a mode grows or the eigenvectors'
    condition number exceeds :data:`FREE_MODES_COND`.
    """
    m = idx.shape[0]
    if grows or not cond <= FREE_MODES_COND:
        return (np.zeros((0, ny), dtype=np.complex128), np.zeros((0, 0), dtype=np.complex128),
                np.zeros((ny, 0), dtype=np.complex128), np.zeros(0, dtype=np.complex128), False)
    W = np.zeros((m, ny), dtype=np.complex128)
    Vfull = np.zeros((ny, m), dtype=np.complex128)
    for i in range(m):
        for j in range(m):
            W[i, idx[j]] = Winv[i, j]
            Vfull[idx[i], j] = V[i, j]
    margin = 1.0 + 1e-12 + 1e-14 * cond
    return W, margin * (c.astype(np.complex128) @ V), Vfull, lam, True

# numba reads the compiled code shipped with the package (isoslide.jit_cache) before compiling any of it
jit_cache.seed(run)
