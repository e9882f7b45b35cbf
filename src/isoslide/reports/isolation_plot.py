"""Figures of the isolation studies (:mod:`isoslide.studies.isolation_study`), from their datasets only.

* ``isolation_bearings`` -- master curves Pi1(Pi2) of the friction pendulum (``iso_fp``) and the
  lead-rubber bearing (``iso_lrb``), one panel per Pi3, one curve per strength Pi9;
* ``isolation_flexible`` -- master curves over Pi12 = T_s/T_p, contents on the base and on the roof;
* ``isolation_rigid`` -- the map of the rigid-superstructure reduction's error over Pi12 and Pi2;
* ``isolation_design`` -- peak sliding over the contents' friction under linear, bilinear and
  friction-pendulum isolation of equal effective period and damping.

:func:`draw_all` renders them with the paper figures' style and deterministic writer
(:data:`isoslide.reports.figures.STYLE`).
"""

from __future__ import annotations

import logging
from pathlib import Path

import numpy as np

from ..datasets import open_dataset
from .figures import LABELS, WIDTH, _colors, _fixed_text, stems_drawer, master_curves

log = logging.getLogger(__name__)

FIGURES = ("isolation_bearings", "isolation_flexible", "isolation_rigid", "isolation_design")
"""Figure names (file stems) drawn by :func:`draw_all`."""


SYSTEM_LABELS = {"linear": "linear (rubber + viscous)", "bilinear": "bilinear (lead-rubber)",
                 "friction_pendulum": "friction pendulum"}


def _open(d):
    return open_dataset(d) if isinstance(d, (str, Path)) else d


def _family_panels(axs, ds, family, head):
    """One panel per Pi3 with a curve per value of ``family``; the Pi2 axis ends past the last sliding."""
    for k, (ax, pi3) in enumerate(zip(axs, ds["pi3"].values, strict=True)):
        sub = master_curves(ax, ds, family, select={"pi3": float(pi3)})
        slides = np.asarray(sub["pi1"].values > 0).reshape(-1, sub.sizes["pi2"]).any(axis=0)
        if slides.any():
            last = float(sub["pi2"].values[np.flatnonzero(slides)[-1]])
            ax.set_xlim(0.0, min(float(sub["pi2"].max()), 1.15 * last + 0.02))
        ax.set_title(rf"{head}, $\Pi_3 = {float(pi3):g}$", fontsize=8)
        if k:
            ax.set_ylabel("")
        if k < len(axs) - 1:
            ax.get_legend().remove()
    return sub


def bearings(datasets):
    """Friction pendulum (top row) and lead-rubber bearing (bottom row), one panel per Pi3."""
    import matplotlib.pyplot as plt

    fp, lrb = _open(datasets["iso_fp"]), _open(datasets["iso_lrb"])
    n = max(fp.sizes["pi3"], lrb.sizes["pi3"])
    fig, axs = plt.subplots(2, n, figsize=(WIDTH, 5.4), squeeze=False, layout="constrained")
    fig.get_layout_engine().set(rect=(0, 0.06, 1, 0.94))
    notes = []
    for row, (ds, head) in enumerate(((fp, "friction pendulum"), (lrb, "lead-rubber"))):
        sub = _family_panels(axs[row][: ds.sizes["pi3"]], ds, "pi9", head)
        for ax in axs[row][ds.sizes["pi3"]:]:
            ax.set_visible(False)
        notes.append(f"{head}: " + _fixed_text(sub, skip=("pi3",)) + rf", $\Pi_{{10}} = {float(sub['pi10']):g}$")
    fig.text(0.01, 0.005, "Fixed, " + "\n".join(notes), fontsize=6.3, color="0.25", ha="left", va="bottom")
    caption = (f"Isolation bearings. Master curves Pi1(Pi2) of a friction pendulum (top; sliding bearing "
               f"with true stick, Pi10 = 0, strength Pi9 = mu_b g/a_p = {_list(fp['pi9'])}, xi_b = "
               f"{float(fp['pi4']):g}) and a lead-rubber bearing (bottom; bilinear, Pi9 = Q_d/(M_b a_p) = "
               f"{_list(lrb['pi9'])}, Pi10 = D_y/(a_p T_p^2) = {float(lrb['pi10']):g}, xi_b = "
               f"{float(lrb['pi4']):g}) at Pi3 = T_b/T_p = {_list(fp['pi3'])} (T_b of the post-yield "
               f"stiffness); {fp.attrs.get('pulse', '')} pulse, Coulomb contents, Pi8 = {float(fp['pi8']):g}.")
    return fig, caption


def flexible(datasets):
    """Pi1(Pi2) over Pi12, contents on the base (top) and the roof (bottom), one panel per Pi3."""
    import matplotlib.pyplot as plt

    base, roof = _open(datasets["iso_flex_base"]), _open(datasets["iso_flex_roof"])
    n = base.sizes["pi3"]
    fig, axs = plt.subplots(2, n, figsize=(WIDTH, 5.4), squeeze=False, layout="constrained")
    fig.get_layout_engine().set(rect=(0, 0.04, 1, 0.96))
    for row, (ds, head) in enumerate(((base, "base"), (roof, "roof"))):
        sub = _family_panels(axs[row], ds, "pi12", f"contents on the {head}")
    fig.text(0.01, 0.005, "Fixed: " + _fixed_text(sub, skip=("pi3",)) +
             rf", $\Pi_{{11}} = {float(sub['pi11']):g}$, $\Pi_{{13}} = \xi_s = {float(sub['pi13']):g}$",
             fontsize=6.3, color="0.25", ha="left", va="bottom")
    caption = (f"Flexible superstructure. Master curves Pi1(Pi2) for Pi12 = T_s/T_p = {_list(base['pi12'])} "
               f"(0: the paper's rigid superstructure) with the contents on the base slab (top) and on the "
               f"roof (bottom); Pi3 = {_list(base['pi3'])}, linear isolator xi_b = {float(sub['pi4']):g}, "
               f"superstructure mass fraction Pi11 = m_st/M_b = {float(sub['pi11']):g}, damping xi_s = "
               f"{float(sub['pi13']):g}; {base.attrs.get('pulse', '')} pulse, Coulomb contents.")
    return fig, caption


def rigid(datasets):
    """Map of the rigid reduction's relative error over Pi12 (rows) and Pi2 (columns)."""
    import matplotlib.pyplot as plt
    from matplotlib.colors import BoundaryNorm

    ds = _open(datasets["isolation_rigid"])
    tol = float(ds.attrs["tolerance"])
    floors, pi3s = ds["floor"].values, ds["pi3"].values
    fig, axs = plt.subplots(len(floors), len(pi3s), figsize=(WIDTH, 2.4 * len(floors) + 0.4), squeeze=False,
                            layout="constrained")
    bounds = [-np.inf, -1.0, -0.3, -tol, tol, 0.3, 1.0, np.inf]
    finite = [-3.0, -1.0, -0.3, -tol, tol, 0.3, 1.0, 3.0]
    cmap = plt.get_cmap("RdBu_r", len(bounds) - 1)
    norm = BoundaryNorm(finite, cmap.N)
    pi2 = ds["pi2"].values
    pi12 = ds["pi12"].values
    mesh = None
    for i, floor in enumerate(floors):
        for j, pi3 in enumerate(pi3s):
            ax = axs[i][j]
            err = ds["rel_error"].sel(floor=floor, pi3=pi3).values
            slides = (ds["pi1"].sel(floor=floor, pi3=pi3).values > 0) | \
                     (ds["pi1_rigid"].sel(floor=floor, pi3=pi3).values[None, :] > 0)
            shown = np.where(slides, np.clip(err, -2.99, 2.99), np.nan)
            mesh = ax.pcolormesh(pi2, np.arange(pi12.size), shown, cmap=cmap, norm=norm, shading="nearest")
            ax.set_yticks(np.arange(pi12.size), [f"{v:g}" for v in pi12])
            ax.set_xlabel(LABELS["pi2"])
            ax.set_ylabel(LABELS["pi12"] if j == 0 else "")
            ax.set_title(rf"contents on the {floor}, $\Pi_3 = {float(pi3):g}$", fontsize=8)
            ax.grid(False)
            ax.set_facecolor("0.82")
    cb = fig.colorbar(mesh, ax=axs.ravel().tolist(), shrink=0.9, pad=0.02)
    cb.set_label(r"$(\Pi_1^{rigid} - \Pi_1)/\Pi_1$ (grey: no sliding)")
    caption = (f"Where the rigid-superstructure reduction holds. Relative error (Pi1_rigid - Pi1)/Pi1 of the "
               f"paper's Fig. 1-b answer (Pi12 = 0) against the flexible building, over Pi12 = T_s/T_p and "
               f"Pi2; the pale band is |error| <= {tol:g}, red: the rigid model overestimates, blue: it "
               f"underestimates; grey: neither slides. Pi11 = {float(ds['pi11']):g}, xi_s = "
               f"{float(ds['pi13']):g}, xi_b = {float(ds['pi4']):g}.")
    return fig, caption


def design(datasets):
    """u_max over mu_k, one panel per excitation, one curve per system."""
    import matplotlib.pyplot as plt

    ds = _open(datasets["isolation_design"])
    exc = ds["excitation"].values
    ncol = min(4, exc.size)
    nrow = int(np.ceil(exc.size / ncol))
    fig, axs = plt.subplots(nrow, ncol, figsize=(WIDTH, 1.9 * nrow + 0.5), squeeze=False, layout="constrained")
    colors = _colors(ds.sizes["system"])
    for k, e in enumerate(exc):
        ax = axs.ravel()[k]
        for c, s in zip(colors, ds["system"].values, strict=True):
            ax.plot(ds["mu_k"].values, ds["u_max"].sel(system=s, excitation=e).values * 100.0, color=c,
                    label=SYSTEM_LABELS.get(str(s), str(s)))
        ax.set_title(_excitation_title(ds, e), fontsize=7)
        ax.set_xlabel(r"$\mu_k$")
        if k % ncol == 0:
            ax.set_ylabel(r"$u_{max}$ [cm]")
        ax.set_ylim(bottom=0.0)
    for ax in axs.ravel()[exc.size:]:
        ax.set_visible(False)
    axs.ravel()[0].legend(loc="upper right", fontsize=6)
    caption = (f"Which isolation protects contents best. Peak sliding u_max of the contents against their "
               f"friction coefficient mu_k under a linear, a bilinear (D_y = {ds.attrs['D_y_bilinear']:g} m) and "
               f"a friction-pendulum isolator designed to the same T_eff = {ds.attrs['T_eff_target']:g} s and "
               f"beta_eff = {ds.attrs['beta_eff_target']:g} at D = {ds.attrs['D']:g} m (ASCE 7 / AASHTO "
               f"linearisation); pulses at {float(ds['a_p'][0]) / 9.80665:.2g} g and records as recorded.")
    return fig, caption


PULSE_TITLES = {"ricker": "Ricker", "antisymmetric_ricker": "antisymmetric Ricker"}


def _excitation_title(ds, e) -> str:
    """``Ricker, T_p = 1 s`` for a pulse, the record's name with spaces for a record."""
    sub = ds.sel(excitation=e)
    if str(sub["kind"].values) == "pulse":
        shape = str(e).split(" ")[0]
        return rf"{PULSE_TITLES.get(shape, shape.replace('_', ' '))}, $T_p$ = {float(sub['T_p']):g} s"
    return str(e).replace("_", " ")


DRAWERS = {"isolation_bearings": bearings, "isolation_flexible": flexible, "isolation_rigid": rigid,
           "isolation_design": design}


def _list(da) -> str:
    return ", ".join(f"{float(v):g}" for v in np.asarray(da).ravel())


draw_all = stems_drawer("draw_all", FIGURES, "isolation figures", lambda name, data: (DRAWERS[name], (data,)),
                        "``iso_fp``, ``iso_lrb``, ``iso_flex_base``, ``iso_flex_roof``, ``isolation_rigid``, "
                        "``isolation_design``.", log)
