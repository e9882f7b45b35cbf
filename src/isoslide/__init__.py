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

import importlib.abc
import importlib.util
import sys
import warnings
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
    "friction_pendulum": "scene", "triple_friction_pendulum": "scene",
    "Pulse": "pulses", "get_pulse": "pulses",
}
_SUBMODULES = ("records", "peers", "groups", "config", "models")

__all__ = sorted(_EXPORTS) + ["__version__"]

MOVED = {
    "kernel": "engine.kernel",
    "building_kernel": "engine.building_kernel",
    "piecewise": "engine.piecewise",
    "dop853": "engine.dop853",
    "building": "engine.building",
    "validation": "model.validation",
    "history": "store.history",
    "history_io": "store.history_io",
    "progress": "store.progress",
    "provenance": "store.provenance",
    "figures": "reports.figures",
    "fragility_plot": "reports.fragility_plot",
    "isolation_plot": "reports.isolation_plot",
    "quicklook": "reports.quicklook",
    "index_page": "reports.index_page",
    "studies.storeys_plot": "reports.storeys_plot",
    "sweep": "studies.sweep",
    "similarity": "studies.similarity",
    "claims": "studies.claims",
    "isolation_study": "studies.isolation_study",
    "record_study": "studies.record_study",
    "fragility_study": "studies.fragility_study",
    "fragility": "studies.fragility",
    "design": "studies.design",
    "intensity": "studies.intensity",
    "pelicun_export": "studies.pelicun_export",
    "opensees_convergence": "studies.opensees_convergence",
}
"""Modules that moved into subpackages: ``isoslide.<old>`` still imports ``isoslide.<new>``.

The package's layout is model, engine, store, studies, reports (see the documentation's
architecture page); code written against the earlier flat layout keeps working, with a
:class:`DeprecationWarning` naming the new place.
"""


class _MovedModules(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Imports ``isoslide.<old>`` of :data:`MOVED` as the module at its new place."""

    def find_spec(self, fullname, path=None, target=None):
        name = fullname.removeprefix(f"{__name__}.")
        if fullname.startswith(f"{__name__}.") and name in MOVED:
            return importlib.util.spec_from_loader(fullname, self)
        return None

    def create_module(self, spec):
        new = f"{__name__}.{MOVED[spec.name.removeprefix(f'{__name__}.')]}"
        warnings.warn(f"{spec.name} moved to {new}; import it from there", DeprecationWarning, stacklevel=2)
        return import_module(new)

    def exec_module(self, module):
        pass


if not any(isinstance(f, _MovedModules) for f in sys.meta_path):
    sys.meta_path.append(_MovedModules())


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
