"""Mode resolution at events: which frictional interfaces at rest stick and which slide.

A frictional interface (the contents on their floor, a sliding bearing under the slab) is stuck
(mode 0) or slides (+1 or -1 along its line).  When an interface comes to rest, or a stuck one
reaches its limit, the force on every other interface at rest can jump, so the modes of all
*free* interfaces (those at zero relative velocity) are chosen together: the candidates of
:func:`candidates` are tried in order and the first *consistent* one is taken, where consistent
means every stuck interface's needed force is within its limit and every sliding one accelerates
in its own direction (the check is the kernel's, which knows the forces).

Order and uniqueness
--------------------
Candidates come with the fewest sliding interfaces first, and among equals in the order stuck,
+1, -1 for each interface, the first interface varying slowest.  Sticking is preferred because
stick is the state a frictional contact keeps as long as it can: with one free interface at
most one of (stuck, +1, -1) is consistent (a stuck interface within its limit accelerates neither
way; past it, only the direction of the excess is consistent).  With two free interfaces coupled
through the building more than one combination can be consistent near a limit; the order then
makes the answer deterministic, and it is the rule the independent peers
(:mod:`isoslide.peers.reference_building`, :mod:`isoslide.peers.si_building`) follow, which the
tests hold the kernel to.  If none is consistent (round-off exactly at a limit) the kernel lets each free
interface slide in the direction its stuck demand pushes it.

Interfaces of dimension 2 (contents sliding in a plane, a friction pendulum in the plane) have a
continuum of sliding directions; their joint decision is a cone complementarity problem and is
not an enumeration of this module.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .. import jit_cache

SIGNS = (0.0, 1.0, -1.0)
"""Modes of a one-dimensional interface in candidate order: stuck, sliding +, sliding -."""


@njit(cache=True)
def candidates(free, current):
    """Joint modes to try, in order, for interfaces of which ``free[j]`` are at rest.

    Parameters
    ----------
    free : ndarray of bool, shape (k,)
        Whether interface ``j`` is free (at zero relative velocity, its mode to be chosen).
    current : ndarray of float, shape (k,)
        The modes of the interfaces; a non-free interface keeps its own.

    Returns
    -------
    ndarray of float, shape (m, k)
        Every combination of stuck, +1, -1 over the free interfaces (the others at their current
        mode), the fewest sliding first, then in the order stuck, +1, -1 with the first interface
        varying slowest.
    """
    k = free.shape[0]
    total = 3 ** k
    rows = np.empty((total, k))
    slides = np.empty(total, dtype=np.int64)
    m = 0
    for idx in range(total):
        rem = idx
        ok = True
        n = 0
        for j in range(k - 1, -1, -1):
            digit = rem % 3
            rem //= 3
            if not free[j]:
                # a non-free interface keeps its mode (whatever its code: a rocking block's too), once
                if digit != 0:
                    ok = False
                    break
                value = current[j]
            else:
                value = SIGNS[digit]
                if value != 0.0:
                    n += 1
            rows[m, j] = value
        if ok:
            slides[m] = n
            m += 1
    order = np.argsort(slides[:m], kind="mergesort")     # stable: keeps the lexicographic order
    return rows[:m][order]


jit_cache.seed(candidates)
