"""Model reductions: each one's error against the full model, and the saving it buys."""

from __future__ import annotations

import dataclasses
import time

import numpy as np
import xarray as xr

from ..scene import Scene
from ..solver import solve, solve_many
from .scenes import SceneSet, scene_coords
from ..solver import warm_up

NOSLIDE_COLUMN = 20
"""Scenes per base over which the no-slide shortcut's cost is amortised (a Pi2 column)."""

REDUCTIONS = ("fixed-base", "no-slide", "coulomb", "one-way", "settlement", "bearing-stuck", "bearing-elastic")
"""The model reductions measured, in the order of the ``reduction`` dimension."""
REDUCTION_TEXT = {
    "fixed-base": "Pi3 = 0: floor = ground (base not integrated); full model: the same scene with a "
                  "very stiff, damped base, Pi3 = 1e-3, xi_b = 0.1",
    "no-slide": "batch shortcut of solve_many: Pi1 = 0 without integrating the block when Pi2/Pi5 "
                "exceeds the stuck floor's peak demand (one demand per base, cost per scene amortised "
                "over a column of 20 Pi2 values); full model: solve(model='full') per scene",
    "coulomb": "rate-independent friction: the Stribeck terms are not evaluated; full model: "
               "solve(model='full')",
    "one-way": "the block's back-reaction on the base is dropped (Pi8 -> 0 in the base equation); "
               "isoslide takes it by itself only where its a-posteriori bound is under rtol/10 "
               "(red_taken); full model: solve(model='full') with the scene's Pi8",
    "settlement": "integration stops when no further sliding is possible; full model: followed to "
                  "the horizon (settle=False)",
    "bearing-stuck": "a sliding bearing proved never to slip runs as the paper's fixed base; full model: "
                     "the general building's kernel, solve(model='full')",
    "bearing-elastic": "a bilinear bearing proved never to yield runs as the paper's linear isolator of its "
                       "initial stiffness; full model: the general building's kernel, solve(model='full')",
}
"""What each reduction does and what it is compared with."""


def _full_variant(red: str, sc: Scene):
    """(scene, kwargs) of the full model for reduction ``red``, or None if not applicable."""
    if red == "fixed-base":
        if sc.pi3 != 0.0:
            return None
        return Scene(pi2=sc.pi2, pi3=1e-3, pi4=0.1, pi5=sc.pi5, pi6=sc.pi6, pi7=sc.pi7,
                     pi8=sc.pi8, pulse=sc.pulse), {"model": "full"}
    if red == "settlement":
        return sc, {"settle": False}
    if red == "one-way":
        return sc, {"model": "full"}
    return sc, {"model": "full"}


def measure_reductions(entries, settings: dict) -> xr.Dataset:
    """For each reduction and each scene it applies to: Pi1 and cost, reduced versus full.

    Both variants of a scene are timed side by side (interleaved, ``reduction_repeats``
    times, median).  A reduction applies to a scene when the solver actually takes it
    (by the facets of the model that ran: ``fixed-base``, ``coulomb``, ``one-way``; ``no-slide`` when
    :func:`isoslide.solve_many` answers without integrating; settlement on every scene
    that settles).
    """
    if not isinstance(entries, SceneSet):
        entries = SceneSet(tuple(entries))
    n, m = len(entries), len(REDUCTIONS)
    H = settings["horizon"]
    R = settings["reduction_repeats"]
    rtol = settings["default_rtol"]
    shape = (m, n)
    pr, pf = np.full(shape, np.nan), np.full(shape, np.nan)
    tr, tf = np.full(shape, np.nan), np.full(shape, np.nan)
    wr, wf = np.full(shape, -1, np.int64), np.full(shape, -1, np.int64)
    taken = np.zeros(shape, dtype=bool)
    warm_up()
    for i, e in enumerate(entries):
        sc = e.scene
        auto = solve(sc, rtol=rtol, horizon=H)
        fa = auto.facets
        slid = auto.pi1 > 0.0
        applies = {
            "fixed-base": fa.isolator == "fixed-base" and sc.paper_model,
            "coulomb": fa.friction == "coulomb" and slid,
            "one-way": sc.pi3 > 0 and sc.pi8 > 0 and sc.paper_model,
            "settlement": auto.settled,
            "bearing-stuck": fa.reduction == "bearing-stuck",
            "bearing-elastic": fa.reduction == "bearing-elastic",
        }
        batch = solve_many([sc], rtol=rtol, horizon=H)
        applies["no-slide"] = batch.facets[0].reduction == "demand-bound" and batch.n_steps[0] == 0
        taken[REDUCTIONS.index("one-way"), i] = (fa.coupling == "one-way" and fa.isolator != "fixed-base" and slid
                                                 and sc.pi8 > 0)
        taken[REDUCTIONS.index("fixed-base"), i] = applies["fixed-base"]
        taken[REDUCTIONS.index("coulomb"), i] = applies["coulomb"]
        taken[REDUCTIONS.index("no-slide"), i] = applies["no-slide"]
        taken[REDUCTIONS.index("settlement"), i] = applies["settlement"]
        for red in ("bearing-stuck", "bearing-elastic"):
            taken[REDUCTIONS.index(red), i] = applies[red]
        oneway_scene = dataclasses.replace(sc, pi8=0.0)
        for k, red in enumerate(REDUCTIONS):
            if not applies[red]:
                continue
            full_sc, kw = _full_variant(red, sc)
            t_red, t_full = [], []
            # the no-slide shortcut shares one stuck-demand computation per base: time it on a
            # column of NOSLIDE_COLUMN scenes (Pi2 above the threshold) as in a study grid
            column = [sc] + [dataclasses.replace(sc, pi2=sc.pi2 * (1.0 + 0.01 * q)) for q in range(1, NOSLIDE_COLUMN)]
            for _ in range(R):
                t0 = time.perf_counter()
                if red == "no-slide":
                    b = solve_many(column, rtol=rtol, horizon=H)
                    p_red, w_red = float(b.pi1[0]), int(b.n_steps[0])
                elif red == "one-way":
                    s = solve(oneway_scene, rtol=rtol, horizon=H, model="full")
                    p_red, w_red = s.pi1, s.n_steps
                else:
                    s = solve(sc, rtol=rtol, horizon=H)
                    p_red, w_red = s.pi1, s.n_steps
                t_red.append((time.perf_counter() - t0) / (len(column) if red == "no-slide" else 1))
                t0 = time.perf_counter()
                f = solve(full_sc, rtol=rtol, horizon=H, **kw)
                t_full.append(time.perf_counter() - t0)
            pr[k, i], pf[k, i] = p_red, f.pi1
            wr[k, i], wf[k, i] = w_red, f.n_steps
            tr[k, i], tf[k, i] = np.median(t_red), np.median(t_full)
    coords = scene_coords(entries.entries)
    coords["reduction"] = ("reduction", np.array(REDUCTIONS, dtype=str),
                           {"long_name": "model reduction made by isoslide.solve", "units": "1"})
    coords["reduction_text"] = ("reduction", np.array([REDUCTION_TEXT[r] for r in REDUCTIONS], dtype=str),
                                {"long_name": "what the reduction does and what it is compared with",
                                 "units": "1"})
    dims = ("reduction", "scene")
    with np.errstate(divide="ignore", invalid="ignore"):
        scale = np.maximum(np.abs(pf), 0.0)
        rel = np.where(scale > 0, np.abs(pr - pf) / np.where(scale > 0, scale, 1.0),
                       np.where(np.isfinite(pr), np.abs(pr - pf), np.nan))
    ds = xr.Dataset(
        {
            "red_pi1": (dims, pr, {"long_name": "Pi1 with the reduction (default rtol)", "units": "1"}),
            "red_pi1_full": (dims, pf, {"long_name": "Pi1 of the full model (default rtol)", "units": "1"}),
            "red_error": (dims, rel, {"long_name": "|Pi1_reduced - Pi1_full| / Pi1_full (absolute "
                                                   "difference where Pi1_full = 0; nan: not applicable)",
                                      "units": "1"}),
            "red_taken": (dims, taken.astype(np.int8),
                          {"long_name": "isoslide.solve (or solve_many) takes this reduction by itself on "
                                        "this scene at the default rtol", "units": "1"}),
            "red_work": (dims, wr, {"long_name": "integrator steps with the reduction (-1: n/a)", "units": "1"}),
            "red_work_full": (dims, wf, {"long_name": "integrator steps of the full model (-1: n/a)",
                                         "units": "1"}),
            "red_cost_seconds": (dims, tr, {"long_name": "wall-clock time with the reduction (median)",
                                            "units": "s", "nondeterministic": "true"}),
            "red_cost_full_seconds": (dims, tf, {"long_name": "wall-clock time of the full model (median)",
                                                 "units": "s", "nondeterministic": "true"}),
        },
        coords=coords,
    )
    return ds
