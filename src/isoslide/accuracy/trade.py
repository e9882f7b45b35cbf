"""The trade: error of Pi1 against a converged answer and cost, for every setting."""

from __future__ import annotations

import logging

import numpy as np
import xarray as xr

from ..solver import solve
from .scenes import SceneSet, scene_coords
from .settings import Setting, method_settings
from ..solver import warm_up
from .timing import PEER_MARGIN, STATUS, STATUS_ATTRS, peer_stop, run_setting

log = logging.getLogger(__name__)


def converged(entries, settings: dict, reference_idx=()) -> dict:
    """Converged answers: ``pi1_converged``, ``converged_spread``, ``peer_stop`` and ``pi1_reference``.

    ``peer_stop`` is where the peers stop on each scene (:func:`~isoslide.accuracy.timing.peer_stop`
    of the converged answer's settlement time).
    """
    n = len(entries)
    conv = np.full(n, np.nan)
    spread = np.full(n, np.nan)
    stop = np.full(n, np.nan)
    ref = np.full(n, np.nan)
    rtol = settings["converged_rtol"]
    H = settings["horizon"]
    for i, e in enumerate(entries):
        a = solve(e.scene, rtol=rtol, horizon=H, model="full")
        conv[i] = a.pi1
        stop[i] = peer_stop(e.scene, H, a.tau_end if a.settled else np.inf)
        b = solve(e.scene, rtol=rtol, horizon=H, model="full", max_step=0.01).pi1
        spread[i] = abs(a.pi1 - b) / a.pi1 if a.pi1 > 0 else abs(a.pi1 - b)
    for i in reference_idx:
        pi1, _, _, st = run_setting(Setting("reference converged", "reference", rtol), entries[i].scene,
                                    H, max_work=settings["peer_max_work"], stop=stop[i])
        ref[i] = pi1 if st == "ok" else np.nan
    return {"pi1_converged": conv, "converged_spread": spread, "peer_stop": stop, "pi1_reference": ref}


def rel_error(pi1, conv):
    """``|pi1 - conv| / conv`` elementwise (broadcast), nan where ``conv`` is not positive."""
    pi1 = np.asarray(pi1, dtype=float)
    conv = np.broadcast_to(np.asarray(conv, dtype=float), pi1.shape)
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.where(conv > 0, np.abs(pi1 - conv) / np.where(conv > 0, conv, 1.0), np.nan)
    return rel


def _setting_coords(sets) -> dict:
    return {
        "setting": ("setting", np.array([s.name for s in sets], dtype=str),
                    {"long_name": "method and accuracy setting", "units": "1"}),
        "method": ("setting", np.array([s.method for s in sets], dtype=str),
                   {"long_name": "solution method: exact (isoslide.solve), reference (plain SciPy "
                                 "solve_ivp event-driven), regularized (paper-style stiff spring, SciPy "
                                 "Radau), opensees (optional peer)", "units": "1"}),
        "rtol": ("setting", np.array([s.rtol for s in sets], dtype=float),
                 {"long_name": "tolerance handed to the method (isoslide: target relative error of Pi1; "
                               "SciPy peers: solve_ivp rtol)", "units": "1"}),
        "stiffness": ("setting", np.array([s.stiffness for s in sets], dtype=float),
                      {"long_name": "regularising stiffness K = k_r T_p^2 / m_EC (nan: not regularised)",
                       "units": "1"}),
    }


def measure_trade(entries, settings: dict, part: str | None = None) -> xr.Dataset:
    """Error and cost of every setting (of ``part``) on the scene set.

    The compiled solver's settings run on every scene, ``repeats`` times, interleaved
    (setting after setting, then the next repetition) so that they are timed side by side;
    the cost is the median.  The SciPy peers run on an evenly spread subset
    (``reference_scenes``/``regularized_scenes``) with ``peer_repeats``, each run bounded by
    ``peer_max_work`` right-hand-side evaluations (work, not wall-clock time: outcomes do not
    depend on the machine's load).

    Parameters
    ----------
    entries : SceneSet or list of Entry
    settings : dict
        :func:`~isoslide.accuracy.settings.settings_from` output.
    part : {None, "exact", "reference", "regularized"}
        Which method family to measure (``"exact"`` includes the reference peer).
    """
    if not isinstance(entries, SceneSet):
        entries = SceneSet(tuple(entries))
    sets = method_settings(settings, part)
    n, m = len(entries), len(sets)
    H = settings["horizon"]
    pi1 = np.full((m, n), np.nan)
    secs = np.full((m, n), np.nan)
    work = np.full((m, n), -1, dtype=np.int64)
    status = np.full((m, n), STATUS["not-run"], dtype=np.int8)
    ref_idx = entries.subset(settings["reference_scenes"])
    paper = [i for i, e in enumerate(entries) if e.scene.paper_model]   # the regularized peer's model
    reg_idx = [paper[k] for k in SceneSet(tuple(entries[i] for i in paper)).subset(settings["regularized_scenes"])]
    coulomb = [i for i, e in enumerate(entries) if e.scene.rate_independent]
    os_idx = [coulomb[k] for k in SceneSet(tuple(entries[i] for i in coulomb)).subset(settings["opensees_scenes"])]
    warm_up()
    extra = {"regularized_method": settings["regularized_method"]}
    conv = converged(entries, settings, ref_idx if part in (None, "exact", "reference") else ())
    exact_rows = [j for j, s in enumerate(sets) if s.method == "exact"]
    for i, e in enumerate(entries):
        runs = {j: [] for j in exact_rows}
        for _ in range(settings["repeats"]):
            for j in exact_rows:
                p, t, w, st = run_setting(sets[j], e.scene, H)
                runs[j].append(t)
                pi1[j, i], work[j, i], status[j, i] = p, w, STATUS[st]
        for j in exact_rows:
            secs[j, i] = float(np.median(runs[j]))
    for j, s in enumerate(sets):
        if s.method == "exact":
            continue
        idx = {"reference": ref_idx, "regularized": reg_idx, "opensees": os_idx}[s.method]
        for i in idx:
            ts = []
            for _ in range(settings["peer_repeats"]):
                p, t, w, st = run_setting(s, entries[i].scene, H, settings["peer_max_work"],
                                          stop=conv["peer_stop"][i], **extra)
                ts.append(t)
                if st != "ok":
                    break
            pi1[j, i], work[j, i], status[j, i] = p, w, STATUS[st]
            secs[j, i] = float(np.median(ts))
            log.info("%s scene %d (%s): pi1=%.10g %.3f s %s", s.name, i, entries[i].cls, p, secs[j, i], st)
    rel = rel_error(pi1, conv["pi1_converged"][None, :])
    abs_err = np.abs(pi1 - conv["pi1_converged"][None, :])
    coords = scene_coords(entries.entries)
    coords.update(_setting_coords(sets))
    ds = xr.Dataset(
        {
            "pi1": (("setting", "scene"), pi1, {"long_name": "Pi1 = u_max / (a_p T_p^2) of the setting",
                                                "units": "1"}),
            "rel_error": (("setting", "scene"), rel,
                          {"long_name": "relative error |Pi1 - Pi1_converged| / Pi1_converged "
                                        "(nan: not run, or the scene does not slide)", "units": "1"}),
            "abs_error": (("setting", "scene"), abs_err,
                          {"long_name": "absolute error |Pi1 - Pi1_converged|", "units": "1"}),
            "cost_seconds": (("setting", "scene"), secs,
                             {"long_name": "wall-clock time per scene (median over repetitions)",
                              "units": "s", "nondeterministic": "true",
                              "comment": "measured, not reproducible: the only non-deterministic "
                                         "kind of variable in this dataset"}),
            "work": (("setting", "scene"), work,
                     {"long_name": "work per scene: integrator steps (exact, incl. rejected and "
                                   "event-location steps) or right-hand-side evaluations (SciPy peers); "
                                   "-1 not run", "units": "1"}),
            "status": (("setting", "scene"), status, dict(STATUS_ATTRS)),
            "pi1_converged": ("scene", conv["pi1_converged"],
                              {"long_name": "converged Pi1: isoslide.solve at rtol=%g, model='full'"
                                            % settings["converged_rtol"], "units": "1"}),
            "converged_spread": ("scene", conv["converged_spread"],
                                 {"long_name": "relative change of the converged Pi1 when the step is "
                                               "capped at 0.01 T_p (a different step sequence)",
                                  "units": "1"}),
            "peer_stop": ("scene", conv["peer_stop"],
                          {"long_name": "time the peers stop at / T_p: the converged answer's settlement "
                                        "plus %g isolation periods (at least T_p), within the horizon"
                                        % PEER_MARGIN, "units": "1"}),
            "pi1_reference": ("scene", conv["pi1_reference"],
                              {"long_name": "Pi1 of the independent plain-SciPy reference solver at "
                                            "rtol=%g (nan: not run on this scene)"
                                            % settings["converged_rtol"], "units": "1"}),
        },
        coords=coords,
    )
    return ds


def summarize_trade(ds: xr.Dataset, default_rtol: float = 1e-6, error_floor: float = 1e-6) -> xr.Dataset:
    """Per-setting statistics over the sliding scenes each setting ran on; adds the default bound.

    Relative errors are summarised over every sliding scene (``error_*``) and over the scenes
    that slide at least ``error_floor`` (units of a_p T_p^2, ``error_*_significant``); below
    the floor the absolute error is summarised (``abs_error_max_small``): a slide of 1e-13
    a_p T_p^2 is below the integrator's absolute tolerance and its relative error is not
    controlled.
    """
    sl = ds["pi1_converged"] > 0
    big = ds["pi1_converged"] >= error_floor
    ok = ds["status"] == STATUS["ok"]
    e = ds["rel_error"].where(sl & ok)
    c = ds["cost_seconds"].where(ok)
    w = ds["work"].where(ok & (ds["work"] >= 0))
    out = ds.copy()
    q = lambda da, f: xr.apply_ufunc(lambda a: _nanq(a, f), da, input_core_dims=[["scene"]],  # noqa: E731
                                     vectorize=True)
    out["n_scenes"] = (ok).sum("scene").astype(np.int32).assign_attrs(
        long_name="scenes the setting ran on successfully", units="1")
    out["n_failed"] = ((ds["status"] == STATUS["error"]) | (ds["status"] == STATUS["over_budget"])).sum(
        "scene").astype(np.int32).assign_attrs(long_name="scenes with an error or over the work budget", units="1")
    out["error_median"] = q(e, 50).assign_attrs(long_name="median relative error of Pi1 over sliding scenes",
                                                units="1")
    out["error_p95"] = q(e, 95).assign_attrs(long_name="95th percentile of the relative error", units="1")
    out["error_max"] = q(e, 100).assign_attrs(long_name="largest relative error of Pi1 over sliding scenes",
                                              units="1")
    out["error_max_significant"] = q(e.where(big), 100).assign_attrs(
        long_name=f"largest relative error over scenes with Pi1 >= {error_floor:g}", units="1")
    out["error_median_significant"] = q(e.where(big), 50).assign_attrs(
        long_name=f"median relative error over scenes with Pi1 >= {error_floor:g}", units="1")
    out["abs_error_max_small"] = q(ds["abs_error"].where(ok & ~big), 100).assign_attrs(
        long_name=f"largest absolute error of Pi1 over scenes with Pi1 < {error_floor:g} "
                  f"(including those that do not slide)", units="1")
    out.attrs["error_floor"] = float(error_floor)
    fs = ((ds["abs_error"] > 0) & ~sl & ok).sum("scene").astype(np.int32)
    out["false_slides"] = fs.assign_attrs(long_name="scenes that do not slide but got Pi1 > 0", units="1")
    out["cost_median_seconds"] = q(c, 50).assign_attrs(long_name="median wall-clock cost per scene",
                                                       units="s", nondeterministic="true")
    out["work_median"] = q(w, 50).assign_attrs(long_name="median work per scene (see work)", units="1")
    # the same statistics on the subset every setting ran on, for a like-for-like comparison
    common = ok.all("setting") if ds.sizes["setting"] else ok.any("setting")
    out["common_scene"] = common.astype(np.int8).assign_attrs(
        long_name="scene on which every setting ran (like-for-like comparison)", units="1")
    out["error_max_common"] = q(e.where(common), 100).assign_attrs(
        long_name="largest relative error over the common sliding scenes", units="1")
    out["cost_median_common_seconds"] = q(c.where(common), 50).assign_attrs(
        long_name="median cost per scene over the common scenes", units="s", nondeterministic="true")
    names = [str(s) for s in ds["setting"].values]
    dname = f"exact rtol={default_rtol:.0e}"
    if dname in names:
        j = names.index(dname)
        out.attrs["default_setting"] = dname
        out.attrs["default_error_bound"] = float(out["error_max"].values[j])
        out.attrs["default_error_median"] = float(out["error_median"].values[j])
        out.attrs["default_error_bound_significant"] = float(out["error_max_significant"].values[j])
        out.attrs["default_abs_error_bound_small"] = float(out["abs_error_max_small"].values[j])
    return out


def _nanq(a, f):
    a = np.asarray(a, dtype=float)
    a = a[np.isfinite(a)]
    if a.size == 0:
        return np.nan
    return float(np.percentile(a, f))
