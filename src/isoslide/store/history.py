"""The time history of a response, shared by the solver and its peers."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["History", "phase_of"]


@dataclass(frozen=True)
class History:
    """Time history of a solve (dimensionless unless a scale is given).

    Attributes
    ----------
    tau : ndarray
        Time ``t / T_p``.
    x, xd : ndarray
        Base displacement relative to the ground (``a_p T_p^2``) and velocity (``a_p T_p``).
    u, ud : ndarray
        Sliding displacement relative to the floor (``a_p T_p^2``) and velocity (``a_p T_p``).
    phase : ndarray of int8
        0 while stuck, +1 / -1 while sliding in the positive / negative direction; a block that can
        rock adds 4 times the corner it rocks on (+4 / -4 rocking, the others slide-rock;
        :func:`isoslide.engine.building_kernel.corner`).
    xs, xsd : ndarray or None
        Superstructure displacement relative to the slab (``a_p T_p^2``) and velocity
        (``a_p T_p``); ``None`` for the paper's model (rigid superstructure).  One column per
        floor, bottom to top (shape ``(rows, storeys)``), for more than one storey.
    fh : ndarray or None
        Hysteretic isolator force over ``M_b a_p`` (bilinear bearing: its elastic-plastic
        part; sliding bearing: the friction force, or the force holding it while stuck);
        ``None`` for a linear isolator.
    iso_phase : ndarray of int8 or None
        Isolator mode: 0 stuck (sliding bearing) or elastic (bilinear bearing), +1 / -1
        sliding or yielding in the positive / negative direction; ``None`` for a linear isolator.
    stage : ndarray of int8 or None
        A triple friction pendulum's regime (0 held, 1..5 Fenz and Constantinou's I..V, -1 another
        set of sliding surfaces; :func:`isoslide.engine.building_kernel.tfp_stage`); ``None`` for
        any other isolator.
    theta, thetad : ndarray or None
        A rocking block's tilt (rad; positive on the corner at ``+b``) and its rate (rad per ``T_p``);
        ``None`` for contents that only slide.
    """

    tau: np.ndarray
    x: np.ndarray
    xd: np.ndarray
    u: np.ndarray
    ud: np.ndarray
    phase: np.ndarray
    xs: np.ndarray | None = None
    xsd: np.ndarray | None = None
    fh: np.ndarray | None = None
    iso_phase: np.ndarray | None = None
    stage: np.ndarray | None = None
    theta: np.ndarray | None = None
    thetad: np.ndarray | None = None


def phase_of(sliding, ud) -> np.ndarray:
    """The ``phase`` array: the sign of the sliding velocity ``ud`` where ``sliding``, else 0.

    Parameters
    ----------
    sliding : array_like of bool
        True where the block slides.
    ud : array_like of float
        Sliding velocity (any unit).

    Returns
    -------
    ndarray of int8
    """
    return np.where(np.asarray(sliding, dtype=bool), np.sign(ud), 0.0).astype(np.int8)
