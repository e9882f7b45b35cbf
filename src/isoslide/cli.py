r"""Command line: one scene, in Pi-groups or in physical units.

Examples
--------
::

    isoslide solve --pi2 0.2 --pi3 1 --pi4 0.1
    isoslide solve --pi2 0.2 --pi3 1 --pi4 0.1 --pi5 0.7 --pi6 1000 --json
    isoslide solve-physical --a-p 6 --T-p 1.2 --M-b 8e5 --T-b 2.4 --xi-b 0.1 \
        --m-ec 800 --mu-s 0.25 --mu-k 0.2 --beta 200 --gamma 0.05 --json
"""

from __future__ import annotations

import argparse
import json
import sys

from . import __version__
from .groups import INPUTS
from .pulses import PULSE_NAMES
from .scene import G_STANDARD, Scene
from .solver import DEFAULT_RTOL, solve


def _common(p: argparse.ArgumentParser) -> None:
    p.add_argument("--pulse", default="ricker", choices=PULSE_NAMES, help="pulse shape (default ricker)")
    p.add_argument("--rtol", type=float, default=DEFAULT_RTOL,
                   help=f"target relative error of Pi1 (default {DEFAULT_RTOL:g})")
    p.add_argument("--json", action="store_true", help="print the result as JSON")


def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="isoslide", description=__doc__.split("\n")[0])
    ap.add_argument("--version", action="version", version=f"isoslide {__version__}")
    sub = ap.add_subparsers(dest="command", required=True)
    s = sub.add_parser("solve", help="one scene given by its Pi-groups")
    for g in INPUTS:
        default = "required" if g.default is None else f"default {g.default:g}"
        s.add_argument(f"--{g.name}", type=float, required=g.default is None, default=g.default,
                       help=f"{g.definition}: {g.meaning}; {g.range_text.replace('value', g.name)} ({default})")
    _common(s)
    q = sub.add_parser("solve-physical", help="one scene in SI units")
    for name, unit, default in [("a-p", "m/s^2", None), ("T-p", "s", None), ("M-b", "kg", None),
                                ("T-b", "s, 0 = fixed base", None), ("xi-b", "-", None),
                                ("m-ec", "kg", None), ("mu-s", "-", None), ("mu-k", "-", None),
                                ("beta", "s/m", 0.0), ("gamma", "s/m", 0.0), ("g", "m/s^2", G_STANDARD)]:
        q.add_argument(f"--{name}", type=float, required=default is None, default=default,
                       help=f"{name.replace('-', '_')} [{unit}]")
    _common(q)
    return ap


def main(argv=None) -> int:
    """Run the command line with ``argv`` (default ``sys.argv[1:]``); return the exit code."""
    args = _parser().parse_args(argv)
    try:
        if args.command == "solve":
            scene = Scene(**{g.name: getattr(args, g.name) for g in INPUTS}, pulse=args.pulse)
        else:
            scene = Scene.from_physical(args.a_p, args.T_p, args.M_b, args.T_b, args.xi_b, args.m_ec,
                                        args.mu_s, args.mu_k, args.beta, args.gamma, args.g, args.pulse)
        sol = solve(scene, rtol=args.rtol)
    except ValueError as exc:
        print(f"isoslide: error: {exc}", file=sys.stderr)
        return 2
    out = {"pi1": sol.pi1, "pi1_residual": sol.pi1_residual, "tau_peak": sol.tau_peak,
           "settled": sol.settled, "model": sol.model, "n_steps": sol.n_steps, "n_events": sol.n_events,
           "scene": {**scene.pis(), "pulse": scene.pulse.name}}
    if scene.scale is not None:
        out.update({"u_max_m": sol.u_max, "u_residual_m": sol.u_residual, "t_peak_s": sol.t_peak})
    if args.json:
        print(json.dumps(out, indent=1))
    else:
        for k, v in out.items():
            if k != "scene":
                print(f"{k:>13s}: {v}")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
