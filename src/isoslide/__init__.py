"""isoslide: exact stick-slip sliding of contents on seismically isolated floors.

Quick start
-----------
>>> import isoslide
>>> sol = isoslide.solve(isoslide.Scene(pi2=0.2, pi3=1.0, pi4=0.1))
>>> sol.pi1, sol.model, sol.settled                      # doctest: +SKIP

See :mod:`isoslide.groups` for the definition and valid range of every Pi-group.
The names below are loaded on first use, so ``import isoslide`` stays light and a
pipeline job imports only the modules it needs.
"""

from importlib import import_module
from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("isoslide")
except PackageNotFoundError:  # pragma: no cover - running from a source tree
    __version__ = "0+unknown"

_EXPORTS = {
    "Batch": "solver", "Solution": "solver", "StepBudgetError": "solver", "solve": "solver",
    "solve_many": "solver",
    "G_STANDARD": "scene", "PhysicalScale": "scene", "Scene": "scene", "paper_groups": "scene",
    "friction_pendulum": "scene",
    "Pulse": "pulses", "get_pulse": "pulses",
}
_SUBMODULES = ("records", "peers", "groups", "config", "models")

__all__ = sorted(_EXPORTS) + ["__version__"]


def __getattr__(name):
    if name in _EXPORTS:
        value = getattr(import_module(f".{_EXPORTS[name]}", __name__), name)
    elif name in _SUBMODULES:
        value = import_module(f".{name}", __name__)
    else:
        raise AttributeError(f"module 'isoslide' has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__) | set(_SUBMODULES))
