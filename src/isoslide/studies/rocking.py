"""Contents that rock: overturning spectra, the sliding-or-rocking map, isolation, an overturning fragility.

Configuration section ``rocking`` (its defaults in ``config/schema.yaml``).  The contents are a rigid
uniform rectangular block (:mod:`isoslide.model.rocking`) of half-width ``b`` and half-height ``h``
(m): slenderness ``alpha = atan(b/h)`` (rad), size ``R = sqrt(b^2 + h^2)`` (m), frequency parameter
``p = sqrt(3 g / (4 R))`` (rad/s).  It stands on Coulomb friction (``mu_s = mu_k``), tips before it
slides when ``mu_s > tan(alpha)`` (:attr:`isoslide.Scene.tips`) and only slides otherwise.  The groups
(:mod:`isoslide.groups`), with ``a_p`` the pulse's acceleration amplitude (m/s^2) and ``T_p`` its
period (s):

=====  ====================  ======================================================================
group  definition            meaning
=====  ====================  ======================================================================
Pi1    u_max / (a_p T_p^2)   peak sliding of the block's base relative to the floor (a result)
Pi2    mu_k g / a_p          friction strength; for a block ``mu_s / (Pi18 Pi21)`` (``Pi5 = 1``)
Pi3    T_b / T_p             isolation period over the pulse's; 0 = fixed base
Pi4    xi_b                  isolation damping ratio
Pi5    mu_k / mu_s           1: Coulomb friction, static = kinetic
Pi8    m_EC / M_b            mass of the block over the isolated mass
Pi18   b / h                 aspect ratio, ``tan(alpha)``
Pi19   p T_p                 block frequency parameter over the pulse's; the spectra's abscissa is 1/Pi19
Pi20   e                     restitution of the angular velocity at impact (Housner's ``1 - 3/2 sin^2(alpha)``)
Pi21   a_p / (g tan alpha)   pulse amplitude over the uplift acceleration
=====  ====================  ======================================================================

The result of a rocking solve is ``theta_max`` (rad), the peak ``|theta|``, stored divided by
``alpha`` (``theta_max_over_alpha``: 1 is the tipping angle, ``(pi/2)/alpha`` an overturned block),
and whether the block overturned.

Four parts, each computed from the configuration alone (no Snakemake):

* **overturning spectra** (:func:`spectra_study`, ``results/datasets/rocking_spectra.nc``), in the
  style of Zhang and Makris (2001): for each pulse, base (``Pi3``) and ``1/Pi19``, the least ``Pi21``
  that overturns the block.  Overturning is not monotonic in the amplitude under a pulse with lobes
  of both signs (a Ricker wavelet): a block may overturn at one amplitude and survive a larger one,
  so a bisection started from a large overturning amplitude may converge to a crossing that is not
  the least.  Each curve is therefore scanned upwards over a coarse geometric grid of ``Pi21``
  (``rocking.spectra.pi21``) and stopped at the first grid amplitude that overturns; only that first
  bracket (the grid amplitude below it, which does not overturn, and it) is bisected, geometrically,
  until its upper end over its lower end is at most ``1 + tolerance`` (``rocking.spectra.tolerance``,
  1e-3 by default).  The answer is the least overturning amplitude to the grid's resolution: a window
  of overturning narrower than one grid step below the first overturning grid point is missed, and
  amplitudes above the first overturning grid point are not solved.  The fixed-base rectangular
  pulse is compared with the linearised closed form (:func:`isoslide.model.rocking.rectangular_overturn_ratio`;
  the exact block needs ``O(alpha^2)`` more).
* **the sliding-or-rocking map** (:func:`map_study`, ``rocking_map.nc``): the modes a block visits
  (rest, slide, rock, slide-rock), its ``theta_max/alpha``, ``Pi1`` and whether it overturned, over
  ``mu_s`` and ``b/h``, under one pulse of fixed ``a_p/g`` and ``Pi19``.  A block with ``mu_s <= b/h``
  never rocks.
* **does isolation protect a tall block or expose it** (the question of Vassiliou and Makris 2012):
  :func:`isolation_effect` and :func:`findings`, from the spectra: the ratio of the least overturning
  ``Pi21`` on the isolated floor to that on the fixed base, per ``1/Pi19`` (above 1: the isolated
  floor needs a stronger ground pulse to overturn the block, it protects; below 1 it exposes).
* **an overturning fragility** (:func:`overturning_fragility`, ``rocking_fragility.nc``): recorded ground
  motions of a suite (the FEMA P695 far-field set by default, a few of them in the default run)
  scaled to PGA stripes, on a fixed base and an isolated slab; lognormal curves ``P(theta_max/alpha >
  limit | IM)`` and ``P(overturning | IM)`` fitted by maximum likelihood (Baker 2015,
  :mod:`isoslide.studies.fragility`) and bootstrapped over the records; the isolated slab's
  overturning curves on PFA and PFV are written for pelicun (:func:`write_pelicun`).

Solves that the exact model cannot finish (the block would leave the floor,
:class:`isoslide.solver.ContactError`; the step budget ran out, :class:`isoslide.solver.StepBudgetError`)
are kept as unresolved (``solve_status``), never guessed.

References
----------
J. Zhang and N. Makris (2001), Rocking response of free-standing blocks under cycloidal pulses,
J. Eng. Mech. 127(5).  M. F. Vassiliou and N. Makris (2012), Analysis of the rocking response of rigid
blocks standing free on a seismically isolated base, Earthquake Eng. Struct. Dyn. 41(2).
J. W. Baker (2015), Efficient analytical fragility function fitting using dynamic structural
analysis, Earthquake Spectra 31(1).
"""

from __future__ import annotations

import copy
import itertools
import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import xarray as xr

from . import fragility as _fit
from .. import solver
from ..datasets import global_attrs, pi_attrs, write_netcdf
from ..engine.building_kernel import BLOCK_MODES
from ..model.rocking import G_STANDARD, Block, housner_restitution, rectangular_overturn_ratio
from ..pulses import get_pulse
from ..records import suite as _suite
from ..scene import Scene
from .fragility_study import FIT_STATUS, REFERENCE_FRAGILITY, add_curves, scaled_pulse
from .intensity import IM_NAMES, IM_UNITS, floor_peaks
from .pelicun_export import write_damage_db

__all__ = ["BASES", "BRACKET_STATUS", "DATASETS", "Outcomes", "PELICUN_COMPONENTS", "RESPONSES", "SOLVE_STATUS",
           "check_fragility", "check_map", "check_settings", "check_spectra", "dataset_names", "findings",
           "fragility_dataset", "fragility_records", "fragility_summary", "isolation_effect",
           "linearised_rectangular", "map_dataset", "map_scene", "map_study", "map_summary", "overturning_fragility",
           "rectangular_check", "rocking_settings", "scan_grid", "solve_blocks", "spectra_dataset", "spectra_scene",
           "spectra_study", "spectra_summary", "study_datasets", "write_outputs", "write_pelicun"]

G = G_STANDARD
"""Gravity (m/s^2)."""

DATASETS = ("rocking_spectra", "rocking_map", "rocking_fragility")
"""The study's datasets (``results/datasets/<name>.nc``)."""

SOLVE_STATUS = ("resolved", "contact_lost", "step_budget")
"""Meanings of ``solve_status`` 0, 1, 2: solved; the block would leave the floor (flight is not
modelled, :class:`isoslide.solver.ContactError`); the solver's step budget ran out
(:class:`isoslide.solver.StepBudgetError`).  -1: not solved."""

BRACKET_STATUS = ("bisected", "overturns_at_scan_start", "none_on_scan", "unresolved")
"""Meanings of ``bracket_status`` 0..3: the first bracket was bisected to the tolerance; the scan's
first amplitude already overturns (``pi21_overturn`` is an upper bound); nothing on the scan
overturns; a solve at the bracket's lower end or during the bisection was unresolved (the bisection
stopped there)."""

RESPONSES = ("rest", "slide", "rock", "slide_and_rock", "overturned")
"""Meanings of the map's ``response`` 0..4: never moved; slid only; rocked only (without
overturning); slid and rocked (the slide-rock mode, or both modes in turn); overturned."""

BASES = ("fixed_base", "isolated")
"""The fragility study's buildings: a fixed base (the floor is the ground), an isolated slab."""

PELICUN_COMPONENTS = {"pfa": "isoslide.BLOCK.PFA", "pfv": "isoslide.BLOCK.PFV"}
"""pelicun component ID of the block's overturning fragility on each floor IM."""

VERDICT_FACTOR = 2.0
"""The isolated and fixed-base thresholds count as the same when their ratio is within ``1 +-
VERDICT_FACTOR * tolerance`` (each is known to the bisection's tolerance)."""


def rocking_settings(config: Mapping) -> dict:
    """The sections of a complete configuration the study reads (copies): ``rocking`` and ``solver``."""
    return {k: copy.deepcopy(config[k]) for k in ("rocking", "solver")}


def dataset_names() -> list:
    """The study's datasets, in order (:data:`DATASETS`)."""
    return list(DATASETS)


# ----------------------------------------------------------------------------------------------
# checks
# ----------------------------------------------------------------------------------------------

def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def _number(key: str, value, lo: float, hi: float, lo_in: bool = True, hi_in: bool = True) -> float:
    ok = _is_number(value) and (value >= lo if lo_in else value > lo) and (value <= hi if hi_in else value < hi)
    if not ok:
        left, right = ("<=" if lo_in else "<"), ("<=" if hi_in else "<")
        raise ValueError(f"rocking.{key} = {value!r} is out of range; allowed range: {lo:g} {left} value {right} {hi:g}")
    return float(value)


def _increasing(key: str, values, lo: float, hi: float, lo_in: bool = False, min_items: int = 1) -> list:
    if not isinstance(values, (list, tuple)) or len(values) < min_items:
        raise ValueError(f"rocking.{key} = {values!r} is invalid; allowed: a list of at least {min_items} numbers")
    out = [_number(key, v, lo, hi, lo_in) for v in values]
    if any(b <= a for a, b in itertools.pairwise(out)):
        raise ValueError(f"rocking.{key} = {values!r} is not strictly increasing; allowed: increasing values, each once")
    return out


def _restitution(key: str, value) -> float | None:
    return None if value is None else _number(key, value, 0.0, 1.0, lo_in=False)


def _pulse(key: str, name) -> str:
    try:
        get_pulse(name)
    except (TypeError, ValueError) as err:
        raise ValueError(f"rocking.{key} = {name!r} is invalid: {err}") from None
    return str(name)


def check_spectra(section: Mapping) -> dict:
    """The checked ``rocking.spectra`` section (lists as lists of floats).

    Raises
    ------
    ValueError
        Naming the key (``rocking.spectra.<key>``), its value and what is allowed: among them
        ``pi3`` must start at 0 (the fixed base) and the restitution must not exceed Housner's.
    """
    pulses = section["pulses"]
    if not isinstance(pulses, (list, tuple)) or not pulses or len(set(pulses)) != len(pulses):
        raise ValueError(f"rocking.spectra.pulses = {pulses!r} is invalid; allowed: a non-empty list of distinct "
                         "pulse names")
    out = {"pulses": [_pulse("spectra.pulses", p) for p in pulses],
           "inverse_pi19": _increasing("spectra.inverse_pi19", section["inverse_pi19"], 0.0, 1e6),
           "pi3": _increasing("spectra.pi3", section["pi3"], 0.0, 1e4, lo_in=True, min_items=2),
           "pi4": _number("spectra.pi4", section["pi4"], 0.0, 1e3),
           "pi8": _number("spectra.pi8", section["pi8"], 0.0, 1e3, lo_in=False),
           "pi18": _number("spectra.pi18", section["pi18"], 0.0, 1e3, lo_in=False),
           "pi20": _restitution("spectra.pi20", section["pi20"]),
           "mu_s": _number("spectra.mu_s", section["mu_s"], 0.0, 1e3, lo_in=False),
           "tolerance": _number("spectra.tolerance", section["tolerance"], 0.0, 1.0, lo_in=False)}
    if out["pi3"][0] != 0.0:
        raise ValueError(f"rocking.spectra.pi3 = {section['pi3']!r} does not start at 0.0; allowed: 0.0 (the fixed "
                         "base the isolated floors are compared with), then increasing values")
    scan = section["pi21"]
    start = _number("spectra.pi21.start", scan["start"], 0.0, 1e6, lo_in=False)
    stop = _number("spectra.pi21.stop", scan["stop"], start, 1e6, lo_in=False)
    num = scan["num"]
    if not (isinstance(num, int) and not isinstance(num, bool) and 2 <= num <= 1000):
        raise ValueError(f"rocking.spectra.pi21.num = {num!r} is out of range; allowed range: 2 <= value <= 1000 "
                         "(an integer)")
    out["pi21"] = {"start": start, "stop": stop, "num": int(num)}
    _check_housner("spectra.pi20", out["pi20"], out["pi18"])
    return out


def _check_housner(key: str, e: float | None, pi18: float) -> None:
    if e is not None and e > housner_restitution(math.atan(pi18)):
        raise ValueError(f"rocking.{key} = {e!r} exceeds Housner's 1 - 3/2 sin^2(alpha) = "
                         f"{housner_restitution(math.atan(pi18)):.6g} of b/h = {pi18:g}; allowed: 0 < e <= that value, "
                         "or null")


def check_map(section: Mapping) -> dict:
    """The checked ``rocking.map`` section (``ValueError`` naming ``rocking.map.<key>``)."""
    return {"pulse": _pulse("map.pulse", section["pulse"]),
            "a_p_over_g": _number("map.a_p_over_g", section["a_p_over_g"], 0.0, 100.0, lo_in=False),
            "pi19": _number("map.pi19", section["pi19"], 0.0, 1e6, lo_in=False),
            "mu_s": _increasing("map.mu_s", section["mu_s"], 0.0, 100.0),
            "pi18": _increasing("map.pi18", section["pi18"], 0.0, 1e3),
            "pi3": _increasing("map.pi3", section["pi3"], 0.0, 1e4, lo_in=True),
            "pi4": _number("map.pi4", section["pi4"], 0.0, 1e3),
            "pi8": _number("map.pi8", section["pi8"], 0.0, 1e3, lo_in=False)}


def check_fragility(section: Mapping) -> dict:
    """The checked ``rocking.fragility`` section (``ValueError`` naming ``rocking.fragility.<key>``)."""
    f = section
    motions = f["motions"]
    if not (isinstance(motions, int) and not isinstance(motions, bool) and 2 <= motions <= 1000):
        raise ValueError(f"rocking.fragility.motions = {motions!r} is out of range; allowed range: 2 <= value <= 1000 "
                         "(an integer: the bootstrap resamples the records)")
    if f["component"] not in ("x", "y"):
        raise ValueError(f"rocking.fragility.component = {f['component']!r} is invalid; allowed: 'x', 'y'")
    if not isinstance(f["suite"], str) or not f["suite"]:
        raise ValueError(f"rocking.fragility.suite = {f['suite']!r} is invalid; allowed: a suite name or path")
    b = _number("fragility.b", f["b"], 0.0, 100.0, lo_in=False)
    h = _number("fragility.h", f["h"], 0.0, 100.0, lo_in=False)
    out = {"suite": f["suite"], "motions": int(motions), "component": f["component"],
           "levels": _increasing("fragility.levels", f["levels"], 0.0, 1e3, min_items=2),
           "b": b, "h": h, "restitution": _restitution("fragility.restitution", f["restitution"]),
           "mu": _number("fragility.mu", f["mu"], 0.0, 100.0, lo_in=False),
           "mass": _number("fragility.mass", f["mass"], 0.0, 1e12, lo_in=False),
           "T_b": _number("fragility.T_b", f["T_b"], 0.0, 100.0, lo_in=False),
           "xi_b": _number("fragility.xi_b", f["xi_b"], 0.0, 1e3),
           "M_b": _number("fragility.M_b", f["M_b"], 0.0, 1e15, lo_in=False),
           "rotation_limits": (_increasing("fragility.rotation_limits", f["rotation_limits"], 0.0, 1.0, min_items=0)
                               if f["rotation_limits"] else []),
           "seed": f["seed"], "n_boot": f["bootstrap"]["n_boot"],
           "level": _number("fragility.bootstrap.level", f["bootstrap"]["level"], 0.0, 1.0, lo_in=False, hi_in=False)}
    if any(v >= 1.0 for v in out["rotation_limits"]):
        raise ValueError(f"rocking.fragility.rotation_limits = {f['rotation_limits']!r} is invalid; allowed: values "
                         "below 1 (the tipping angle; overturning is the last limit state anyway)")
    for key in ("seed", "n_boot"):
        v = out[key]
        if not (isinstance(v, int) and not isinstance(v, bool) and v >= 0):
            where = "seed" if key == "seed" else "bootstrap.n_boot"
            raise ValueError(f"rocking.fragility.{where} = {v!r} is invalid; allowed: an integer >= 0")
    _check_housner("fragility.restitution", out["restitution"], b / h)
    return out


def check_settings(settings: Mapping) -> dict:
    """The checked subsections of ``settings["rocking"]`` that are present (``spectra``, ``map``, ``fragility``).

    Raises
    ------
    ValueError
        Naming the key (``rocking.<subsection>.<key>``), its value and what is allowed.
    """
    checks = {"spectra": check_spectra, "map": check_map, "fragility": check_fragility}
    return {k: fn(settings["rocking"][k]) for k, fn in checks.items() if k in settings["rocking"]}


# ----------------------------------------------------------------------------------------------
# solving blocks
# ----------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Outcomes:
    """What the study reads of the solves of rocking scenes, one entry per scene, in order.

    Attributes
    ----------
    theta_max : numpy.ndarray of float
        Peak ``|theta|`` (rad; ``pi/2`` where overturned); NaN where unresolved.
    overturned : numpy.ndarray of bool
        The block overturned.
    pi1 : numpy.ndarray of float
        Peak sliding of the block's base, ``u_max / (a_p T_p^2)``; NaN where unresolved.
    modes : numpy.ndarray of int8
        Modes visited, bit ``k`` for :data:`isoslide.engine.building_kernel.BLOCK_MODES` ``[k]``
        (rest, slide, rock, slide-rock); 0 where unresolved.
    status : numpy.ndarray of int8
        :data:`SOLVE_STATUS` code.
    """

    theta_max: np.ndarray
    overturned: np.ndarray
    pi1: np.ndarray
    modes: np.ndarray
    status: np.ndarray


def solve_blocks(scenes, rtol: float | None = None) -> Outcomes:
    """Solve rocking scenes one by one with :func:`isoslide.solve`, keeping the unresolved ones.

    Parameters
    ----------
    scenes : sequence of isoslide.Scene
        Scenes with a rocking block (or contents that only slide).
    rtol : float, optional
        The solver's target relative error.

    Returns
    -------
    Outcomes
        A scene whose block would leave the floor (:class:`isoslide.solver.ContactError`) or that
        exhausts the step budget (:class:`isoslide.solver.StepBudgetError`) is stored with its
        status and NaN results.
    """
    scenes = list(scenes)
    n = len(scenes)
    theta, pi1 = np.full(n, np.nan), np.full(n, np.nan)
    over, modes, status = np.zeros(n, bool), np.zeros(n, np.int8), np.zeros(n, np.int8)
    for i, sc in enumerate(scenes):
        try:
            sol = solver.solve(sc, rtol=rtol)
        except solver.ContactError:
            status[i] = 1
            continue
        except solver.StepBudgetError:
            status[i] = 2
            continue
        theta[i], over[i], pi1[i] = sol.theta_max, sol.overturned, sol.pi1
        modes[i] = sum(1 << k for k, m in enumerate(BLOCK_MODES) if m in sol.modes)
    return Outcomes(theta_max=theta, overturned=over, pi1=pi1, modes=modes, status=status)


def _solver(fn):
    return solve_blocks if fn is None else fn


def _flags(meanings, start: int = 0) -> dict:
    return {"units": "1", "flag_values": np.arange(start, start + len(meanings), dtype=np.int8),
            "flag_meanings": " ".join(meanings)}


THETA_ATTRS = {"long_name": "peak rotation of the block over its slenderness, theta_max / alpha", "units": "1",
               "comment": "theta_max = peak |theta| (rad), alpha = atan(b/h) (rad); 1 is the tipping angle, "
                          "(pi/2)/alpha an overturned block, 0 a block that never rocked"}


# ----------------------------------------------------------------------------------------------
# overturning spectra
# ----------------------------------------------------------------------------------------------

def scan_grid(section: Mapping) -> np.ndarray:
    """The coarse scan of Pi21: ``num`` values geometrically spaced from ``start`` to ``stop`` (``section["pi21"]``)."""
    s = section["pi21"]
    return np.geomspace(float(s["start"]), float(s["stop"]), int(s["num"]))


def spectra_scene(section: Mapping, pulse: str, pi3: float, pi19: float, pi21: float) -> Scene:
    """The scene of one spectra point: the block of ``section`` under ``pulse`` at ``Pi3``, ``Pi19``, ``Pi21``.

    Parameters
    ----------
    section : mapping
        :func:`check_spectra` of ``rocking.spectra``: the block's ``pi18 = b/h``, ``pi20 = e`` (None:
        Housner's), friction ``mu_s`` (static = kinetic, dimensionless), the isolator's ``pi4 =
        xi_b`` and the mass ratio ``pi8 = m_EC/M_b``.
    pulse : str
        Pulse shape (:mod:`isoslide.pulses`).
    pi3 : float
        ``T_b/T_p``; 0 = fixed base.
    pi19 : float
        ``p T_p``.
    pi21 : float
        ``a_p/(g tan(alpha))``.

    Returns
    -------
    isoslide.Scene
        With ``Pi2 = mu_s / (Pi18 Pi21)`` (``mu_k g / a_p``, ``a_p = Pi21 g tan(alpha)``), ``Pi5 = 1``, and
        ``Pi4`` of the section on an isolated floor, 0 on the fixed base.
    """
    pi18 = float(section["pi18"])
    return Scene(pi2=float(section["mu_s"]) / (pi18 * pi21), pi3=pi3, pi4=float(section["pi4"]) if pi3 > 0 else 0.0,
                 pi5=1.0, pi8=float(section["pi8"]), pi18=pi18, pi19=pi19, pi20=section["pi20"], pi21=pi21,
                 pulse=pulse)


def linearised_rectangular(pi18: float, pi19) -> np.ndarray:
    """Least Pi21 of the linearised block under the rectangular pulse (duration ``T_p``: ``p t_d = Pi19``).

    Parameters
    ----------
    pi18 : float
        ``b/h = tan(alpha)``.
    pi19 : float or array_like
        ``p T_p``.

    Returns
    -------
    numpy.ndarray
        :func:`isoslide.model.rocking.rectangular_overturn_ratio` gives ``beta_c = a/(g alpha) = 1/(1 -
        exp(-Pi19))``; in Pi21 (``a/(g tan(alpha))``) that is ``beta_c alpha / tan(alpha)``.
    """
    alpha = math.atan(pi18)
    return np.array([rectangular_overturn_ratio(float(x)) for x in np.atleast_1d(pi19)]) * alpha / pi18


def spectra_study(settings: Mapping, solve_blocks=None) -> xr.Dataset:
    """The overturning spectra: least Pi21 that overturns the block, per pulse, Pi3 and 1/Pi19.

    The scan (:func:`scan_grid`) runs upwards, one grid amplitude at a time for every curve not yet
    overturned, and stops each curve at its first overturning amplitude; the bracket below it is
    bisected geometrically (midpoint ``sqrt(lo hi)``) until ``hi/lo <= 1 + tolerance``, every
    curve's midpoints solved together.

    Parameters
    ----------
    settings : mapping
        :func:`rocking_settings` of a complete configuration.
    solve_blocks : callable, optional
        ``solve_blocks(scenes, rtol=...)`` returning :class:`Outcomes`; default :func:`solve_blocks`.

    Returns
    -------
    xarray.Dataset
        Dimensions ``pulse, pi3, pi19`` (``pi19`` in the order of increasing ``inverse_pi19 =
        1/Pi19``) and ``pi21`` (the scan): ``theta_max_over_alpha``, ``overturned``, ``pi1`` and
        ``solve_status`` of the scan (NaN / -1 above a curve's first overturning amplitude: not
        solved); per curve ``pi21_overturn`` (least overturning Pi21 found: the bracket's upper end),
        ``pi21_survive`` (its lower end, which does not overturn), ``theta_max_over_alpha_survive``
        (the peak rotation there), ``bracket_status`` (:data:`BRACKET_STATUS`), ``bisection_steps``
        and ``isolation_ratio`` (``pi21_overturn`` over the fixed base's, ``Pi3 = 0``); per ``pi19``
        ``pi21_linearised_rectangular`` (:func:`linearised_rectangular`).
    """
    solve = _solver(solve_blocks)
    sec = check_spectra(settings["rocking"]["spectra"])
    rtol = settings["solver"]["rtol"]
    pulses, pi3 = sec["pulses"], np.array(sec["pi3"])
    inv = np.array(sec["inverse_pi19"])
    pi19 = 1.0 / inv
    grid = scan_grid(sec)
    shape = (len(pulses), pi3.size, pi19.size)
    G_ = grid.size
    theta = np.full(shape + (G_,), np.nan)
    pi1 = np.full(shape + (G_,), np.nan)
    over = np.full(shape + (G_,), -1, np.int8)
    status = np.full(shape + (G_,), -1, np.int8)
    first = np.full(shape, -1, np.int64)
    curves = list(np.ndindex(shape))

    def scenes_of(idx, amplitudes):
        return [spectra_scene(sec, pulses[p], float(pi3[b]), float(pi19[x]), float(a))
                for (p, b, x), a in zip(idx, amplitudes, strict=True)]

    n_solves = 0
    active = list(curves)
    for g in range(G_):
        if not active:
            break
        out = solve(scenes_of(active, [grid[g]] * len(active)), rtol=rtol)
        n_solves += len(active)
        still = []
        for k, c in enumerate(active):
            theta[c + (g,)], pi1[c + (g,)] = out.theta_max[k], out.pi1[k]
            status[c + (g,)] = out.status[k]
            over[c + (g,)] = int(bool(out.overturned[k])) if out.status[k] == 0 else -1
            if out.status[k] == 0 and out.overturned[k]:
                first[c] = g
            else:
                still.append(c)
        active = still

    lo, hi = np.full(shape, np.nan), np.full(shape, np.nan)
    theta_lo = np.full(shape, np.nan)
    bracket = np.zeros(shape, np.int8)
    steps = np.zeros(shape, np.int32)
    for c in curves:
        g = first[c]
        if g < 0:
            bracket[c] = 2
        elif g == 0:
            bracket[c], hi[c] = 1, grid[0]
        else:
            hi[c], lo[c], theta_lo[c] = grid[g], grid[g - 1], theta[c + (g - 1,)]
            bracket[c] = 0 if status[c + (g - 1,)] == 0 else 3
    tol = sec["tolerance"]
    while True:
        todo = [c for c in curves if bracket[c] == 0 and hi[c] / lo[c] > 1.0 + tol]
        if not todo:
            break
        mid = [math.sqrt(lo[c] * hi[c]) for c in todo]
        out = solve(scenes_of(todo, mid), rtol=rtol)
        n_solves += len(todo)
        for k, c in enumerate(todo):
            steps[c] += 1
            if out.status[k] != 0:
                bracket[c] = 3
            elif out.overturned[k]:
                hi[c] = mid[k]
            else:
                lo[c], theta_lo[c] = mid[k], out.theta_max[k]

    alpha = math.atan(sec["pi18"])
    e = sec["pi20"] if sec["pi20"] is not None else housner_restitution(alpha)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = hi / hi[:, :1, :]
    one = {"units": "1"}
    ds = xr.Dataset(coords={
        "pulse": ("pulse", np.array(pulses, dtype=object), {"long_name": "pulse shape (isoslide.pulses)"}),
        "pi3": ("pi3", pi3, pi_attrs("pi3")),
        "pi19": ("pi19", pi19, pi_attrs("pi19")),
        "pi21": ("pi21", grid, {**pi_attrs("pi21"), "comment": "the coarse scan, geometrically spaced"}),
    })
    ds.coords["inverse_pi19"] = ("pi19", inv, {"long_name": "1/Pi19 = 1/(p T_p): the spectra's abscissa", **one})
    ds.coords["pi2"] = ("pi21", sec["mu_s"] / (sec["pi18"] * grid),
                        {**pi_attrs("pi2"), "comment": "mu_s / (Pi18 Pi21): the block's friction over a_p/g"})
    for g, v in (("pi18", sec["pi18"]), ("pi20", e), ("pi4", sec["pi4"]), ("pi5", 1.0), ("pi8", sec["pi8"])):
        ds.coords[g] = ((), float(v), pi_attrs(g))
    ds.coords["pi4"].attrs["comment"] = "on the isolated floors (Pi3 > 0); 0 on the fixed base"
    d4 = ("pulse", "pi3", "pi19", "pi21")
    not_solved = "NaN above the curve's first overturning amplitude (not solved) and where unresolved (solve_status)"
    ds["theta_max_over_alpha"] = (d4, theta / alpha, {**THETA_ATTRS, "comment": THETA_ATTRS["comment"] + "; "
                                                      + not_solved})
    ds["overturned"] = (d4, over, {"long_name": "the block overturned", **_flags(("not_solved", "stood", "overturned"),
                                                                                -1)})
    ds["pi1"] = (d4, pi1, {**pi_attrs("pi1"), "comment": "peak sliding of the block's base; " + not_solved})
    ds["solve_status"] = (d4, status, {"long_name": "outcome of the solve",
                                       **_flags(("not_solved",) + SOLVE_STATUS, -1)})
    d3 = ("pulse", "pi3", "pi19")
    ds["pi21_overturn"] = (d3, hi, {"long_name": "least Pi21 = a_p/(g tan alpha) found to overturn the block", **one,
                                    "comment": "upper end of the first overturning bracket of the upward scan after "
                                               "bisection (bracket_status); NaN where nothing on the scan overturns"})
    ds["pi21_survive"] = (d3, lo, {"long_name": "largest Pi21 below pi21_overturn found not to overturn the block",
                                   **one, "comment": "lower end of the bisected bracket: pi21_overturn / pi21_survive "
                                                     "<= 1 + tolerance where bracket_status is bisected"})
    ds["theta_max_over_alpha_survive"] = (d3, theta_lo / alpha, {**THETA_ATTRS,
                                                                  "long_name": "theta_max / alpha at pi21_survive"})
    ds["bracket_status"] = (d3, bracket, {"long_name": "how the least overturning Pi21 was found",
                                          **_flags(BRACKET_STATUS)})
    ds["bisection_steps"] = (d3, steps, {"long_name": "bisection steps of the curve", **one})
    ds["isolation_ratio"] = (d3, ratio, {
        "long_name": "pi21_overturn on the floor of Pi3 over that on the fixed base (Pi3 = 0)", **one,
        "comment": "above 1: the isolated floor needs a stronger ground pulse to overturn the block (isolation "
                   "protects it); below 1: a weaker one (isolation exposes it); NaN where either threshold is "
                   "not on the scan"})
    ds["pi21_linearised_rectangular"] = ("pi19", linearised_rectangular(sec["pi18"], pi19), {
        "long_name": "least Pi21 of the linearised block under the rectangular pulse on a fixed base", **one,
        "comment": "beta_c alpha / tan(alpha), beta_c = 1/(1 - exp(-Pi19)) (isoslide.model.rocking."
                   "rectangular_overturn_ratio, pulse duration T_p); the exact block needs O(alpha^2) more"})
    ds.attrs.update({"tolerance": tol, "mu_s": sec["mu_s"], "alpha": alpha,
                     "restitution": "Housner" if sec["pi20"] is None else "given",
                     "scan": f"{G_} values of Pi21 from {grid[0]:g} to {grid[-1]:g}, geometric; each curve stopped at its "
                             "first overturning amplitude, whose bracket is bisected",
                     "n_solves": n_solves, "rtol": "default" if rtol is None else float(rtol)})
    return ds


def spectra_dataset(settings: Mapping, solve_blocks=None) -> xr.Dataset:
    """:func:`spectra_study` with CF global attributes and provenance."""
    ds = spectra_study(settings, solve_blocks=solve_blocks)
    extra = dict(ds.attrs)
    ds.attrs = global_attrs(
        title="isoslide: overturning spectra of a rocking block on a fixed base and on isolated floors",
        history=(f"isoslide.studies.rocking.spectra_study: {ds.sizes['pulse']} pulses x {ds.sizes['pi3']} Pi3 x "
                 f"{ds.sizes['pi19']} Pi19, {extra['n_solves']} solves (upward scan of Pi21, then bisection of the first "
                 "overturning bracket), each by isoslide.solve; no timestamps are stored"),
        config={"spectra": settings["rocking"]["spectra"], "solver": settings["solver"]},
        references_rocking="Zhang, J. and Makris, N. (2001): Rocking response of free-standing blocks under "
                           "cycloidal pulses, J. Eng. Mech. 127(5)", **extra)
    return ds


# ----------------------------------------------------------------------------------------------
# the sliding-or-rocking map
# ----------------------------------------------------------------------------------------------

def map_scene(section: Mapping, pi3: float, mu_s: float, pi18: float) -> Scene:
    """The scene of one map point.

    Parameters
    ----------
    section : mapping
        :func:`check_map` of ``rocking.map``: the pulse, ``a_p_over_g`` (``a_p/g``, dimensionless),
        ``pi19 = p T_p``, the isolator's ``pi4 = xi_b`` and ``pi8 = m_EC/M_b``.
    pi3 : float
        ``T_b/T_p``; 0 = fixed base.
    mu_s : float
        Friction coefficient of the block, static = kinetic (``Pi5 = 1``).
    pi18 : float
        ``b/h``.

    Returns
    -------
    isoslide.Scene
        With ``Pi2 = mu_s / (a_p/g)``, ``Pi21 = (a_p/g) / Pi18`` and Housner's restitution.
    """
    a = float(section["a_p_over_g"])
    return Scene(pi2=mu_s / a, pi3=pi3, pi4=float(section["pi4"]) if pi3 > 0 else 0.0, pi5=1.0,
                 pi8=float(section["pi8"]), pi18=pi18, pi19=float(section["pi19"]), pi21=a / pi18,
                 pulse=section["pulse"])


def _response(modes: np.ndarray, over: np.ndarray, status: np.ndarray) -> np.ndarray:
    bit = {m: 1 << k for k, m in enumerate(BLOCK_MODES)}
    slid = (modes & bit["slide"]) > 0
    rocked = (modes & bit["rock"]) > 0
    both = ((modes & bit["slide-rock"]) > 0) | (slid & rocked)
    out = np.where(both, 3, np.where(rocked, 2, np.where(slid, 1, 0)))
    out = np.where(over, 4, out)
    return np.where(status == 0, out, -1).astype(np.int8)


def map_study(settings: Mapping, solve_blocks=None) -> xr.Dataset:
    """Which modes the block visits, how far it rocks and slides, over ``Pi3 x mu_s x b/h``.

    Parameters
    ----------
    settings : mapping
        :func:`rocking_settings`.
    solve_blocks : callable, optional
        As for :func:`spectra_study`.

    Returns
    -------
    xarray.Dataset
        Dimensions ``pi3, mu_s, pi18`` (and ``mode``): ``theta_max_over_alpha``, ``overturned``,
        ``pi1``, ``response`` (:data:`RESPONSES`), ``visited`` over ``mode`` (1 where the mode was
        visited), ``solve_status``; ``tips`` over ``mu_s, pi18`` (``mu_s > b/h``); coordinates ``pi2``
        (on ``mu_s``), ``pi21``, ``pi20`` (Housner's) and ``alpha`` (on ``pi18``).
    """
    solve = _solver(solve_blocks)
    sec = check_map(settings["rocking"]["map"])
    rtol = settings["solver"]["rtol"]
    pi3, mu, pi18 = np.array(sec["pi3"]), np.array(sec["mu_s"]), np.array(sec["pi18"])
    shape = (pi3.size, mu.size, pi18.size)
    scenes = [map_scene(sec, float(pi3[i]), float(mu[j]), float(pi18[k])) for i, j, k in np.ndindex(shape)]
    out = solve(scenes, rtol=rtol)
    theta = np.asarray(out.theta_max, float).reshape(shape)
    over = np.asarray(out.overturned, bool).reshape(shape)
    status = np.asarray(out.status, np.int8).reshape(shape)
    modes = np.asarray(out.modes, np.int8).reshape(shape)
    alpha = np.arctan(pi18)
    visited = np.stack([(modes >> k) & 1 for k in range(len(BLOCK_MODES))], axis=-1).astype(np.int8)
    one = {"units": "1"}
    a = sec["a_p_over_g"]
    ds = xr.Dataset(coords={
        "pi3": ("pi3", pi3, pi_attrs("pi3")),
        "mu_s": ("mu_s", mu, {"long_name": "friction coefficient of the block, static = kinetic (Pi5 = 1)", **one}),
        "pi18": ("pi18", pi18, pi_attrs("pi18")),
        "mode": ("mode", np.array(BLOCK_MODES, dtype=object), {"long_name": "mode of the contents"}),
    })
    ds.coords["pi2"] = ("mu_s", mu / a, {**pi_attrs("pi2"), "comment": "mu_s / (a_p/g)"})
    ds.coords["pi21"] = ("pi18", a / pi18, {**pi_attrs("pi21"), "comment": "(a_p/g) / Pi18"})
    ds.coords["pi20"] = ("pi18", np.array([housner_restitution(x) for x in alpha]),
                         {**pi_attrs("pi20"), "comment": "Housner's 1 - 3/2 sin^2(alpha)"})
    ds.coords["alpha"] = ("pi18", alpha, {"long_name": "slenderness angle alpha = atan(b/h)", "units": "rad"})
    for g, v in (("pi19", sec["pi19"]), ("pi4", sec["pi4"]), ("pi5", 1.0), ("pi8", sec["pi8"])):
        ds.coords[g] = ((), float(v), pi_attrs(g))
    ds.coords["pi4"].attrs["comment"] = "on the isolated floors (Pi3 > 0); 0 on the fixed base"
    d3 = ("pi3", "mu_s", "pi18")
    unresolved = "NaN where unresolved (solve_status)"
    ds["theta_max_over_alpha"] = (d3, theta / alpha, {**THETA_ATTRS, "comment": THETA_ATTRS["comment"] + "; "
                                                      + unresolved})
    ds["overturned"] = (d3, over.astype(np.int8), {"long_name": "the block overturned",
                                                   **_flags(("stood", "overturned"))})
    ds["pi1"] = (d3, np.asarray(out.pi1, float).reshape(shape), {**pi_attrs("pi1"), "comment":
                                                                  "peak sliding of the block's base; " + unresolved})
    ds["response"] = (d3, _response(modes, over, status), {
        "long_name": "what the block did", **_flags(("unresolved",) + RESPONSES, -1),
        "comment": "slide_and_rock: the slide-rock mode, or sliding and rocking in turn"})
    ds["visited"] = (d3 + ("mode",), visited, {"long_name": "the block visited the mode",
                                               **_flags(("no", "yes"))})
    ds["solve_status"] = (d3, status, {"long_name": "outcome of the solve", **_flags(SOLVE_STATUS)})
    ds["tips"] = (("mu_s", "pi18"), (mu[:, None] > pi18[None, :]).astype(np.int8), {
        "long_name": "the block tips before it can slide: mu_s > b/h (isoslide.Scene.tips)",
        **_flags(("slides_only", "can_tip"))})
    ds.attrs.update({"pulse": sec["pulse"], "a_p_over_g": a, "restitution": "Housner",
                     "rtol": "default" if rtol is None else float(rtol)})
    return ds


def map_dataset(settings: Mapping, solve_blocks=None) -> xr.Dataset:
    """:func:`map_study` with CF global attributes and provenance."""
    ds = map_study(settings, solve_blocks=solve_blocks)
    extra = dict(ds.attrs)
    n = int(np.prod([ds.sizes[d] for d in ("pi3", "mu_s", "pi18")]))
    ds.attrs = global_attrs(
        title="isoslide: sliding or rocking, the modes a block visits over its friction and aspect ratio",
        history=(f"isoslide.studies.rocking.map_study: {n} scenes ({ds.sizes['pi3']} Pi3 x {ds.sizes['mu_s']} mu_s x "
                 f"{ds.sizes['pi18']} b/h), each solved by isoslide.solve; no timestamps are stored"),
        config={"map": settings["rocking"]["map"], "solver": settings["solver"]}, **extra)
    return ds


# ----------------------------------------------------------------------------------------------
# the overturning fragility
# ----------------------------------------------------------------------------------------------

STUCK_FRICTION = 1.0e3
"""Friction coefficient of the contents that never slide in the solve that gives the floor's motion."""


def fragility_records(section: Mapping) -> list:
    """The records of the fragility study: the ``component`` of the suite's first ``motions`` ground motions.

    Parameters
    ----------
    section : mapping
        :func:`check_fragility` of ``rocking.fragility``.

    Raises
    ------
    ValueError
        Naming ``rocking.fragility.<key>``: a suite that cannot be read, fewer ground motions than
        ``motions``, a ground motion without the component.
    """
    sec = section
    try:
        motions = _suite(sec["suite"])
    except (ValueError, OSError, LookupError) as err:
        raise ValueError(f"rocking.fragility.suite = {sec['suite']!r} cannot be read: {err}") from None
    if len(motions) < sec["motions"]:
        raise ValueError(f"rocking.fragility.motions = {sec['motions']!r} exceeds the {len(motions)} ground motions of "
                         f"suite {sec['suite']!r}; allowed: 2 <= motions <= {len(motions)}")
    out = []
    for gm in motions[:sec["motions"]]:
        rec = gm.components.get(sec["component"])
        if rec is None:
            raise ValueError(f"rocking.fragility.component = {sec['component']!r}: ground motion {gm.name!r} of suite "
                             f"{sec['suite']!r} has none; allowed: {list(gm.components)}")
        out.append(rec)
    return out


def _floor_ratios(sec: Mapping, record, rtol) -> tuple[float, float]:
    """PFA/PGA and PFV/PGA (s) of the isolated slab under ``record`` (the stuck, linear system)."""
    pulse, pga, _ = scaled_pulse(record, "pga", 1.0)
    scene = Scene.from_physical(a_p=pga, T_p=1.0, M_b=sec["M_b"], T_b=sec["T_b"], xi_b=sec["xi_b"], m_ec=sec["mass"],
                                mu_s=STUCK_FRICTION, mu_k=STUCK_FRICTION, pulse=pulse)
    pfa, pfv = floor_peaks(solver.solve(scene, rtol=rtol, history=True), scene)
    return pfa / pga, pfv / pga


def overturning_fragility(settings: Mapping, solve_blocks=None) -> xr.Dataset:
    """Overturning of the block under recorded ground motions scaled to PGA stripes, and its fragility curves.

    Each record (the ``component`` of the suite's first ``motions`` ground motions) is scaled, as
    recorded, to each PGA level (:func:`isoslide.studies.fragility_study.scaled_pulse`) and drives
    the block (``b``, ``h``, ``restitution``, friction ``mu``, mass) on a fixed base and on an
    isolated slab (rigid building on a linear isolator of period ``T_b`` and damping ``xi_b``).  The
    intensity measures are PGA and PGV of the scaled record and PFA and PFV of the floor; on the
    isolated slab those of the slab without the block's feedback (its mass ratio is small): one
    solve per record of the stuck, linear system, scaled with the level.

    Curves ``P(theta_max/alpha > limit | IM) = Phi(ln(IM/theta)/beta)`` for each
    ``rotation_limits`` value and ``P(overturning | IM)`` (the last limit state, written
    ``(pi/2)/alpha``) are fitted by maximum likelihood (:func:`isoslide.studies.fragility.fit_lognormal`;
    PGA by stripe counts, the others one outcome per analysis) with a bootstrap over the records;
    unresolved analyses are left out of the fits.

    Parameters
    ----------
    settings : mapping
        :func:`rocking_settings`.
    solve_blocks : callable, optional
        As for :func:`spectra_study`.

    Returns
    -------
    xarray.Dataset
        Dimensions ``base, record, im_level``: ``theta_max_over_alpha``, ``overturned``, ``u_max``
        [m], ``solve_status``, ``pfa`` [m/s^2], ``pfv`` [m/s]; ``pga``, ``pgv`` over ``record,
        im_level``; the curves over ``base, limit_state, im`` (``theta``, ``beta``, their bootstrap
        bounds, ``fit_status``, ``n_boot_failed``) and ``n_exceeded`` over ``base, limit_state``.
    """
    solve = _solver(solve_blocks)
    sec = check_fragility(settings["rocking"]["fragility"])
    rtol = settings["solver"]["rtol"]
    records = fragility_records(sec)
    levels = np.array(sec["levels"])
    block = Block(sec["b"], sec["h"], sec["restitution"])
    alpha = block.alpha
    nr, nl = len(records), levels.size
    pga, pgv = np.zeros((nr, nl)), np.zeros((nr, nl))
    pfa, pfv = np.zeros((2, nr, nl)), np.zeros((2, nr, nl))
    scenes, lengths, pulses = [], [], {}
    for r, rec in enumerate(records):
        ratios = _floor_ratios(sec, rec, rtol)
        for j, level in enumerate(levels):
            pulses[r, j], pga[r, j], pgv[r, j] = scaled_pulse(rec, "pga", float(level))
            pfa[0, r, j], pfv[0, r, j] = pga[r, j], pgv[r, j]
            pfa[1, r, j], pfv[1, r, j] = ratios[0] * pga[r, j], ratios[1] * pga[r, j]
    for base in BASES:
        for r in range(nr):
            for j in range(nl):
                sc = Scene.from_physical(a_p=pga[r, j], T_p=1.0, M_b=sec["M_b"],
                                         T_b=0.0 if base == "fixed_base" else sec["T_b"],
                                         xi_b=sec["xi_b"], m_ec=sec["mass"], mu_s=sec["mu"], mu_k=sec["mu"],
                                         pulse=pulses[r, j], b=sec["b"], h=sec["h"], restitution=sec["restitution"])
                scenes.append(sc)
                lengths.append(sc.scale.length)
    shape = (len(BASES), nr, nl)
    out = solve(scenes, rtol=rtol)
    theta = np.asarray(out.theta_max, float).reshape(shape)
    over = np.asarray(out.overturned, bool).reshape(shape)
    status = np.asarray(out.status, np.int8).reshape(shape)
    u_max = (np.asarray(out.pi1, float) * np.array(lengths)).reshape(shape)
    ratio = theta / alpha
    limits = np.array(list(sec["rotation_limits"]) + [0.5 * math.pi / alpha])
    names = [f"rotation_{v:g}" for v in sec["rotation_limits"]] + ["overturning"]

    res = {k: np.full((2, limits.size, len(IM_NAMES)), np.nan)
           for k in ("theta", "beta", "theta_low", "theta_high", "beta_low", "beta_high", "log_likelihood")}
    fit_status = np.zeros((2, limits.size, len(IM_NAMES)), np.int8)
    failed = np.zeros((2, limits.size, len(IM_NAMES)), np.int32)
    n_exc = np.zeros((2, limits.size), np.int64)
    rec_names = np.array([rec.name for rec in records], dtype=object)
    ims = {"pga": pga, "pgv": pgv}
    for b in range(len(BASES)):
        ok = status[b] == 0
        groups = np.broadcast_to(rec_names[:, None], (nr, nl))[ok].astype(str)
        stripe = np.broadcast_to(np.arange(nl)[None, :], (nr, nl))[ok]
        values = {**ims, "pfa": pfa[b], "pfv": pfv[b]}
        for a, limit in enumerate(limits):
            exc = (over[b] if a == limits.size - 1 else ratio[b] > limit)[ok]
            n_exc[b, a] = int(exc.sum())
            for m, im in enumerate(IM_NAMES):
                if not exc.any() or exc.all():
                    fit_status[b, a, m] = 1 if not exc.any() else 2
                    continue
                if im == "pga":
                    n_j = np.bincount(stripe, minlength=nl)
                    z_j = np.bincount(stripe, weights=exc, minlength=nl).astype(int)
                    args = (levels[n_j > 0], z_j[n_j > 0], n_j[n_j > 0])
                    x = levels[stripe]
                else:
                    x = values[im][ok]
                    args = (x, exc, None)
                try:
                    fit = _fit.fit_lognormal(*args)
                except (ValueError, RuntimeError):  # not identifiable; RuntimeError: no convergence
                    fit_status[b, a, m] = 3
                    continue
                res["theta"][b, a, m], res["beta"][b, a, m] = fit.theta, fit.beta
                res["log_likelihood"][b, a, m] = fit.log_likelihood
                if sec["n_boot"] > 0:
                    try:
                        bi = _fit.bootstrap(x, exc, groups, n_boot=sec["n_boot"],
                                            seed=sec["seed"] + 7919 * (limits.size * b + a) + m, level=sec["level"])
                    except (ValueError, RuntimeError):
                        failed[b, a, m] = sec["n_boot"]
                        continue
                    res["theta_low"][b, a, m], res["theta_high"][b, a, m] = bi.theta_low, bi.theta_high
                    res["beta_low"][b, a, m], res["beta_high"][b, a, m] = bi.beta_low, bi.beta_high
                    failed[b, a, m] = bi.n_failed

    one = {"units": "1"}
    ds = xr.Dataset(coords={
        "base": ("base", np.array(BASES, dtype=object), {"long_name": "building: fixed base or isolated slab"}),
        "record": ("record", rec_names.astype(str), {"long_name": "record (one horizontal component, as recorded)"}),
        "im_level": ("im_level", levels, {"long_name": "PGA stripe the record was scaled to", "units": "m s-2"}),
        "limit_state": ("limit_state", limits, {
            "long_name": "limit of theta_max / alpha", **one,
            "comment": "exceeded when theta_max/alpha > limit; the last, (pi/2)/alpha, is overturning (exceeded "
                       "when the block overturned)"}),
        "im": ("im", np.array(IM_NAMES, dtype=object), {"long_name": "intensity measure"}),
    })
    ds.coords["limit_state_name"] = ("limit_state", np.array(names, dtype=object), {"long_name": "limit state"})
    ds.coords["im_units"] = ("im", np.array([IM_UNITS[k] for k in IM_NAMES], dtype=object),
                             {"long_name": "units of the intensity measure"})
    ds.coords["pi18"] = ((), sec["b"] / sec["h"], pi_attrs("pi18"))
    ds.coords["pi20"] = ((), block.e, {**pi_attrs("pi20"), "comment": "Housner's" if sec["restitution"] is None
                                       else "given"})
    d3 = ("base", "record", "im_level")
    unresolved = "NaN where unresolved (solve_status)"
    ds["theta_max_over_alpha"] = (d3, ratio, {**THETA_ATTRS, "comment": THETA_ATTRS["comment"] + "; " + unresolved})
    ds["overturned"] = (d3, over.astype(np.int8), {"long_name": "the block overturned",
                                                   **_flags(("stood", "overturned"))})
    ds["u_max"] = (d3, u_max, {"long_name": "peak sliding of the block's base relative to the floor", "units": "m",
                               "comment": unresolved})
    ds["solve_status"] = (d3, status, {"long_name": "outcome of the solve", **_flags(SOLVE_STATUS)})
    ds["pga"] = (("record", "im_level"), pga, {"long_name": "peak ground acceleration of the scaled record",
                                               "units": "m s-2"})
    ds["pgv"] = (("record", "im_level"), pgv, {"long_name": "peak ground velocity of the scaled record (exact "
                                                            "integral, linear between samples)", "units": "m s-1"})
    floor_note = ("fixed base: the ground's; isolated slab: the slab's without the block's feedback (the stuck, "
                  "linear system, one solve per record, scaled with the level)")
    ds["pfa"] = (d3, pfa, {"long_name": "peak absolute acceleration of the floor under the block", "units": "m s-2",
                           "comment": floor_note})
    ds["pfv"] = (d3, pfv, {"long_name": "peak absolute velocity of the floor under the block", "units": "m s-1",
                           "comment": floor_note})
    dims = ("base", "limit_state", "im")
    add_curves(ds, dims, res, fit_status, failed, u="theta_max/alpha",
               u_txt="m s-2 (pga, pfa) or m s-1 (pgv, pfv): see im_units", pct=f"{sec['level']:.0%}",
               resampled="records", extra={"log_likelihood": ("maximised log-likelihood of the fit", "1")})
    ds["n_exceeded"] = (("base", "limit_state"), n_exc, {"long_name": "analyses exceeding the limit state", **one})
    ds["fit_method"] = ("im", np.array(["stripes" if k == "pga" else "per analysis" for k in IM_NAMES], dtype=object),
                        {"long_name": "maximum likelihood on stripe counts or on one outcome per analysis"})
    ds.attrs.update({"suite": sec["suite"], "component": sec["component"], "b": sec["b"], "h": sec["h"],
                     "R": block.R, "alpha": alpha, "p": block.p(G), "mu": sec["mu"], "mass": sec["mass"],
                     "T_b": sec["T_b"], "xi_b": sec["xi_b"], "M_b": sec["M_b"], "seed": sec["seed"],
                     "n_boot": sec["n_boot"], "confidence_level": sec["level"],
                     "sources": "; ".join(sorted({r.licence for r in records if r.licence})),
                     "rtol": "default" if rtol is None else float(rtol)})
    return ds


def fragility_dataset(settings: Mapping, solve_blocks=None) -> xr.Dataset:
    """:func:`overturning_fragility` with CF global attributes and provenance."""
    ds = overturning_fragility(settings, solve_blocks=solve_blocks)
    extra = dict(ds.attrs)
    ds.attrs = global_attrs(
        title="isoslide: overturning fragility of a rocking block on a fixed base and on an isolated slab",
        history=(f"isoslide.studies.rocking.overturning_fragility: {ds.sizes['record']} records x {ds.sizes['im_level']} PGA "
                 f"stripes x {ds.sizes['base']} bases solved by isoslide.solve, fitted by maximum likelihood "
                 f"(isoslide.studies.fragility), {extra['n_boot']} bootstrap resamples of the records; no timestamps "
                 "are stored"),
        config={"fragility": settings["rocking"]["fragility"], "solver": settings["solver"]},
        references_fragility=REFERENCE_FRAGILITY, **extra)
    return ds


def write_pelicun(ds: xr.Dataset, path, json_path=None, base: str = "isolated") -> Path:
    """Write the overturning curves of ``base`` on PFA and PFV as a pelicun damage-model CSV.

    One limit state (overturning, one damage state), components :data:`PELICUN_COMPONENTS`
    (:func:`isoslide.studies.pelicun_export.write_damage_db`: PFA in g, PFV in m/s,
    ``Demand-Directional`` 0: assign them with direction 0, pelicun then feeds the larger floor
    demand of the directions times its non-directional multiplier, a conservative reading for a block
    that rocks in the plane of its smaller side); a curve the data could not identify is written
    with ``Incomplete = 1``.

    Parameters
    ----------
    ds : xarray.Dataset
        :func:`fragility_dataset`.
    path : str or os.PathLike
        The ``.csv``.
    json_path : str or os.PathLike, optional
        The companion ``.json`` of descriptions.
    base : {"isolated", "fixed_base"}
        Which building's curves.

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    if base not in BASES:
        raise ValueError(f"base = {base!r} is invalid; allowed: {BASES}")
    theta = ds["theta"].sel(base=base).isel(limit_state=[-1]).drop_vars("limit_state_name")
    beta = ds["beta"].sel(base=base).isel(limit_state=[-1]).drop_vars("limit_state_name")
    where = "an isolated slab" if base == "isolated" else "a fixed base"
    a = ds.attrs
    return write_damage_db(
        path, theta, beta, json_path=json_path, component_ids=PELICUN_COMPONENTS, incomplete="flag",
        description=f"{a['title']} ({a['source']})", short_name="isoslide rocking block",
        component_text=(f"Free-standing rigid block (half-width b = {a['b']:g} m, half-height h = {a['h']:g} m, "
                        f"friction {a['mu']:g}) on {where}, overturning"),
        comments=("Lognormal curve fitted by maximum likelihood (Baker 2015) to exact rocking analyses (isoslide) "
                  "under recorded ground motions scaled to PGA stripes"),
        limit_texts=["The block overturned"])


# ----------------------------------------------------------------------------------------------
# the pipeline's job
# ----------------------------------------------------------------------------------------------

def study_datasets(settings: Mapping, solve_blocks=None) -> dict:
    """Every dataset of the study: ``{name: dataset}`` in the order of :data:`DATASETS`.

    :func:`spectra_dataset`, :func:`map_dataset` and :func:`fragility_dataset` of ``settings``
    (:func:`rocking_settings`), each storing only its own subsection as ``isoslide_config``.
    """
    makers = (spectra_dataset, map_dataset, fragility_dataset)
    return {name: make(settings, solve_blocks=solve_blocks) for name, make in zip(DATASETS, makers, strict=True)}


def write_outputs(datasets: Mapping, *, spectra, map, fragility, csv, json) -> None:
    """Write the datasets of :func:`study_datasets` (netCDF) and the pelicun CSV and JSON (:func:`write_pelicun`).

    Parameters
    ----------
    datasets : mapping
        :func:`study_datasets`.
    spectra, map, fragility : str or os.PathLike
        The files of ``rocking_spectra``, ``rocking_map`` and ``rocking_fragility``.
    csv, json : str or os.PathLike
        The pelicun damage-model CSV and its JSON of descriptions.
    """
    for name, path in zip(DATASETS, (spectra, map, fragility), strict=True):
        write_netcdf(datasets[name], path)
    write_pelicun(datasets["rocking_fragility"], csv, json_path=json)


# ----------------------------------------------------------------------------------------------
# what the data say
# ----------------------------------------------------------------------------------------------

def _g(v: float) -> str:
    return f"{v:.3g}" if np.isfinite(v) else "none"


def spectra_summary(ds: xr.Dataset) -> list:
    """One row per curve: ``pulse, pi3, inverse_pi19, pi21_overturn, pi21_survive, bracket, isolation_ratio``."""
    rows = []
    for p in ds["pulse"].values:
        for b in ds["pi3"].values:
            for x in ds["pi19"].values:
                s = ds.sel(pulse=p, pi3=b, pi19=x)
                rows.append({"pulse": str(p), "pi3": float(b), "inverse_pi19": float(s["inverse_pi19"]),
                             "pi21_overturn": float(s["pi21_overturn"]), "pi21_survive": float(s["pi21_survive"]),
                             "bracket": BRACKET_STATUS[int(s["bracket_status"])],
                             "isolation_ratio": float(s["isolation_ratio"])})
    return rows


def rectangular_check(ds: xr.Dataset) -> dict | None:
    """The fixed-base rectangular-pulse curve against the linearised closed form.

    Returns
    -------
    dict or None
        ``rel_diff`` (per ``pi19``: ``pi21_overturn`` over the closed form, minus 1), ``max_abs``,
        ``alpha_squared``; None without a rectangular pulse.
    """
    if "rectangular" not in [str(p) for p in ds["pulse"].values]:
        return None
    exact = ds["pi21_overturn"].sel(pulse="rectangular", pi3=0.0).values
    closed = ds["pi21_linearised_rectangular"].values
    rel = exact / closed - 1.0
    return {"rel_diff": rel, "max_abs": float(np.nanmax(np.abs(rel))) if np.isfinite(rel).any() else math.nan,
            "alpha_squared": float(ds.attrs["alpha"]) ** 2}


def isolation_effect(ds: xr.Dataset) -> list:
    """Per pulse and isolated ``Pi3``: where isolation protects the block and where it exposes it.

    The isolated and fixed-base least overturning Pi21 at each ``1/Pi19``: their ratio above ``1 +
    VERDICT_FACTOR tolerance`` protects, below ``1 - VERDICT_FACTOR tolerance`` exposes; where only
    one of them overturns on the scan, that one is exposed.

    Returns
    -------
    list of dict
        ``pulse, pi3, protects, exposes, same`` (lists of 1/Pi19), ``only_isolated``,
        ``only_fixed`` (1/Pi19 where only that base overturns on the scan), ``neither``,
        ``ratio_min``, ``ratio_max`` (over the finite ratios) and ``at_min``, ``at_max`` (their 1/Pi19).
    """
    tol = VERDICT_FACTOR * float(ds.attrs["tolerance"])
    inv = ds["inverse_pi19"].values
    rows = []
    for p in ds["pulse"].values:
        fixed = ds["pi21_overturn"].sel(pulse=p, pi3=0.0).values
        for b in ds["pi3"].values[1:]:
            iso = ds["pi21_overturn"].sel(pulse=p, pi3=b).values
            r = iso / fixed
            row = {"pulse": str(p), "pi3": float(b), "protects": [], "exposes": [], "same": [], "only_isolated": [],
                   "only_fixed": [], "neither": []}
            for k, x in enumerate(inv):
                f_ok, i_ok = np.isfinite(fixed[k]), np.isfinite(iso[k])
                key = ("neither" if not (f_ok or i_ok) else "only_isolated" if not f_ok else "only_fixed" if not i_ok
                       else "protects" if r[k] > 1 + tol else "exposes" if r[k] < 1 - tol else "same")
                row[key].append(float(x))
            fin = np.isfinite(r)
            row["ratio_min"] = float(r[fin].min()) if fin.any() else math.nan
            row["ratio_max"] = float(r[fin].max()) if fin.any() else math.nan
            row["at_min"] = float(inv[fin][np.argmin(r[fin])]) if fin.any() else math.nan
            row["at_max"] = float(inv[fin][np.argmax(r[fin])]) if fin.any() else math.nan
            rows.append(row)
    return rows


def map_summary(ds: xr.Dataset) -> list:
    """Per ``Pi3``: how many (mu_s, b/h) points end in each response, and whether any block with mu_s <= b/h rocked.

    Returns
    -------
    list of dict
        ``pi3``, one count per :data:`RESPONSES` name, ``unresolved``, ``rocked_without_tipping``
        (points with ``mu_s <= b/h`` that visited rock or slide-rock: 0 by the physics),
        ``largest_theta_standing`` (largest theta_max/alpha of a block that stood) and
        ``largest_pi1``.
    """
    rows = []
    tips = ds["tips"].values.astype(bool)
    for b in ds["pi3"].values:
        s = ds.sel(pi3=b)
        resp = s["response"].values
        row = {"pi3": float(b), **{name: int(np.sum(resp == k)) for k, name in enumerate(RESPONSES)},
               "unresolved": int(np.sum(resp < 0))}
        rocked = (s["visited"].sel(mode="rock").values + s["visited"].sel(mode="slide-rock").values) > 0
        row["rocked_without_tipping"] = int(np.sum(rocked & ~tips))
        stood = (s["overturned"].values == 0) & (resp >= 0)
        th = s["theta_max_over_alpha"].values
        row["largest_theta_standing"] = float(np.max(th[stood])) if stood.any() else math.nan
        row["largest_pi1"] = float(np.nanmax(s["pi1"].values)) if np.isfinite(s["pi1"].values).any() else math.nan
        rows.append(row)
    return rows


def fragility_summary(ds: xr.Dataset) -> list:
    """One row per base, limit state and IM: ``theta``, ``beta``, bounds, ``status`` and exceedances."""
    rows = []
    for b in ds["base"].values:
        for k, ls in enumerate(ds["limit_state_name"].values):
            for im in ds["im"].values:
                s = ds.sel(base=b, im=im).isel(limit_state=k)
                rows.append({"base": str(b), "limit_state": str(ls), "im": str(im), "units": str(s["im_units"].values),
                             "theta": float(s["theta"]), "beta": float(s["beta"]),
                             "theta_low": float(s["theta_low"]), "theta_high": float(s["theta_high"]),
                             "status": FIT_STATUS[int(s["fit_status"])], "n_exceeded": int(s["n_exceeded"])})
    return rows


def _list(values) -> str:
    return ", ".join(f"{v:g}" for v in values)


def findings(spectra: xr.Dataset, map_ds: xr.Dataset, fragility: xr.Dataset) -> list:
    """The study's findings, each ``(title, text with its numbers)``, computed from the three datasets only."""
    out = []
    alpha = float(spectra.attrs["alpha"])
    tol = float(spectra.attrs["tolerance"])
    parts = []
    for p in spectra["pulse"].values:
        s = spectra.sel(pulse=p, pi3=0.0)
        thr = s["pi21_overturn"].values
        inv = s["inverse_pi19"].values
        fin = np.isfinite(thr)
        none = inv[~fin]
        txt = (f"{p}: from Π₂₁ = {_g(thr[fin][0]) if fin.any() else 'none'} at 1/Π₁₉ = "
               f"{inv[fin][0]:g} to {_g(thr[fin][-1])} at 1/Π₁₉ = {inv[fin][-1]:g}" if fin.any() else f"{p}: none")
        if none.size:
            txt += f"; no overturning up to Π₂₁ = {float(spectra['pi21'].values[-1]):g} at 1/Π₁₉ = {_list(none)}"
        parts.append(txt)
    rect = rectangular_check(spectra)
    rect_txt = ""
    if rect is not None and np.isfinite(rect["max_abs"]):
        rel = rect["rel_diff"]
        rect_txt = (f" The fixed-base rectangular-pulse curve lies {np.nanmin(rel):+.2%} to {np.nanmax(rel):+.2%} from the "
                    f"linearised closed form 1/(1 − exp(−Π₁₉)) (in Π₂₁ units), within α² = {rect['alpha_squared']:.3g} "
                    f"(α = {alpha:.4g} rad): " + ("yes" if rect["max_abs"] <= rect["alpha_squared"] else "no") + ".")
    out.append(("Overturning spectra on a fixed base",
                f"Least Π₂₁ = a_p/(g tan α) that overturns a block of b/h = {float(spectra['pi18']):g} on a fixed base, "
                f"bisected to a relative tolerance of {tol:g} after an upward scan: " + "; ".join(parts) + "." + rect_txt))

    lines = []
    for row in isolation_effect(spectra):
        bits = []
        for key, word in (("protects", "protects"), ("exposes", "exposes"), ("same", "makes no difference"),
                          ("only_isolated", "exposes (only the isolated floor overturns it on the scan)"),
                          ("only_fixed", "protects (only the fixed base overturns it on the scan)")):
            if row[key]:
                bits.append(f"{word} at 1/Π₁₉ = {_list(row[key])}")
        ratio = (f"; the ratio of the isolated to the fixed-base overturning Π₂₁ runs from {row['ratio_min']:.2f} "
                 f"(1/Π₁₉ = {row['at_min']:g}) to {row['ratio_max']:.2f} (1/Π₁₉ = {row['at_max']:g})"
                 if np.isfinite(row["ratio_min"]) else "")
        lines.append(f"{row['pulse']}, Π₃ = {row['pi3']:g}: isolation " + ", ".join(bits) + ratio)
    out.append(("Does isolation protect the block or expose it?",
                "Ratio of the least overturning Π₂₁ on an isolated floor (rigid building on a linear isolator, "
                f"ξ_b = {float(spectra['pi4']):g}) to that on the fixed base, per 1/Π₁₉ = 1/(p T_p) (above 1: the "
                f"isolated block needs a stronger ground pulse; the same within {VERDICT_FACTOR * tol:g}). "
                + "; ".join(lines) + "."))

    rows = map_summary(map_ds)
    lines = []
    for row in rows:
        counts = ", ".join(f"{row[name]} {name.replace('_', ' ')}" for name in RESPONSES if row[name])
        lines.append(f"Π₃ = {row['pi3']:g}: {counts}" + (f", {row['unresolved']} unresolved" if row["unresolved"] else "")
                     + f"; the largest θ_max/α of a block left standing {_g(row['largest_theta_standing'])}, the largest "
                       f"Π₁ {_g(row['largest_pi1'])}")
    never = sum(r["rocked_without_tipping"] for r in rows)
    n = map_ds.sizes["mu_s"] * map_ds.sizes["pi18"]
    out.append(("Sliding or rocking",
                f"Under one {map_ds.attrs['pulse']} pulse of a_p/g = {map_ds.attrs['a_p_over_g']:g} and Π₁₉ = "
                f"{float(map_ds['pi19']):g}, over {n} blocks (μ_s = {_list(map_ds['mu_s'].values)} × b/h = "
                f"{_list(map_ds['pi18'].values)}): " + "; ".join(lines) + f". Blocks with μ_s ≤ b/h that rocked: {never} "
                "(a block that cannot tip only slides)."))

    lines = []
    last = fragility["limit_state"].size - 1
    uplift = G * float(fragility["pi18"])       # g tan(alpha), m/s^2
    for b in fragility["base"].values:
        s = fragility.sel(base=b).isel(limit_state=last)
        parts = []
        for im in ("pga", "pfa", "pfv"):
            t = s.sel(im=im)
            if np.isfinite(float(t["theta"])):
                parts.append(f"{im.upper()} median {float(t['theta']):.3g} {t['im_units'].values} (β = "
                             f"{float(t['beta']):.2f})")
            else:
                parts.append(f"{im.upper()}: no curve ({FIT_STATUS[int(t['fit_status'])].replace('_', ' ')})")
        n_over = int(fragility["overturned"].sel(base=b).sum())
        n_all = int((fragility["solve_status"].sel(base=b) == 0).sum())
        pfa = float(s["theta"].sel(im="pfa"))
        if np.isfinite(pfa):
            parts.append(f"the PFA median is {pfa / uplift:.2f}× the uplift acceleration g tan α = {uplift:.3g} m/s²")
        for k in range(last):
            n_k = int(fragility["n_exceeded"].sel(base=b).isel(limit_state=k))
            parts.append(f"{n_k} analyses exceed θ_max/α = {float(fragility['limit_state'][k]):g}"
                         + (" (every one of them overturns)" if n_k == n_over else ""))
        lines.append(f"{str(b).replace('_', ' ')}: {n_over} of {n_all} analyses overturn; " + ", ".join(parts))
    t_fix = float(fragility["theta"].sel(base="fixed_base", im="pga").isel(limit_state=last))
    t_iso = float(fragility["theta"].sel(base="isolated", im="pga").isel(limit_state=last))
    ratio = (f" The isolated slab's median PGA of overturning is {t_iso / t_fix:.2f}× the fixed base's."
             if np.isfinite(t_fix) and np.isfinite(t_iso) else "")
    a = fragility.attrs
    out.append(("Overturning fragility under recorded ground motions",
                f"A block of b = {a['b']:g} m, h = {a['h']:g} m (α = {a['alpha']:.3f} rad, p = {a['p']:.2f} rad/s) under "
                f"{fragility.sizes['record']} records of {a['suite']} scaled to PGA = "
                f"{_list(fragility['im_level'].values)} m/s²; isolated slab T_b = {a['T_b']:g} s, ξ_b = {a['xi_b']:g}. "
                + "; ".join(lines) + "." + ratio))
    return out
