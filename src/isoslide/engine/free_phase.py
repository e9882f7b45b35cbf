"""Exact propagation of a building's free linear phase after the excitation (numba).

Once every excitation has ended, a building whose contents are stuck and whose isolator is held or
elastic is a linear time-invariant system ``z' = A z`` of its moving states ``z``
(:func:`isoslide.engine.building.modal_data`), the same along each horizontal axis.  With
``A = V diag(lambda) V^-1`` and the modal coordinates ``a = W y`` of an axis, each mode evolves
exactly as

    a_k(t + s) = a_k(t) exp(lambda_k s),

so a step of any length costs one complex exponential per mode and axis, where an explicit
Runge-Kutta step is held to a fraction of the shortest period followed (a stiff superstructure
of many storeys makes that period short and the wait for settlement long).

What a step must not skip is a demand reaching its limit: the stuck contents' floor acceleration
(limit ``thr``) and the isolator's force (limit ``q``), in the plane the vectors
``d_j = o_j + Re sum_k C[j, k] a_k`` with ``a_k = (a_k^x, a_k^y)`` (along a line ``a^y = 0``).  As
``Re lambda_k <= 0`` (checked by :func:`isoslide.engine.building.modal_data`), ``|a_k|`` never
grows, and for any split of the modes into tracked ones ``L`` and bounded ones ``H``, for
``0 <= s <= h``::

    |d_j(t + s)| <= |o_j + Re sum_L C_jk a_k(t)| + h sum_L |C_jk lambda_k| |a_k(t)| + sum_H |C_jk| |a_k(t)|

(the tracked part moves at most at its rate bound, the bounded part never exceeds its amplitude;
``|a_k| = sqrt(|a_k^x|^2 + |a_k^y|^2)``).  :func:`safe_step` returns the longest ``h`` this proves
safe for every demand, over the splits that bound the fastest modes by their amplitudes and track
the slower ones.  A step within it contains no breakaway and no yield, so its end is reached
exactly (to the round-off of ``V`` and ``W``) with nothing to locate.  Where the bound allows no
useful step (a demand near its limit), the caller takes an ordinary Runge-Kutta step, which
locates any event.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .. import jit_cache

SAFETY = 0.9
"""Fraction of the proven-safe step length taken."""
SLACK = 1e-6
"""Room kept below each limit, relative to the demand's bound: the round-off of the bound and the
relative margin that :func:`isoslide.engine.building.modal_data` puts on ``C``."""


@njit(cache=True)
def decompose(A):
    """Modes of a real matrix: ``(lam, V, W, cond, grows)`` with ``A = V diag(lam) W``.

    The modes are ordered from the fastest (largest ``|lambda|``) to the slowest, in a stable order,
    and each complex mode's conjugate is a mode with exactly the conjugate eigenvalue and
    eigenvector (as for a real matrix's own decomposition); ``W = V^-1``, ``cond`` is the 2-norm
    condition number of ``V`` and ``grows`` whether a mode grows (``Re lambda > 1e-12 max(1,
    |lambda|)``).
    """
    lam, V = np.linalg.eig(A.astype(np.complex128))
    return arrange(lam, V)


@njit(cache=True)
def arrange(lam, V):
    """The modes ``(lam, V)`` of a real matrix from an eigensolver, arranged as :func:`decompose` gives them.

    ``lam`` and ``V`` (complex128) are changed in place: a complex mode's conjugate made exact, the
    modes sorted from the fastest, ``W = V^-1``, the condition number and whether a mode grows.
    """
    m = lam.shape[0]
    top = 1.0
    for k in range(m):
        top = max(top, abs(lam[k]))
    real_tol = 1e-14 * top
    paired = np.zeros(m, dtype=np.bool_)
    for k in range(m):
        if paired[k] or lam[k].imag <= real_tol:
            continue
        best = -1
        gap = np.inf
        for j in range(m):
            if j != k and not paired[j] and lam[j].imag < -real_tol and abs(lam[j] - np.conj(lam[k])) < gap:
                best, gap = j, abs(lam[j] - np.conj(lam[k]))
        if best >= 0:
            lam[best] = np.conj(lam[k])
            V[:, best] = np.conj(V[:, k])
            paired[k] = True
            paired[best] = True
    grow = -np.inf
    for k in range(m):
        if not paired[k] and abs(lam[k].imag) <= real_tol:
            lam[k] = lam[k].real
        grow = max(grow, lam[k].real)
    order = np.argsort(-np.abs(lam), kind="mergesort")
    lam = lam[order]
    V = np.ascontiguousarray(V[:, order])
    cond = np.linalg.cond(V)
    W = np.ascontiguousarray(np.linalg.inv(V)) if cond < 1e300 else np.zeros((m, m), dtype=np.complex128)
    return lam, V, W, cond, grow > 1e-12 * top


MODES_KEPT = 512
"""How many matrices' modes :func:`modes` keeps (the oldest dropped first)."""
_MODES: dict = {}


def modes(A: np.ndarray) -> tuple:
    """:func:`decompose` of a real matrix ``A``, kept per matrix.

    The scenes of a study share their buildings' matrices (the contents' friction and the pulse
    enter the forcing, not the matrix), so each is decomposed once; the same matrix gives the same
    bits, kept or decomposed anew.  The arrays returned are shared: they must not be changed (they
    stay writable, so that the kernels compiled for the modal data take them as they are).
    """
    A = np.ascontiguousarray(A, dtype=np.float64)
    key = (A.shape, A.tobytes())
    kept = _MODES.get(key)
    if kept is None:
        kept = decompose(A)
        if len(_MODES) >= MODES_KEPT:
            del _MODES[next(iter(_MODES))]
        _MODES[key] = kept
    return kept


def forget() -> None:
    """Forget every matrix's modes that :func:`modes` keeps."""
    _MODES.clear()


@njit(cache=True)
def modal_coordinates(W, y, o, a):
    """``a = W y[o : o + W.shape[1]]``: the complex modal coordinates of one axis, into ``a``."""
    for k in range(W.shape[0]):
        acc = 0.0 + 0.0j
        for i in range(W.shape[1]):
            acc += W[k, i] * y[o + i]
        a[k] = acc


@njit(cache=True)
def safe_step(ax, ay, lam, C, offsets, limits):
    """Longest step proven free of any demand reaching its limit (see the module docstring).

    Parameters
    ----------
    ax, ay : ndarray of complex128, shape (n_modes,)
        Modal coordinates of the x and y axes at the step's start (``ay`` zero along a line), the
        modes ordered from the fastest (largest ``|lambda|``) to the slowest.
    lam : ndarray of complex128, shape (n_modes,)
        Eigenvalues, ``Re lambda <= 0`` (units of ``1/T_p``).
    C : ndarray of complex128, shape (n_demands, n_modes)
        Demand ``j`` per unit of mode ``k`` (units of the demand).
    offsets : ndarray of float64, shape (n_demands, 2)
        Constant part of each demand (x, y).
    limits : ndarray of float64, shape (n_demands,) or longer
        Limit of each demand's length.

    Returns
    -------
    float
        Step length (units of ``T_p``): ``inf`` when no demand can ever reach its limit, 0 when
        none can be proven safe.
    """
    n = ax.shape[0]
    h = math.inf
    for j in range(C.shape[0]):
        amp_total = 0.0
        for k in range(n):
            amp_total += abs(C[j, k]) * math.sqrt(abs(ax[k]) ** 2 + abs(ay[k]) ** 2)
        slack = SLACK * (amp_total + math.sqrt(offsets[j, 0] ** 2 + offsets[j, 1] ** 2))
        # split s: modes 0 .. s-1 (the fastest) bounded by their amplitudes, s .. n-1 tracked
        dx = offsets[j, 0]
        dy = offsets[j, 1]
        rate = 0.0
        amp_bounded = amp_total
        best = -math.inf
        for s in range(n, -1, -1):
            if s < n:
                c = C[j, s]
                size = abs(c) * math.sqrt(abs(ax[s]) ** 2 + abs(ay[s]) ** 2)
                dx += (c * ax[s]).real
                dy += (c * ay[s]).real
                rate += size * abs(lam[s])
                amp_bounded -= size
            room = limits[j] - math.sqrt(dx * dx + dy * dy) - max(amp_bounded, 0.0) - slack
            if room < 0.0:
                continue
            hs = math.inf if rate == 0.0 else room / rate
            if hs > best:
                best = hs
        if best <= 0.0:
            return 0.0
        h = min(h, best)
    return SAFETY * h


@njit(cache=True)
def advance(a, lam, V, h, y, o):
    """Propagate one axis's modal coordinates ``a`` by ``h`` (units of ``T_p``) into its states ``y[o:]``.

    ``V`` (shape ``(n_states, n_modes)``) maps the modes back to the axis's states; its rows are
    zero for the states that do not move in this phase (the stuck contents, a held slab), which
    keep their values.  ``a`` is updated in place.
    """
    n = a.shape[0]
    for k in range(n):
        a[k] = a[k] * np.exp(lam[k] * h)
    for i in range(V.shape[0]):
        moving = False
        acc = 0.0
        for k in range(n):
            v = V[i, k]
            if v != 0.0:
                moving = True
                acc += (v * a[k]).real
        if moving:
            y[o + i] = acc


@njit(cache=True)
def exact_step(W, C, V, lam, y, oy, held, base, kd, limits, offsets, a_x, a_y, tau, tau_stop, h_useful, capped):
    """One exact step of the free phase from ``(tau, y)``, where :func:`safe_step` proves a useful one safe.

    Parameters
    ----------
    W, C, V, lam : ndarray of complex128
        The phase's modal data (:func:`isoslide.engine.building.modal_data`; empty: no step).
    y : ndarray of float64
        The state, advanced in place: the x axis's states from 0, the y axis's from ``oy``
        (``oy < 0`` along a line, where ``a_y`` stays zero).
    held : bool
        A bearing holds the slab: its demand has the constant part ``base + kd`` times the slab's
        displacement (``kd`` a pendulum's stiffness, units of ``M_b / T_p^2``; ``base`` the centre
        of a triple pendulum's stick band, units of ``M_b a_p``).
    limits, offsets, a_x, a_y : ndarray
        The demands' limits, scratch space for their constant parts ``(n_demands, 2)`` and for the
        modal coordinates of each axis (at least as long as the modes).
    tau, tau_stop : float
        The step's start and the end of the run (units of ``T_p``).
    h_useful : float
        Shortest step worth taking (a Runge-Kutta step is held to it); with ``capped`` (a history
        recorded) also the longest.

    Returns
    -------
    tuple
        ``(taken, tau)``: whether a step was taken and the time reached (``tau_stop`` at the end).
    """
    nm = W.shape[0]
    if nm == 0 or V.shape[1] != nm:
        return False, tau
    ax = a_x[:nm]
    ay = a_y[:nm]
    modal_coordinates(W, y, 0, ax)
    if oy >= 0:
        modal_coordinates(W, y, oy, ay)
    if held:
        offsets[1, 0] = base + kd * y[0]
        if oy >= 0:
            offsets[1, 1] = base + kd * y[oy]
    hf = min(safe_step(ax, ay, lam, C, offsets, limits), tau_stop - tau)
    if capped:
        hf = min(hf, h_useful)
    if not (hf >= h_useful or tau + hf >= tau_stop):
        return False, tau
    advance(ax, lam, V, hf, y, 0)
    if oy >= 0:
        advance(ay, lam, V, hf, y, oy)
    return True, (tau_stop if tau + hf >= tau_stop else tau + hf)


# numba reads the compiled code shipped with the package (isoslide.jit_cache) before compiling any of it
jit_cache.seed(advance)
