"""isoslide: exact stick-slip sliding of contents on seismically isolated floors.

Quick start
-----------
>>> import isoslide
>>> sol = isoslide.solve(isoslide.Scene(pi2=0.2, pi3=1.0, pi4=0.1))
>>> sol.pi1, sol.model, sol.settled                      # doctest: +SKIP

See :class:`isoslide.Scene` for the definition and valid range of every Pi-group.
"""

from importlib.metadata import PackageNotFoundError, version

from .pulses import Pulse, get_pulse
from .scene import G_STANDARD, PhysicalScale, Scene, paper_groups
from .solver import Batch, Solution, solve, solve_many
from . import records  # noqa: E402  (isoslide.records.read_at2, sample, fit_pulse, ...)

try:
    __version__ = version("isoslide")
except PackageNotFoundError:  # pragma: no cover - running from a source tree
    __version__ = "0+unknown"

__all__ = [
    "Batch", "G_STANDARD", "PhysicalScale", "Pulse", "Scene", "Solution",
    "get_pulse", "paper_groups", "solve", "solve_many", "__version__",
]
