"""The OpenSees peer approaching isoslide's answer as its time step and stick displacement shrink.

OpenSees (:func:`isoslide.peers.solve_opensees`) replaces each true stick by an elastic-plastic
spring of small yield displacement (the *stick displacement*) and integrates with a fixed Newmark
step; isoslide solves the stick-slip problem exactly.  :func:`opensees_convergence` runs OpenSees at
a sequence of ``(dtau, stick displacement)`` pairs and tabulates ``Pi1`` and its relative error
against a target: isoslide's exact solver, its event-driven reference peer, a given value, a
finer OpenSees run, or the first of these that models the scene's building (``"auto"``, the
default: for a building of several storeys a solver that reads only one storey is passed over).
Where the contents reverse without stopping, the regularised spring needs twice the stick
displacement to swap its force, and the error falls only as the square root of the stick
displacement (measured on the lead-rubber roofs of :data:`STOREY_SCENES`: about ``1e-3`` at
``1e-8``).  ``python -m isoslide.studies.opensees_convergence`` prints the table for a friction pendulum (``--scene``
for others, ``--suite storeys`` for the buildings of :data:`STOREY_SCENES`; needs
``pip install -e .[peers]``).
"""

from __future__ import annotations

import argparse
import dataclasses
import itertools
import math
from dataclasses import dataclass

from ..peers import opensees_available, solve_opensees
from ..scene import Scene
from ..solver import solve

__all__ = ["Convergence", "ConvergenceRow", "DEFAULT_PAIRS", "STOREY_SCENES", "TARGETS", "format_table",
           "main", "modelled_pi1", "opensees_convergence", "target_pi1"]

DEFAULT_PAIRS = ((1e-2, 1e-4), (3e-3, 1e-5), (1e-3, 1e-6), (3e-4, 1e-7), (1e-4, 1e-8))
"""``(dtau, stick displacement)`` pairs, both shrinking (units ``T_p`` and ``a_p T_p^2``)."""

TARGETS = ("exact", "reference", "opensees", "auto")
"""Named comparison targets: ``isoslide.solve`` (exact stick-slip solver, ``rtol = 1e-9``), its
event-driven SciPy reference peer (``method="reference"``), OpenSees at the finest pair's step
and stick displacement each divided by :data:`FINER`, and the first of these three that models
the scene's building (see :func:`modelled_pi1`)."""

FINER = 10.0
"""Refinement of the ``"opensees"`` target over the finest pair."""

DEFAULT_HORIZON = 10.0
"""Time after the pulse both solvers run to (units ``T_p``)."""


@dataclass(frozen=True)
class ConvergenceRow:
    """One OpenSees run of the table.

    Attributes
    ----------
    dtau : float
        Newmark time step, units ``T_p``.
    stick_displacement : float
        Yield displacement of the block's and a sliding bearing's spring, units ``a_p T_p^2``.
    pi1 : float
        OpenSees' peak sliding ``u_max / (a_p T_p^2)``.
    rel_error : float
        ``|pi1 - target| / target`` (absolute ``|pi1|`` when the target is 0).
    n_steps : int
        Newmark steps run.
    """

    dtau: float
    stick_displacement: float
    pi1: float
    rel_error: float
    n_steps: int


@dataclass(frozen=True)
class Convergence:
    """The convergence table of one scene.

    Attributes
    ----------
    scene : Scene
    target : str
        What the errors are measured against (one of :data:`TARGETS`, or ``"given"``).
    target_pi1 : float
        Its ``Pi1``.
    tau_max : float
        End time of every run, units ``T_p``.
    rows : tuple of ConvergenceRow
        In the order of the pairs.
    """

    scene: Scene
    target: str
    target_pi1: float
    tau_max: float
    rows: tuple


def _check_pairs(pairs) -> tuple:
    out = []
    for pair in pairs:
        dtau, stick = (float(v) for v in pair)
        for name, v in (("dtau", dtau), ("stick_displacement", stick)):
            if not (math.isfinite(v) and v > 0.0):
                raise ValueError(f"{name} = {v!r} in pairs is out of range; allowed range: 0 < value < inf")
        out.append((dtau, stick))
    if not out:
        raise ValueError("pairs = () is empty; allowed: at least one (dtau, stick_displacement) pair")
    return tuple(out)


def _solver_pi1(target: str, scene: Scene, tau_max: float) -> float:
    """``Pi1`` of isoslide's exact solver (``"exact"``) or its reference peer (``"reference"``)."""
    if target == "exact":
        return solve(scene, rtol=1e-9, horizon=tau_max - scene.pulse.tau_end).pi1
    return solve(scene, method="reference", tau_max=tau_max).pi1


def _one_storey(scene: Scene) -> Scene:
    """The scene as a solver reading one storey only sees it.

    A single-storey superstructure of the same ``Pi11, Pi12, Pi13``; the contents on its top floor
    if they are on the top floor, else on the slab.
    """
    return dataclasses.replace(scene, storeys=1, floor_masses=None, storey_stiffnesses=None,
                               floor="roof" if scene.floor_index == scene.storeys else "base")


UNSUPPORTED = (NotImplementedError, ValueError, TypeError)
"""Exceptions by which a solver refuses a building it does not model."""


def modelled_pi1(target: str, scene: Scene, tau_max: float) -> float | None:
    """``Pi1`` by isoslide's ``"exact"`` solver or ``"reference"`` peer; None if it does not model the building.

    A solver models a flexible building of ``storeys > 1`` when it accepts it and its ``Pi1``
    differs from its ``Pi1`` of the single-storey building of the same ``Pi11, Pi12, Pi13`` (a
    solver that reads one storey only gives exactly the same value).  Other scenes are always
    modelled.

    Parameters
    ----------
    target : {"exact", "reference"}
    scene : Scene
    tau_max : float
        End time, units ``T_p``.

    Returns
    -------
    float or None
    """
    if target not in ("exact", "reference"):
        raise ValueError(f"target = {target!r} is invalid here; allowed: 'exact', 'reference'")
    if not (scene.flexible and scene.storeys > 1):
        return _solver_pi1(target, scene, tau_max)
    try:
        value = _solver_pi1(target, scene, tau_max)
        single = _solver_pi1(target, _one_storey(scene), tau_max)
    except UNSUPPORTED:
        return None
    return None if value == single else value


def target_pi1(scene: Scene, target, tau_max: float, pairs=DEFAULT_PAIRS) -> tuple:
    """The comparison value: ``(label, Pi1)``.

    Parameters
    ----------
    scene : Scene
    target : {"exact", "reference", "opensees", "auto"} or float
        See :data:`TARGETS`; a number is taken as the target ``Pi1`` itself (label ``"given"``).
        ``"auto"`` is labelled with the target it chose.  ``"exact"`` and ``"reference"`` raise a
        ValueError for a building the solver does not model (:func:`modelled_pi1`).
    tau_max : float
        End time, units ``T_p`` (the exact solver's horizon is ``tau_max - pulse.tau_end``).
    pairs : sequence of (float, float)
        The table's pairs (the ``"opensees"`` target refines the finest of them).

    Returns
    -------
    (str, float)
    """
    if not isinstance(target, str):
        value = float(target)
        if not (math.isfinite(value) and value >= 0.0):
            raise ValueError(f"target = {target!r} is out of range; allowed: {', '.join(TARGETS)} or 0 <= value < inf")
        return "given", value
    if target in ("exact", "reference"):
        value = modelled_pi1(target, scene, tau_max)
        if value is None:
            raise ValueError(f"target = {target!r} does not model this building (storeys = {scene.storeys}, "
                             f"floor = {scene.floor!r}); allowed here: 'opensees', 'auto' or a number")
        return target, value
    if target == "opensees":
        pairs = _check_pairs(pairs)
        dtau = min(p[0] for p in pairs) / FINER
        stick = min(p[1] for p in pairs) / FINER
        return target, solve_opensees(scene, tau_max=tau_max, dtau=dtau, stick_displacement=stick).pi1
    if target == "auto":
        for name in ("exact", "reference"):
            value = modelled_pi1(name, scene, tau_max)
            if value is not None:
                return name, value
        return target_pi1(scene, "opensees", tau_max, pairs)
    raise ValueError(f"target = {target!r} is invalid; allowed: {', '.join(map(repr, TARGETS))} or a number")


def opensees_convergence(scene: Scene, pairs=DEFAULT_PAIRS, target="auto",
                         horizon: float = DEFAULT_HORIZON) -> Convergence:
    """OpenSees' ``Pi1`` and relative error over ``(dtau, stick displacement)`` pairs.

    Parameters
    ----------
    scene : Scene
        A scene with rate-independent friction (any isolator, superstructure, storeys and floor).
    pairs : sequence of (float, float)
        ``(dtau, stick_displacement)``, units ``T_p`` and ``a_p T_p^2``, each > 0.
    target : {"exact", "reference", "opensees", "auto"} or float
        What the errors are measured against (:func:`target_pi1`).
    horizon : float
        Time after the pulse every run goes to, units ``T_p``, > 0.

    Returns
    -------
    Convergence
    """
    pairs = _check_pairs(pairs)
    if not (math.isfinite(float(horizon)) and horizon > 0.0):
        raise ValueError(f"horizon = {horizon!r} is out of range; allowed range: 0 < value < inf")
    tau_max = float(scene.pulse.tau_end) + float(horizon)
    label, ref = target_pi1(scene, target, tau_max, pairs)
    rows = []
    for dtau, stick in pairs:
        r = solve_opensees(scene, tau_max=tau_max, dtau=dtau, stick_displacement=stick)
        err = abs(r.pi1 - ref) / ref if ref > 0.0 else abs(r.pi1)
        rows.append(ConvergenceRow(dtau=dtau, stick_displacement=stick, pi1=r.pi1, rel_error=err,
                                   n_steps=r.n_steps))
    return Convergence(scene=scene, target=label, target_pi1=ref, tau_max=tau_max, rows=tuple(rows))


def format_table(conv: Convergence) -> str:
    """The table as text: one line per pair, after a line naming the target."""
    lines = [f"target: {conv.target}, Pi1 = {conv.target_pi1:.10g} (runs to tau = {conv.tau_max:g})",
             f"{'dtau':>9} {'stick disp.':>12} {'Pi1 (OpenSees)':>15} {'rel. error':>11} {'steps':>8}"]
    for r in conv.rows:
        lines.append(f"{r.dtau:9.1e} {r.stick_displacement:12.1e} {r.pi1:15.8f} {r.rel_error:11.2e} {r.n_steps:8d}")
    return "\n".join(lines)


EXAMPLE = {"pi2": 0.2, "pi3": 2.0, "pi9": 0.05}
"""Friction pendulum of the command line's default scene (``T_b = 2 T_p``, ``mu = 0.05 a_p/g``)."""

_FP = {"pi2": 0.2, "pi3": 2.0, "pi9": 0.05}
_LRB = {"pi2": 0.2, "pi3": 2.0, "pi4": 0.05, "pi9": 0.05, "pi10": 0.005}
_FRAME = {"pi11": 0.5, "pi12": 0.3, "pi13": 0.02}
STOREY_SCENES = {
    "2 storeys, friction pendulum, floor 1": Scene(**_FP, **_FRAME, storeys=2, floor=1),
    "2 storeys, lead-rubber, roof": Scene(**_LRB, **_FRAME, storeys=2, floor="roof"),
    "5 storeys, friction pendulum, floor 3": Scene(**_FP, **_FRAME, storeys=5, floor=3),
    "5 storeys, lead-rubber, roof": Scene(**_LRB, **_FRAME, storeys=5, floor="roof"),
    "5 storeys tapered, friction pendulum, roof": Scene(**_FP, **_FRAME, storeys=5, floor="roof",
                                                       floor_masses=(1.2, 1.1, 1.0, 0.9, 0.8),
                                                       storey_stiffnesses=(1.6, 1.4, 1.2, 1.0, 0.8)),
    "8 storeys, friction pendulum, floor 4": Scene(**_FP, **_FRAME, storeys=8, floor=4),
    "8 storeys, lead-rubber, roof": Scene(**_LRB, **_FRAME, storeys=8, floor="roof"),
}
"""Buildings of several storeys for ``--suite storeys``: a friction pendulum (``T_b = 2 T_p``,
``mu = 0.05 a_p/g``) and a lead-rubber bearing (``Pi10 = 0.005``) under a superstructure of half
the isolated mass with ``T_s = 0.3 T_p`` and 2 % damping in every mode; contents on a middle floor
or the roof; one building with floor masses and storey stiffnesses decreasing upwards."""

SUITES = {"storeys": STOREY_SCENES}
"""Named sets of scenes the command line can tabulate."""


def _field(key: str, value: str):
    """A ``Scene`` field from the command line's ``KEY=VALUE``."""
    if key == "floor":
        return int(value) if value.lstrip("-").isdigit() else value
    if key == "storeys":
        return int(value) if value.lstrip("-").isdigit() else float(value)
    if key in ("floor_masses", "storey_stiffnesses"):
        return tuple(float(v) for v in value.split(","))
    return float(value)


def main(argv=None) -> int:
    """``python -m isoslide.studies.opensees_convergence [--scene k=v ... | --suite storeys] [--target T] [--grid]``."""
    ap = argparse.ArgumentParser(prog="python -m isoslide.studies.opensees_convergence", description=__doc__.split("\n")[0])
    ap.add_argument("--scene", nargs="*", default=[], metavar="KEY=VALUE",
                    help="Scene fields (pi2=0.2 pi9=0.05 storeys=5 floor=3 floor_masses=1,1,1,1,2 ...); "
                    "default " + " ".join(f"{k}={v}" for k, v in EXAMPLE.items()))
    ap.add_argument("--suite", choices=sorted(SUITES), help="tabulate every scene of a named set instead")
    ap.add_argument("--target", default="auto", help=f"one of {', '.join(TARGETS)} or a number")
    ap.add_argument("--grid", action="store_true",
                    help="every step with every stick displacement of the default pairs")
    ap.add_argument("--horizon", type=float, default=DEFAULT_HORIZON)
    args = ap.parse_args(argv)
    if not opensees_available():
        ap.error("openseespy does not import: pip install -e .[peers]")
    fields = dict(EXAMPLE) if not args.scene else {}
    for kv in args.scene:
        k, _, v = kv.partition("=")
        fields[k] = _field(k, v)
    target = args.target if args.target in TARGETS else float(args.target)
    pairs = DEFAULT_PAIRS
    if args.grid:
        pairs = tuple(itertools.product(sorted({p[0] for p in pairs}, reverse=True),
                                        sorted({p[1] for p in pairs}, reverse=True)))
    scenes = SUITES[args.suite] if args.suite else {"": Scene(**fields)}
    for name, scene in scenes.items():
        if name:
            print(f"\n{name}")
        print(scene)
        print(format_table(opensees_convergence(scene, pairs, target, args.horizon)), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
