"""The planar OpenSees peer approaching isoslide's answer as its stick stiffness grows.

The planar OpenSees peer (:func:`isoslide.peers.opensees_planar.solve_opensees_planar`) replaces
each true stick of the contents on their floor by the elastic range of a ``flatSliderBearing``
element (circular Coulomb yield surface, elastic stiffness ``K m``) and integrates with a fixed
time step tied to the stick's period; isoslide solves the planar stick-slip problem exactly.
:func:`convergence_table` runs OpenSees on a few planar scenes (:data:`SCENES`: two on a fixed
base, two on a linear isolator with heavy contents) at growing stick stiffness ``K`` and tabulates
the relative error of ``Pi1`` and the error of the peak's direction against a target
(:data:`TARGETS`): isoslide's exact solver, the independent event-driven planar reference peer,
or, as a stand-in where neither is available, OpenSees itself far stiffer and with a finer step.

Both errors fall as ``K`` grows.  With the default Newmark integrator the error has two parts:
the regularisation's, like ``1 / K`` on these scenes, and the time error where the sliding
direction turns, of order ``dt`` (the default step ``~ 1 / sqrt(K)``), so like ``1 / sqrt(K)``;
where they have opposite signs the total can pass near 0 on the way (the table shows the signed
error).  With ``--integrator GeneralizedAlpha`` the time error of order ``dt`` is gone and the error
falls like ``1 / K``.  ``python -m isoslide.studies.opensees_planar_convergence`` prints the table
(``--stiffness`` for other stiffnesses, ``--target`` for another target, ``--integrator``; needs
``pip install -e .[peers]``).  The module imports without ``openseespy``.
"""

from __future__ import annotations

import argparse
import math
import time

from ..peers.opensees import opensees_available
from ..peers.opensees_planar import INTEGRATORS, ground_window, solve_opensees_planar
from ..peers.reference_planar import solve_reference_planar
from ..scene import Scene
from ..solver import solve

__all__ = ["DEFAULT_STIFFNESSES", "SCENES", "STAND_IN", "TARGETS", "angle_error", "convergence_table",
           "format_table", "main", "target_of"]

DEFAULT_STIFFNESSES = (1e3, 1e4, 1e5, 1e6)
"""Stick stiffnesses ``K T_p^2 / m`` of the table (dimensionless)."""

SCENES = {
    "fixed base, Ricker x, antisymmetric Ricker y (Pi14 = 0.8)":
        Scene(pi2=0.2, pi3=0.0, pulse="ricker", pulse_y="antisymmetric_ricker", pi14=0.8),
    "fixed base, two Rickers, y 0.4 T_p later (Pi14 = 0.7)":
        Scene(pi2=0.3, pi3=0.0, pulse="ricker", pulse_y="ricker", pi14=0.7, pi16=0.4),
    "linear base, T_b = 2.5 T_p, xi_b = 0.1, Pi8 = 0.5":
        Scene(pi2=0.2, pi3=2.5, pi4=0.1, pi8=0.5, pulse="ricker", pulse_y="antisymmetric_ricker", pi14=0.8),
    "linear base, T_b = 2 T_p, xi_b = 0.05, Pi8 = 0.2, y longer (Pi15 = 1.5) and later":
        Scene(pi2=0.1, pi3=2.0, pi4=0.05, pi8=0.2, pulse="ricker", pulse_y="ricker", pi14=0.6, pi15=1.5,
              pi16=0.3),
}
"""Planar scenes of the table (the ground's two components not proportional)."""

TARGETS = ("exact", "reference", "opensees", "auto")
"""Comparison targets: ``isoslide.solve`` (exact solver, ``rtol = 1e-9``), the event-driven planar
reference peer (:mod:`isoslide.peers.reference_planar`), the OpenSees stand-in (:data:`STAND_IN`),
and the first of these three that answers the scene (``"auto"``)."""

STAND_IN = {"stiffness": 1e7, "dt": 1e-4, "integrator": "GeneralizedAlpha"}
"""The OpenSees stand-in target: stick stiffness ``1e7``, step ``1e-4 T_p`` (20 steps per stick
period), the generalized-alpha integrator (no time error of order ``dt`` in the plane)."""

EXACT_RTOL = 1e-9
"""``rtol`` of the exact solver as a target."""

UNSUPPORTED = (NotImplementedError, ValueError, TypeError)
"""Exceptions by which a target solver refuses a scene it does not model."""


def angle_error(angle: float, target: float) -> float:
    """``angle - target`` wrapped to ``[-pi, pi)`` (radians; nan if either is nan)."""
    return (angle - target + math.pi) % (2.0 * math.pi) - math.pi


def _exact(scene: Scene) -> tuple:
    s = solve(scene, rtol=EXACT_RTOL)
    angle = getattr(s, "peak_angle", math.nan)
    if s.pi1 > 0.0 and not math.isfinite(angle):
        raise NotImplementedError("the exact solver reports no peak_angle")
    return float(s.pi1), float(angle)


def _reference(scene: Scene) -> tuple:
    r = solve_reference_planar(scene)
    return float(r.pi1), float(r.peak_angle)


def _stand_in(scene: Scene) -> tuple:
    r = solve_opensees_planar(scene, **STAND_IN)
    return float(r.pi1), float(r.peak_angle)


_SOLVERS = {"exact": _exact, "reference": _reference, "opensees": _stand_in}


def target_of(scene: Scene, target: str = "auto") -> tuple:
    """The comparison value: ``(label, Pi1, peak_angle)``.

    Parameters
    ----------
    scene : Scene
    target : {"exact", "reference", "opensees", "auto"}
        See :data:`TARGETS`; ``"auto"`` is labelled with the target it chose.  A named target that
        does not answer the scene raises a ValueError.

    Returns
    -------
    (str, float, float)
        Label, ``Pi1`` (units ``a_p T_p^2``) and ``peak_angle`` (radians, building axes).
    """
    if target not in TARGETS:
        raise ValueError(f"target = {target!r} is invalid; allowed: {', '.join(map(repr, TARGETS))}")
    names = ("exact", "reference", "opensees") if target == "auto" else (target,)
    failures = []
    for name in names:
        try:
            pi1, angle = _SOLVERS[name](scene)
        except UNSUPPORTED as exc:
            failures.append(f"{name}: {type(exc).__name__}: {exc}")
            continue
        return name, pi1, angle
    raise ValueError(f"target = {target!r} does not answer this scene ({'; '.join(failures)})")


def _check_stiffnesses(stiffnesses) -> tuple:
    out = []
    for k in stiffnesses:
        v = float(k)
        if not (math.isfinite(v) and v > 0.0):
            raise ValueError(f"stiffness = {k!r} in stiffnesses is out of range; allowed range: 0 < value < inf")
        out.append(v)
    if not out:
        raise ValueError("stiffnesses = () is empty; allowed: at least one stiffness")
    return tuple(out)


def convergence_table(scenes=None, stiffnesses=DEFAULT_STIFFNESSES, target: str = "auto",
                      integrator: str = "Newmark") -> list:
    """OpenSees' ``Pi1`` and peak direction, and their errors, over stick stiffnesses.

    Parameters
    ----------
    scenes : dict of str to Scene, or sequence of Scene, or None
        Planar scenes the peer models (default :data:`SCENES`); a sequence is named by position.
    stiffnesses : sequence of float
        Stick stiffnesses ``K T_p^2 / m`` (dimensionless, each > 0); every run uses the peer's
        default step and end time.
    target : {"exact", "reference", "opensees", "auto"}
        What the errors are measured against (:func:`target_of`).
    integrator : {"Newmark", "GeneralizedAlpha"}
        The peer's time integrator (:data:`isoslide.peers.opensees_planar.INTEGRATORS`).

    Returns
    -------
    list of dict
        One row per scene and stiffness, scene by scene: ``scene`` (name), ``target`` (label),
        ``target_pi1`` and ``target_angle``; ``stiffness``; ``dt`` (units ``T_p``); ``pi1``
        (units ``a_p T_p^2``); ``rel_error`` ``(pi1 - target_pi1) / target_pi1``, signed (``pi1``
        when the target is 0); ``peak_angle`` and ``angle_error`` ``peak_angle - target_angle``
        (radians, wrapped to ``[-pi, pi)``); ``integrator``; ``n_steps``; ``tau_end`` (units
        ``T_p``); ``seconds`` (wall-clock time of the run).
    """
    scenes = SCENES if scenes is None else scenes
    if not isinstance(scenes, dict):
        scenes = {f"scene {i + 1}": s for i, s in enumerate(scenes)}
    stiffnesses = _check_stiffnesses(stiffnesses)
    rows = []
    for name, scene in scenes.items():
        label, ref, ref_angle = target_of(scene, target)
        tau0 = ground_window(scene)[0]
        for k in stiffnesses:
            t0 = time.perf_counter()
            r = solve_opensees_planar(scene, k, integrator=integrator)
            seconds = time.perf_counter() - t0
            err = (r.pi1 - ref) / ref if ref > 0.0 else r.pi1
            rows.append({"scene": name, "target": label, "target_pi1": ref, "target_angle": ref_angle,
                         "stiffness": k, "dt": (r.tau_end - tau0) / r.n_steps, "pi1": r.pi1,
                         "rel_error": err, "peak_angle": r.peak_angle,
                         "angle_error": angle_error(r.peak_angle, ref_angle), "integrator": integrator, "n_steps": r.n_steps,
                         "tau_end": r.tau_end, "seconds": seconds})
    return rows


def format_table(rows: list) -> str:
    """The table as text: per scene a line naming it and its target, then one line per stiffness."""
    lines = []
    scene = None
    for r in rows:
        if r["scene"] != scene:
            scene = r["scene"]
            if lines:
                lines.append("")
            lines.append(scene)
            lines.append(f"target: {r['target']}, Pi1 = {r['target_pi1']:.10g}, "
                         f"peak angle = {r['target_angle']:.8f} rad; OpenSees with {r['integrator']}")
            lines.append(f"{'stiffness':>9} {'dt':>9} {'Pi1 (OpenSees)':>15} {'rel. error':>11} "
                         f"{'angle error':>12} {'steps':>8} {'time':>8}")
        lines.append(f"{r['stiffness']:9.0e} {r['dt']:9.2e} {r['pi1']:15.10f} {r['rel_error']:+11.2e} "
                     f"{r['angle_error']:+12.2e} {r['n_steps']:8d} {r['seconds']:7.2f}s")
    return "\n".join(lines)


def main(argv=None) -> int:
    """``python -m isoslide.studies.opensees_planar_convergence [--stiffness K ...] [--target T] [--integrator I]``."""
    ap = argparse.ArgumentParser(prog="python -m isoslide.studies.opensees_planar_convergence",
                                 description=__doc__.split("\n")[0])
    ap.add_argument("--stiffness", nargs="+", type=float, default=list(DEFAULT_STIFFNESSES),
                    help="stick stiffnesses K T_p^2 / m (default: %(default)s)")
    ap.add_argument("--target", default="auto", choices=TARGETS)
    ap.add_argument("--integrator", default="Newmark", choices=sorted(INTEGRATORS))
    args = ap.parse_args(argv)
    if not opensees_available():
        ap.error("openseespy does not import: pip install -e .[peers]")
    for name, scene in SCENES.items():
        print(format_table(convergence_table({name: scene}, args.stiffness, args.target, args.integrator)), flush=True)
        print(flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
