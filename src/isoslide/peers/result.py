"""The result every peer solver returns."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..store.history import History
from ..scene import Scene, to_metres

__all__ = ["PeerResult", "WorkLimitError", "counted"]


@dataclass(frozen=True)
class PeerResult:
    """Result of a peer solver (dimensionless, like :class:`isoslide.Solution`).

    Attributes
    ----------
    method : str
        Which peer ran: ``"reference"``, ``"regularized"``, ``"si"`` or ``"opensees"``.
    pi1 : float
        ``u_max / (a_p T_p^2)``: peak ``|u|`` over the response.
    pi1_residual : float
        Final signed sliding displacement (units ``a_p T_p^2``; nan if not recorded).
    tau_peak : float
        Time of the peak, units of ``T_p`` (nan if not recorded).
    settled : bool
        True when the run stopped because no further sliding is possible; False
        when it ran to its end time (a peer without a settlement test always does).
    n_events : int
        Stick/slip transitions (breakaways, stops, reversals); the regularized
        peer counts elastic-to-plastic switches between steps; -1 if not counted.
    tau_end : float
        Time at which the run stopped, units of ``T_p``.
    nfev, njev, n_steps : int
        Right-hand-side evaluations, Jacobian evaluations and time steps
        (accepted steps; fixed steps for OpenSees); -1 where not counted.
    stiffness : float
        Regularising stiffness ``K = k_r T_p^2 / m_EC`` (regularized, opensees), else nan.
    integrator : str
        Time integrator used (``"DOP853"``, ``"Radau"``, ``"BDF"``, ``"Newmark"``).
    history : History or None
        Time history when requested, with the solver's fields
        (``tau, x, xd, u, ud, phase``, dimensionless).
    peak_angle : float
        Direction of the sliding displacement at its peak, ``atan2(u_y, u_x)`` in the building's
        axes (radians; nan when the contents never slid, or for a peer that does not report it).
    """

    method: str
    pi1: float
    pi1_residual: float = math.nan
    tau_peak: float = math.nan
    settled: bool = False
    n_events: int = -1
    tau_end: float = math.nan
    nfev: int = -1
    njev: int = -1
    n_steps: int = -1
    stiffness: float = math.nan
    integrator: str = ""
    history: History | None = field(default=None, repr=False)
    peak_angle: float = math.nan

    @property
    def work(self) -> int:
        """Cost counter: right-hand-side evaluations where counted, else time steps."""
        return self.nfev if self.nfev >= 0 else self.n_steps

    def metres(self, scene: Scene) -> float:
        """``u_max`` in metres for a scene built with :meth:`isoslide.Scene.from_physical`."""
        return to_metres(self.pi1, scene)


class WorkLimitError(RuntimeError):
    """A peer solve needed more right-hand-side evaluations than its ``max_work`` allows."""


def counted(fun, max_work: int | None, what: str, used: list):
    """``fun`` counting its calls in ``used[0]``; raises :class:`WorkLimitError` past ``max_work``.

    A peer bounded this way stops after the same amount of work on every machine and under any
    load, so its outcome (answer or ``WorkLimitError``) does not depend on wall-clock time.
    """
    if max_work is None:
        return fun
    if not (isinstance(max_work, int) and max_work > 0):
        raise ValueError(f"max_work = {max_work!r} is invalid; allowed: a positive integer or None")

    def wrapped(t, y):
        used[0] += 1
        if used[0] > max_work:
            raise WorkLimitError(f"{what}: more than max_work = {max_work} right-hand-side evaluations")
        return fun(t, y)

    return wrapped
