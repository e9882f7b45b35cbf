"""What the building peers share: the state's layout and the stick/slip bookkeeping of their interfaces.

:mod:`isoslide.peers.reference_building` (dimensionless) and :mod:`isoslide.peers.si_building`
(SI units) write the equations of motion of a building with a hysteretic isolator, floors and
contents each on its own.  Both store the state in one layout (:class:`StateIndex`) and follow
one rule for the modes of the frictional interfaces at a phase start (:func:`choose_modes`,
:func:`phase_modes`): of the combinations (stuck, +1, -1) of the contents and a sliding bearing,
in the order all stuck; contents stuck & bearing sliding; contents sliding & bearing stuck; both
sliding, the first consistent one is taken (every stuck interface within its limit, every
sliding one accelerating in its own direction).  A bilinear bearing yields and unloads alike in
both (:func:`bearing_event`).

Each function works in the units of its caller: ``a_p``, ``T_p``, ``M_b a_p`` for the reference,
m, s, N for the SI peer.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["X", "XD", "XS", "StateIndex", "bearing_event", "candidates", "choose_modes", "farther", "phase_modes",
           "sign"]

X, XD, XS = 0, 1, 2
"""Indices of the slab's displacement and velocity and of the first floor's displacement in the
state; the other indices depend on the number of floors (:class:`StateIndex`)."""


def sign(a: float) -> int:
    """The sign of ``a`` as an int: 1, -1, or 0 for zero."""
    return 1 if a > 0.0 else (-1 if a < 0.0 else 0)


class StateIndex:
    """Indices into the state of a building peer: slab, floors, contents, isolator force.

    The state holds the slab's displacement and velocity relative to the ground (``X``, ``XD``),
    the floors' displacements relative to the slab (from ``XS``), then their velocities (from
    :attr:`XSD`), the contents' sliding displacement and velocity (:attr:`U`, :attr:`UD`) and the
    hysteretic isolator force (:attr:`FH`); a rigid superstructure keeps one unused floor slot.
    A model using it has the floor masses ``ms`` (an array, empty when rigid) and the isolator
    ``kind`` (``"linear"``, ``"bilinear"``, ``"sliding"`` or ``"fixed"``).
    """

    ms: np.ndarray
    kind: str

    @property
    def n(self) -> int:
        """Number of floors ``N`` above the slab (0 when rigid)."""
        return int(self.ms.size)

    @property
    def slots(self) -> int:
        """Floor slots in the state (``N``, or one unused slot when rigid)."""
        return max(1, self.n)

    @property
    def XSD(self) -> int:   # noqa: N802 - a state index, named like X, XD, XS
        """Index of the first floor's velocity in the state."""
        return XS + self.slots

    @property
    def U(self) -> int:     # noqa: N802
        """Index of the contents' sliding displacement in the state."""
        return XS + 2 * self.slots

    @property
    def UD(self) -> int:    # noqa: N802
        """Index of the contents' sliding velocity in the state."""
        return self.U + 1

    @property
    def FH(self) -> int:    # noqa: N802
        """Index of the hysteretic isolator force in the state."""
        return self.U + 2

    @property
    def holds(self) -> bool:
        """True when the isolator can hold the slab still (sliding bearing or fixed base)."""
        return self.kind in ("sliding", "fixed")


def candidates(broke: int, mode: int, v: float) -> tuple:
    """The modes to try for one frictional interface at a phase start.

    Parameters
    ----------
    broke : int
        Nonzero: the interface just broke away and slides in this direction.
    mode : int
        Its mode before the phase start (0 stuck, +1 or -1 sliding).
    v : float
        Its relative velocity (units of the caller).

    Returns
    -------
    modes : tuple of int
        ``(broke,)``; ``(0, 1, -1)`` at rest (stuck, or sliding with zero velocity); else the
        sign of ``v``.
    free : bool
        True when the interface is at rest and its mode is to be chosen.
    """
    if broke:
        return (broke,), False
    if mode == 0 or v == 0.0:
        return (0, 1, -1), True
    return (sign(v),), False


def choose_modes(B: StateIndex, y, sb: int, si: int, broke_b: int, broke_i: int, lim_b: float, lim_q: float,
                 motion) -> tuple | None:
    """The first consistent modes ``(sb, si)`` of the contents and a sliding bearing (module docstring).

    Parameters
    ----------
    B : StateIndex
        The model.
    y : ndarray
        The state.
    sb, si : int
        Modes of the contents and the isolator before the phase start; an isolator other than a
        sliding bearing keeps ``si``.
    broke_b, broke_i : int
        Nonzero: the contents (the bearing) just broke away and slide in this direction.
    lim_b, lim_q : float
        Stick limits of the contents (acceleration of their floor) and of the bearing (force it
        must supply), with their slack.
    motion : callable
        ``motion(sb, si)``: the accelerations of the model in those modes, a tuple starting
        ``(x_b'', ., u'', ., a_F, f_need)`` (slab, contents' sliding, contents' floor, force the
        held bearing must supply).

    Returns
    -------
    tuple of int or None
        The modes, or None when no combination is consistent.
    """
    sliding = B.kind == "sliding"
    cand_b, free_b = candidates(broke_b, sb, y[B.UD])
    cand_i, free_i = candidates(broke_i, si, y[XD]) if sliding else ((si,), False)
    order = sorted(((b, i) for b in cand_b for i in cand_i), key=lambda c: (c[0] != 0, sliding and c[1] != 0))
    for b, i in order:
        xdd, _, udd, _, a_f, f_need = motion(b, i)[:6]
        if b == 0 and abs(a_f) > lim_b:
            continue
        if b != 0 and free_b and not b * udd > 0.0:
            continue
        if sliding:
            if i == 0 and abs(f_need) > lim_q:
                continue
            if i != 0 and free_i and not i * xdd > 0.0:
                continue
        return b, i
    return None


def phase_modes(B: StateIndex, y, sb: int, si: int, q: float, after_event: bool, yield_mode, choose) -> tuple:
    """The modes at a phase start, the state's resting velocities set to zero.

    A bilinear bearing first settles whether it yields (unless an event just set it; a bearing
    that starts to yield has its force set to ``+-q``), then the frictional interfaces choose
    their modes.

    Parameters
    ----------
    B : StateIndex
        The model.
    y : ndarray
        The state, changed in place: the isolator force, and the velocities of the interfaces
        that stick.
    sb, si : int
        Modes of the contents and the isolator before the phase start.
    q : float
        Strength of the isolator (units of the caller).
    after_event : bool
        The phase starts at a located event, which has counted its own transition.
    yield_mode : callable
        ``yield_mode(si)``: 0 (elastic) or +-1 (yielding) for a bilinear bearing.
    choose : callable
        ``choose(si)``: the modes ``(sb, si)`` of the frictional interfaces.

    Returns
    -------
    sb, si : int
        The modes of the phase.
    changes : int
        The mode changes to count as transitions.
    """
    changes = 0
    if B.kind == "bilinear" and not after_event:
        new = yield_mode(si)
        if new != si:
            changes += 1
            si = new
            if si:
                y[B.FH] = si * q
    nb, ni = choose(si)
    if not after_event:
        changes += (nb != sb) + (B.kind == "sliding" and ni != si)
    if nb == 0:
        y[B.UD] = 0.0
    if B.holds and ni == 0:
        y[XD] = 0.0
    return nb, ni, changes


def bearing_event(kind: str, y, fh: int, q: float) -> int:
    """The bilinear bearing's mode after its ``"yield"`` or ``"unload"`` event, its force set in ``y``.

    Parameters
    ----------
    kind : {"yield", "unload"}
        ``yield``: the force reached ``+-q``, the bearing yields in its direction; ``unload``: the
        slab turned, the bearing is elastic again from ``+-q``.
    y : ndarray
        The state, changed in place at ``fh``.
    fh : int
        Index of the isolator force in ``y``.
    q : float
        Strength of the bearing (units of the caller).

    Returns
    -------
    int
        +-1 yielding, 0 elastic.
    """
    if kind == "yield":
        si = sign(y[fh])
        y[fh] = si * q
        return si
    y[fh] = math.copysign(q, y[fh])
    return 0


def farther(peak: float, t_peak: float, u: float, t: float) -> tuple:
    """The peak slide and its time after the slide ``u`` at ``t``: ``(|u|, t)`` when farther, else as was."""
    return (abs(u), t) if abs(u) > peak else (peak, t_peak)
