r"""Command line: one scene in Pi-groups or physical units, real records and their fitted pulses.

Examples
--------
::

    isoslide solve --pi2 0.2 --pi3 1 --pi4 0.1
    isoslide solve --pi2 0.2 --pi3 1 --pi4 0.1 --pi5 0.7 --pi6 1000 --json
    isoslide solve-physical --a-p 6 --T-p 1.2 --M-b 8e5 --T-b 2.4 --xi-b 0.1 \
        --m-ec 800 --mu-s 0.25 --mu-k 0.2 --beta 200 --gamma 0.05 --json
    isoslide solve-physical --record TAK-090 --M-b 8e5 --T-b 2.4 --xi-b 0.1 \
        --m-ec 800 --mu-s 0.25 --mu-k 0.2 --history kobe.h5 --plot kobe.png
    isoslide solve --pi2 0.2 --pi3 1 --pi4 0.1 --pulse-y antisymmetric_ricker --pi14 0.7 --angle 0.5
    isoslide solve --pi2 0.2 --pi3 2 --pi4 0.1 --record pair_x.AT2 --record-y pair_y.AT2
    isoslide fit Kobe_1995_TAK-090 --shape mp --plot fit.png
    isoslide records
    isoslide records fema-p695-near-field-pulse

A record (``--record``, ``fit``) is a PEER ``.AT2`` file, a two-column
``.csv`` file (time in s, acceleration in g) or the name of a bundled sample
(``isoslide records pyslammer``).  It runs as recorded (its own sign and time axis);
its fitted Ricker pulse supplies the scales ``a_p`` and ``T_p`` that are not
given.  ``--record-y`` adds the pair's second horizontal component, run as
recorded on the same time axis with the first one's scales.

A second horizontal component (``--pulse-y`` or ``--record-y``) not along the
first one's line makes the contents slide in the plane: ``pi1`` is then the
peak of ``|u|`` and ``peak_angle`` its direction in the building's axes
(``--angle`` turns the excitation's axes against the building's); ``--history``
then writes every motion along both axes (``slide_disp_x``, ``slide_disp_y``, ...)
and ``--plot`` adds the contents' path on their floor.

Bad input prints one line naming the parameter and its value, and
exits with code 2.
"""

from __future__ import annotations

import argparse
import json
import math
import sys

from . import __version__
from .groups import INPUTS, ROCKING, TFP_SPEED
from .store.history_io import FORMATS, history_format, history_table, write_history
from .pulses import PULSE_NAMES
from .reports.quicklook import check_plot_path, plot_fit, plot_history
from .records import SUITES, load_record, suite
from .scene import FLOORS, G_STANDARD, Scene, friction_pendulum, triple_friction_pendulum
from .solver import DEFAULT_RTOL, solve

EXIT_USAGE = 2
"""Exit code for bad input (as argparse uses)."""
_Y_GROUPS = ("pi14", "pi15", "pi16")
"""Groups of the second horizontal component (read only with one)."""
_Y_DEFAULTS = {**{g.name: g.default for g in INPUTS if g.name in _Y_GROUPS}, "t_y": 0.0}
"""Values of the second component's options that mean 'not given'."""


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors: ``isoslide: error: <message>``, exit code 2."""

    def error(self, message):  # noqa: D102 (argparse API)
        self.exit(EXIT_USAGE, f"isoslide: error: {message}\n")


def _floor(text: str):
    """``--floor``: a named floor or a floor's number (checked against ``--storeys`` by the scene)."""
    return int(text) if text.strip().lstrip("+-").isdigit() else text


def _common(p: argparse.ArgumentParser) -> None:
    p.add_argument("--pulse-y", default=None, choices=PULSE_NAMES,
                   help="shape of the second horizontal ground acceleration, shaped by --pi14/--pi15/--pi16 "
                        "(solve) or --a-py/--T-py/--t-y (solve-physical); none by default: the ground moves "
                        "along the excitation's x axis")
    p.add_argument("--angle", type=float, default=0.0, metavar="RAD",
                   help="angle (radians, counter-clockwise) from the building's x axis to the excitation's "
                        "(default 0)")
    p.add_argument("--pulse-z", default=None, choices=PULSE_NAMES,
                   help="shape of the vertical ground acceleration (with --pi17 or --a-pz; none by default)")
    p.add_argument("--pulse", default=None, choices=PULSE_NAMES,
                   help="pulse shape (default ricker; not with --record)")
    p.add_argument("--record", metavar="PATH|SAMPLE",
                   help="excite with a real record: .AT2 or .csv file (time s, acceleration g) or a bundled "
                        "sample name (isoslide records pyslammer); runs as recorded, scaled by its fitted Ricker pulse")
    p.add_argument("--record-y", metavar="PATH|SAMPLE",
                   help="second horizontal component of a recorded pair (with --record; not with --pulse-y): "
                        "runs as recorded on the same time axis, scaled by the --record record's fitted pulse")
    p.add_argument("--rtol", type=float, default=DEFAULT_RTOL,
                   help=f"target relative error of Pi1 (default {DEFAULT_RTOL:g})")
    p.add_argument("--history", metavar="FILE",
                   help="write the time history (ground, floor, block) to FILE: .csv, .h5 or .hdf5")
    p.add_argument("--plot", metavar="FILE",
                   help="plot accelerations and sliding (stick/slip shaded) to FILE: .png, .pdf or .svg")
    p.add_argument("--floor", type=_floor, default=FLOORS[0],
                   help=f"floor carrying the contents: {FLOORS[0]} (the isolated slab, 0), {FLOORS[1]} (the "
                        "superstructure's top floor) or a floor's number 0 .. storeys "
                        f"(default {FLOORS[0]}; the slab's with a rigid superstructure)")
    p.add_argument("--storeys", type=int, default=1,
                   help="floors of a uniform flexible superstructure (default 1); its fixed-base "
                        "fundamental period is T_s, its damping ratio xi_s in every mode")
    p.add_argument("--json", action="store_true", help="print the result as JSON")


def _parser() -> argparse.ArgumentParser:
    ap = _Parser(prog="isoslide", description=__doc__.split("\n")[0])
    ap.add_argument("--version", action="version", version=f"isoslide {__version__}")
    sub = ap.add_subparsers(dest="command", required=True)
    s = sub.add_parser("solve", help="one scene given by its Pi-groups")
    for g in INPUTS:
        default = "required" if g.default is None else f"default {g.default:g}"
        s.add_argument(f"--{g.name}", type=float, required=g.default is None, default=g.default,
                       help=f"{g.definition}: {g.meaning}; {g.range_text.replace('value', g.name)} ({default})")
    for g in ROCKING:
        s.add_argument(f"--{g.name}", type=float, default=None,
                       help=f"{g.definition}: {g.meaning}; {g.range_text.replace('value', g.name)} (default: none, "
                            "contents that only slide" + (", Housner's" if g.name == "pi20" else "") + ")")
    for g in TFP_SPEED:
        s.add_argument(f"--{g.name}", type=float, default=None,
                       help=f"{g.definition}: {g.meaning}; {g.range_text.replace('value', g.name)} (default: none, "
                            f"surface 1's {'pi22' if g.name in ('pi31', 'pi32') else 'pi23'})")
    _common(s)
    q = sub.add_parser("solve-physical", help="one scene in SI units")
    for name, unit, default in [("a-p", "m/s^2; default with --record: the fitted pulse's", None),
                                ("T-p", "s; default with --record: the fitted pulse's", None),
                                ("M-b", "kg", None),
                                ("T-b", "s, 0 = fixed base", None), ("xi-b", "-", None),
                                ("m-ec", "kg", None), ("mu-s", "-", None), ("mu-k", "-", None),
                                ("beta", "s/m", 0.0), ("gamma", "s/m", 0.0), ("g", "m/s^2", G_STANDARD),
                                ("Q-d", "N, isolator strength; 0 = linear isolator", 0.0),
                                ("D-y", "m, bilinear bearing's yield displacement; 0 = sliding bearing", 0.0),
                                ("m-st", "kg, superstructure mass (part of M_b)", 0.0),
                                ("T-s", "s, superstructure period; 0 = rigid", 0.0),
                                ("xi-s", "-, superstructure damping ratio", 0.0),
                                ("R", "m, friction pendulum radius: sets T_b and, with --mu-b, Q_d", None),
                                ("mu-b", "-, friction pendulum's friction coefficient (at high speed with "
                                         "--mu-b-slow)", None),
                                ("mu-b-slow", "-, friction pendulum's friction at breakaway: mu(v) = mu_b - "
                                              "(mu_b - mu_b_slow) exp(-rate |v|); default: mu_b at every speed",
                                 None),
                                ("Q-slow", "N, sliding bearing's breakaway strength (with --Q-d, --rate); "
                                           "default Q_d", None),
                                ("rate", "s/m, rate of the sliding bearing's friction law (with --mu-b-slow "
                                         "or --Q-slow)", 0.0),
                                ("a-pz", "m/s^2, vertical ground acceleration amplitude (with --pulse-z)", 0.0),
                                ("a-py", "m/s^2, second horizontal component's amplitude (with --pulse-y); "
                                         "default a_p", None),
                                ("T-py", "s, second horizontal component's period (with --pulse-y); default T_p",
                                 None),
                                ("t-y", "s, time by which the second horizontal component lags the first "
                                        "(with --pulse-y or --record-y)", 0.0),
                                ("b", "m, half-width of contents that can rock (with --h)", None),
                                ("h", "m, half-height of contents that can rock (with --b)", None),
                                ("restitution", "-, the rocking block's restitution at impact; default Housner's",
                                 None)]:
        required = default is None and name not in ("a-p", "T-p", "T-b", "R", "mu-b", "mu-b-slow", "Q-slow",
                                                    "a-py", "T-py", "b", "h", "restitution")
        q.add_argument(f"--{name}", type=float, required=required, default=default,
                       help=f"{name.replace('-', '_')} [{unit}]")
    for name, unit in (("L", "m, effective radii L1 (each inner surface), L2 (lower outer), L3 (upper outer)"),
                       ("mu", "-, friction coefficients mu1 <= mu2 <= mu3 of the same surfaces"),
                       ("d", "m, displacement limits d1, d2, d3 of the same surfaces")):
        q.add_argument(f"--tfp-{name}", type=float, nargs=3, metavar=(f"{name}1", f"{name}2", f"{name}3"),
                       help=f"triple friction pendulum (with the other --tfp options; sets T_b and Q_d): {unit}")
    _common(q)
    f = sub.add_parser("fit", help="fit a pulse to a record's dominant acceleration pulse")
    f.add_argument("record", metavar="PATH|SAMPLE", help=".AT2 or .csv file, or a bundled sample name")
    f.add_argument("--shape", default="ricker", choices=("ricker", "mp", "mavroeidis_papageorgiou"),
                   help="pulse shape (default ricker; mp = Mavroeidis-Papageorgiou)")
    f.add_argument("--plot", metavar="FILE", help="plot record and pulse to FILE: .png, .pdf or .svg")
    f.add_argument("--json", action="store_true", help="print the fit as JSON")
    r = sub.add_parser("records", help="list the record suites, or the ground motions of one suite")
    r.add_argument("suite", nargs="?", metavar="SUITE|FOLDER|MANIFEST",
                   help="a suite name (isoslide records lists them), a folder of .AT2 pairs or a .csv "
                        "manifest (name,x,y[,z]); without it: the suites")
    r.add_argument("--json", action="store_true", help="print the list as JSON")
    return ap


def _fit_dict(fit) -> dict:
    """A fitted pulse as plain values (a_p in m/s^2 and g, times in s)."""
    out = {"shape": fit.shape, "a_p": fit.a_p, "a_p_g": fit.a_p_g, "T_p": fit.T_p, "t_peak": fit.t_peak,
           "polarity": fit.polarity, "r2": fit.r2, "nrmse": fit.nrmse, "energy_fraction": fit.energy_fraction}
    out.update(dict(fit.params))
    return out


def _record_dict(rec) -> dict:
    return {"name": rec.name, "event": rec.event, "station": rec.station, "component": rec.component,
            "npts": rec.npts, "dt": rec.dt, "pga_g": rec.pga, "source": rec.source, "licence": rec.licence}


def _check_outputs(args) -> None:
    """Refuse bad output file names before any work."""
    if getattr(args, "history", None):
        try:
            history_format(args.history)
        except ValueError:
            raise ValueError(f"history = {args.history!r} has an unknown extension; allowed: "
                             f"{', '.join(FORMATS)}") from None
    if getattr(args, "plot", None):
        check_plot_path(args.plot)


def _load_record_y(spec):
    """The pair's second component (``--record-y``); errors name ``record_y``."""
    try:
        return load_record(spec)
    except ValueError as exc:
        msg = str(exc)
        raise ValueError(f"record_y = {msg[len('record = '):]}" if msg.startswith("record = ")
                         else f"record_y = {spec!r}: {msg}") from None


def _second_component(args):
    """The second horizontal component (shape name, record or None); refuses contradictory options."""
    if args.record_y is not None and args.pulse_y is not None:
        raise ValueError(f"pulse_y = {args.pulse_y!r} and record_y = {args.record_y!r} exclude each other; "
                         "allowed: one of --pulse-y, --record-y")
    if args.record_y is not None and args.record is None:
        raise ValueError(f"record_y = {args.record_y!r} without --record; allowed: --record-y with --record "
                         "(the pair's first component), or --pulse-y")
    if args.record_y is not None:
        return _load_record_y(args.record_y)
    if args.pulse_y is None:
        names = _Y_GROUPS if args.command == "solve" else ("a_py", "T_py", "t_y")
        for name, value in ((n, getattr(args, n)) for n in names):
            if value is not None and value != _Y_DEFAULTS.get(name):
                raise ValueError(f"{name} = {value!r} shapes a second horizontal component, and there is none; "
                                 "allowed: --pulse-y or --record-y with it")
    return args.pulse_y


def _scene(args):
    """The scene of ``solve`` / ``solve-physical`` and the records' description (or None)."""
    if args.record is not None and args.pulse is not None:
        raise ValueError(f"pulse = {args.pulse!r} and record = {args.record!r} exclude each other; "
                         "allowed: one of --pulse, --record")
    rec = load_record(args.record) if args.record is not None else None
    second = _second_component(args)
    excitation = rec if rec is not None else (args.pulse or "ricker")
    info = None if rec is None else {"record": _record_dict(rec)}
    if second is not None and not isinstance(second, str):
        info["record_y"] = _record_dict(second)
    if args.command == "solve":
        scene = Scene(**{g.name: getattr(args, g.name) for g in INPUTS + ROCKING + TFP_SPEED}, pulse=excitation, floor=args.floor,
                      storeys=args.storeys, pulse_z=args.pulse_z, pulse_y=second, angle=args.angle)
        if rec is not None:
            info["fitted_pulse"] = _fit_dict(rec.fit())
        return scene, info
    a_p, T_p = args.a_p, args.T_p
    if rec is None:
        missing = [n for n, v in (("--a-p", a_p), ("--T-p", T_p)) if v is None]
        if missing:
            raise ValueError(f"the following arguments are required: {', '.join(missing)} "
                             "(or --record to take them from the record's fitted pulse)")
    elif a_p is None or T_p is None:
        fit = rec.fit()
        info["fitted_pulse"] = _fit_dict(fit)
        a_p = fit.a_p if a_p is None else a_p
        T_p = fit.T_p if T_p is None else T_p
    T_b, Q_d, D_y = args.T_b, args.Q_d, args.D_y
    bearing = {"Q_slow": args.Q_slow, "rate": args.rate}
    if (args.R is None) != (args.mu_b is None):
        raise ValueError("a friction pendulum needs both --R and --mu-b; allowed: both or neither")
    tfp = [v for v in (args.tfp_L, args.tfp_mu, args.tfp_d) if v is not None]
    if tfp:
        if len(tfp) != 3:
            raise ValueError("a triple friction pendulum needs --tfp-L, --tfp-mu and --tfp-d; allowed: all three or "
                             "none")
        if args.R is not None or T_b is not None or Q_d != 0.0 or D_y != 0.0 or args.Q_slow is not None:
            raise ValueError("--tfp-L/--tfp-mu/--tfp-d set T_b, Q_d and D_y; allowed: either the --tfp options or "
                             "--R/--mu-b or --T-b/--Q-d/--D-y/--Q-slow")
        fp = triple_friction_pendulum(args.tfp_L, args.tfp_mu, args.tfp_d, args.M_b, args.g,
                                      mu_slow=args.mu_b_slow, rate=args.rate)
        T_b, Q_d, D_y = fp["T_b"], fp["Q_d"], fp["D_y"]
        bearing = {"tfp": fp["tfp"], "Q_slow": fp.get("Q_slow"), "rate": fp.get("rate", 0.0)}
    elif args.mu_b_slow is not None and args.R is None:
        raise ValueError("--mu-b-slow is given without a friction pendulum; allowed: with --R and --mu-b "
                         "(or --Q-slow with --Q-d)")
    if args.R is not None:
        if T_b is not None or Q_d != 0.0 or D_y != 0.0 or args.Q_slow is not None:
            raise ValueError("--R/--mu-b set T_b, Q_d, D_y and Q_slow; allowed: either --R/--mu-b or "
                             "--T-b/--Q-d/--D-y/--Q-slow")
        fp = friction_pendulum(args.R, args.mu_b, args.M_b, args.g, mu_slow=args.mu_b_slow, rate=args.rate)
        T_b, Q_d, D_y = fp["T_b"], fp["Q_d"], fp["D_y"]
        bearing = {"Q_slow": fp.get("Q_slow"), "rate": fp.get("rate", 0.0)}
    if T_b is None:
        raise ValueError("the following arguments are required: --T-b (or --R and --mu-b for a friction pendulum)")
    scene = Scene.from_physical(a_p, T_p, args.M_b, T_b, args.xi_b, args.m_ec, args.mu_s, args.mu_k,
                                args.beta, args.gamma, args.g, excitation, Q_d=Q_d, D_y=D_y, m_st=args.m_st,
                                T_s=args.T_s, xi_s=args.xi_s, floor=args.floor, storeys=args.storeys,
                                a_pz=args.a_pz, pulse_z=args.pulse_z, pulse_y=second, a_py=args.a_py,
                                T_py=args.T_py, t_y=args.t_y, angle=args.angle, b=args.b, h=args.h,
                                restitution=args.restitution, **bearing)
    return scene, info


def _print_fit(fit: dict, indent: str = "") -> None:
    extra = ", ".join(f"{k} = {fit[k]:.6g}" for k in ("gamma", "nu", "t0", "A") if k in fit)
    print(f"{indent}{fit['shape']}: a_p = {fit['a_p']:.6g} m/s^2 ({fit['a_p_g']:.4f} g), "
          f"T_p = {fit['T_p']:.6g} s, t_peak = {fit['t_peak']:.6g} s, polarity {fit['polarity']:+d}, "
          f"R^2 = {fit['r2']:.3f}" + (f", {extra}" if extra else ""))


def _solve(args) -> int:
    _check_outputs(args)
    scene, info = _scene(args)
    want_history = bool(args.history or args.plot)
    sol = solve(scene, rtol=args.rtol, history=want_history)
    slid = math.isfinite(sol.peak_angle)
    out = {"pi1": sol.pi1, "pi1_residual": sol.pi1_residual, "tau_peak": sol.tau_peak,
           "peak_angle": sol.peak_angle if slid else None,
           "peak_angle_deg": math.degrees(sol.peak_angle) if slid else None,
           "settled": sol.settled, "model": sol.model, "contact": sol.facets.contact,
           "n_steps": sol.n_steps, "n_events": sol.n_events, "peak_stage": sol.peak_stage,
           "theta_max": sol.theta_max, "overturned": sol.overturned, "modes": list(sol.modes),
           "scene": {**scene.pis(), **{g.name: getattr(scene, g.name) for g in ROCKING + TFP_SPEED}, "floor": scene.floor, "storeys": scene.storeys, "pulse": scene.pulse.name,
                     "pulse_y": None if scene.pulse_y is None else scene.pulse_y.name, "angle": scene.angle,
                     "planar": scene.planar,
                     "pulse_z": None if scene.pulse_z is None else scene.pulse_z.name}}
    if scene.scale is not None:
        out.update({"u_max_m": sol.u_max, "u_residual_m": sol.u_residual, "t_peak_s": sol.t_peak})
        out["scene"].update({"a_p": scene.scale.a_p, "T_p": scene.scale.T_p} if info else {})
    if info:
        out.update(info)
    try:
        if args.history:
            write_history(sol, scene, args.history)
            out["history_file"] = args.history
        if args.plot:
            title = f"{scene.pulse.name}: Pi1 = {sol.pi1:.4g}" + (
                f", u_max = {sol.u_max:.4g} m" if scene.scale is not None else "")
            plot_history(history_table(sol, scene), args.plot, title=title)
            out["plot_file"] = args.plot
    except OSError as exc:
        which = "history" if args.history and "history_file" not in out else "plot"
        raise ValueError(f"{which} = {getattr(args, which)!r}: cannot be written ({exc.strerror})") from None
    if args.json:
        print(json.dumps(out, indent=1))
        return 0
    for k, v in out.items():
        if k in ("scene", "record", "record_y", "fitted_pulse", "peak_angle_deg"):
            continue
        if k == "peak_angle":
            v = "none (no slide)" if v is None else f"{v} rad ({out['peak_angle_deg']:.6g} deg)"
        print(f"{k:>13s}: {v}")
    if info:
        r = info["record"]
        print(f"{'record':>13s}: {r['name']} ({r['event']}, {r['station']} {r['component']}), as recorded")
        if "record_y" in info:
            r = info["record_y"]
            print(f"{'record_y':>13s}: {r['name']} ({r['event']}, {r['station']} {r['component']}), as "
                  "recorded, on the record's scales")
        if "fitted_pulse" in info:
            print(f"{'fitted pulse':>13s}: ", end="")
            _print_fit(info["fitted_pulse"])
    return 0


def _fit(args) -> int:
    if args.plot:
        check_plot_path(args.plot)
    rec = load_record(args.record)
    fit = rec.fit(args.shape)
    out = {"record": _record_dict(rec), "fitted_pulse": _fit_dict(fit)}
    if args.plot:
        try:
            plot_fit(rec, fit, args.plot)
        except OSError as exc:
            raise ValueError(f"plot = {args.plot!r}: cannot be written ({exc.strerror})") from None
        out["plot_file"] = args.plot
    if args.json:
        print(json.dumps(out, indent=1))
        return 0
    r = out["record"]
    print(f"record: {r['name']} ({r['event']}, {r['station']} {r['component']}), {r['npts']} samples "
          f"at {r['dt']:g} s, PGA {r['pga_g']:.3f} g")
    print("fitted ", end="")
    _print_fit(out["fitted_pulse"])
    f = out["fitted_pulse"]
    print(f"window: {fit.window[0]:.4g} to {fit.window[1]:.4g} s, NRMSE {f['nrmse']:.3f}, "
          f"share of the record's energy {f['energy_fraction']:.3f}")
    if args.plot:
        print(f"plot: {args.plot}")
    return 0


def _records(args) -> int:
    """``isoslide records [SUITE]``: the suites, or one suite's ground motions."""
    if args.suite is None:
        rows = [{"name": name, "description": text} for name, text in SUITES.items()]
        if args.json:
            print(json.dumps(rows, indent=1))
            return 0
        for r in rows:
            print(f"{r['name']:<30s} {r['description']}")
        print("a folder of .AT2 pairs or a .csv manifest (name,x,y[,z]) is a suite too: isoslide records PATH")
        return 0
    rows = [_motion_dict(gm) for gm in suite(args.suite)]
    if args.json:
        print(json.dumps(rows, indent=1))
        return 0
    print(f"{'name':<30s} {'comp':<5s} {'dt s':>7s} {'npts':>11s} {'PGA g':>6s} pulse  event, station")
    for r in rows:
        npts = sorted({c["npts"] for c in r["components"].values()})
        pulse = {True: "yes", False: "no", None: "-"}[r["pulse"]]
        print(f"{r['name']:<30s} {''.join(r['components']):<5s} {r['dt']:7.4g} "
              f"{'/'.join(map(str, npts)):>11s} {r['pga_g']:6.3f} {pulse:<6s} {r['event']}, {r['station']}")
    for lic in sorted({r["licence"] for r in rows if r["licence"]}):
        print(f"licence: {lic}")
    return 0


def _motion_dict(gm) -> dict:
    """One ground motion of a suite as plain values (dt in s, PGA in g)."""
    first = gm.x
    return {"name": gm.name, "components": {k: _record_dict(rec) for k, rec in gm.components.items()},
            "dt": first.dt, "pga_g": gm.pga, "pulse": gm.pulse,
            "event": gm.metadata.get("event", first.event), "station": gm.metadata.get("station", first.station),
            "licence": gm.metadata.get("licence", first.licence)}


def main(argv=None) -> int:
    """Run the command line with ``argv`` (default ``sys.argv[1:]``); return the exit code."""
    try:
        args = _parser().parse_args(argv)
    except SystemExit as exc:  # --help, --version, or a usage error already printed
        return exc.code if isinstance(exc.code, int) else EXIT_USAGE
    for k, v in vars(args).items():
        if isinstance(v, float) and not math.isfinite(v):
            return _fail(f"{k} = {v!r} is invalid; allowed: a finite number")
    try:
        if args.command == "fit":
            return _fit(args)
        if args.command == "records":
            return _records(args)
        return _solve(args)
    except (ValueError, ModuleNotFoundError) as exc:
        return _fail(str(exc))


def _fail(message: str) -> int:
    """Print ``isoslide: error: <message>`` on one line to stderr; return the usage exit code."""
    print(f"isoslide: error: {' '.join(message.split())}", file=sys.stderr)
    return EXIT_USAGE


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
