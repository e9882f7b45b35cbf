"""Figures of the isolation studies (:mod:`isoslide.studies.isolation_study`), from their datasets only.

* ``isolation_bearings`` -- master curves Pi1(Pi2) of the friction pendulum (``iso_fp``) and the
  lead-rubber bearing (``iso_lrb``), one panel per Pi3, one curve per strength Pi9;
* ``isolation_flexible`` -- master curves over Pi12 = T_s/T_p, contents on the base and on the roof;
* ``isolation_rigid`` -- the map of the rigid-superstructure reduction's error over Pi12 and Pi2;
* ``isolation_design`` -- peak sliding over the contents' friction under linear, bilinear and
  friction-pendulum isolation of equal effective period and damping;
* ``isolation_intensity`` -- the contents' peak sliding, the floor's peak acceleration and the
  bearing's displacement over the pulse's amplitude, under a lead-rubber bearing and friction
  pendulums of constant and speed-dependent friction (``isolation_bearings``).

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

FIGURES = ("isolation_bearings", "isolation_flexible", "isolation_rigid", "isolation_design", "isolation_intensity")
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


BEARING_STYLES = {"lead_rubber": {"color": 0, "ls": "-", "marker": "s", "label": "lead-rubber"},
                  "friction_pendulum": {"color": 1, "ls": "-", "marker": "o", "label": r"pendulum, constant $\mu$"},
                  "friction_pendulum_speed": {"color": 1, "ls": "--", "marker": "x",
                                              "label": r"pendulum, $\mu$ rising with speed"}}
"""Line of each isolator of the bearing study: the two pendulums share a colour, the speed-dependent one dashed."""


def intensity(datasets):
    """The bearing study over the pulse's intensity, two rows of panels per building.

    First row: u_max over a_p, one panel per mu_k; second row: the floor's peak acceleration, the
    bearing's displacement over D, and the speed-dependent pendulum's u_max and PFA over the constant one's.
    """
    import matplotlib.pyplot as plt
    from matplotlib.ticker import NullLocator

    ds = _open(datasets["isolation_bearings"])
    G = 9.80665
    mus, buildings = ds["mu_k"].values, ds["building"].values
    ncol = max(mus.size, 3)
    fig, axs = plt.subplots(2 * buildings.size, ncol, figsize=(WIDTH, 3.3 * buildings.size + 0.5), squeeze=False,
                            layout="constrained")
    colors = _colors(3)[:2]
    a_p, D = ds["a_p"].values, float(ds.attrs["D"])
    ticks = _log_ticks(a_p)

    def line(ax, iso, y, **kw):
        st = BEARING_STYLES.get(str(iso), {"color": 0, "ls": ":", "marker": ".", "label": str(iso)})
        ax.plot(a_p, y, color=colors[st["color"]], ls=st["ls"], marker=st["marker"], ms=3.0, lw=1.0,
                label=st["label"], **kw)

    for r, b in enumerate(buildings):
        sub = ds.sel(building=b)
        where = "slab (rigid)" if str(b) == "rigid" else "roof (flexible)"
        top, bottom = axs[2 * r], axs[2 * r + 1]
        for j, m in enumerate(mus):
            ax = top[j]
            for iso in ds["isolator"].values:
                line(ax, iso, sub["u_max"].sel(isolator=iso, mu_k=m).values * 100.0)
            ax.set_title(rf"{where}: $\mu_k = {float(m):g}$", fontsize=7)
            ax.set_ylabel(r"$u_{max}$ [cm]" if j == 0 else "")
            ax.set_ylim(bottom=0.0)
        for ax in top[mus.size:]:
            ax.set_visible(False)
        for iso in ds["isolator"].values:
            line(bottom[0], iso, sub["pfa"].sel(isolator=iso).values / G)
            line(bottom[1], iso, sub["bearing_disp"].sel(isolator=iso).values / D)
        bottom[0].set_ylabel("peak floor accel. [g]")
        bottom[0].set_title(f"{where}: floor", fontsize=7)
        bottom[0].set_ylim(bottom=0.0)
        bottom[1].axhline(1.0, color="0.6", lw=0.8, ls=":")
        bottom[1].set_ylabel(r"bearing displacement / $D$")
        bottom[1].set_title(f"{where}: bearing", fontsize=7)
        const, speed = sub.sel(isolator="friction_pendulum"), sub.sel(isolator="friction_pendulum_speed")
        ax = bottom[2]
        mcolors = _colors(mus.size + 1)
        for j, m in enumerate(mus):
            uc, us = const["u_max"].sel(mu_k=m).values, speed["u_max"].sel(mu_k=m).values
            ratio = np.where(uc > 0, us / np.where(uc > 0, uc, 1.0), np.nan)
            ax.plot(a_p, ratio, color=mcolors[j], marker="o", ms=3.0, lw=1.0, label=rf"$u_{{max}}$, $\mu_k = {float(m):g}$")
        ax.plot(a_p, speed["pfa"].values / const["pfa"].values, color="k", ls="--", lw=1.0, label="peak floor accel.")
        ax.axhline(1.0, color="0.6", lw=0.8, ls=":")
        ax.set_ylabel("speed-dependent / constant")
        ax.set_title(f"{where}: pendulums", fontsize=7)
        ax.legend(fontsize=5.5, loc="lower right")
        for ax in bottom[3:]:
            ax.set_visible(False)
        for ax in (*top[:mus.size], *bottom[:3]):
            ax.set_xscale("log")
            ax.set_xticks(ticks, [f"{v:g}" for v in ticks])
            ax.xaxis.set_minor_locator(NullLocator())     # the grid's a_p are the ticks
            ax.set_xlabel(r"$a_p$ [m/s$^2$]")
    axs[0][0].legend(fontsize=5.5, loc="upper left")
    fs = ds.sel(isolator="friction_pendulum_speed")
    caption = (f"What the bearing does to the contents, from service-level shaking to beyond the design. Peak sliding "
               f"u_max of Coulomb contents (mu_k = {_list(ds['mu_k'])}), peak floor acceleration and peak bearing "
               f"displacement against the amplitude a_p = {_list(ds['a_p'])} m/s^2 of a {ds.attrs['pulse']} pulse of "
               f"T_p = {ds.attrs['T_p']:g} s, under a lead-rubber bearing (D_y = {ds.attrs['D_y_bilinear']:g} m) and a "
               f"friction pendulum designed to the same T_eff = {ds.attrs['T_eff_target']:g} s and beta_eff = "
               f"{ds.attrs['beta_eff_target']:g} at D = {D:g} m (mu = {float(ds['Q_over_W'].sel(isolator='friction_pendulum')):.4f}, "
               f"R = {float(ds['R'].sel(isolator='friction_pendulum')):.2f} m), and that pendulum with friction rising "
               f"with speed (dashed: mu_slow = {float(fs['mu_slow']):.4f}, a = {float(fs['rate']):g} s/m); contents on "
               f"the slab of a rigid superstructure"
               + (f" and on the roof of a flexible one (Pi11 = {ds.attrs['pi11_flexible']:g}, Pi12 = T_s/T_p = "
                  f"{ds.attrs['pi12_flexible']:g}, xi_s = {ds.attrs['pi13_flexible']:g})" if "flexible" in buildings else "")
               + ". Last panel of each building: the speed-dependent pendulum's u_max and peak floor acceleration over "
               "the constant one's.")
    return fig, caption


def _log_ticks(values, spacing: float = 0.25) -> list:
    """Values to label on a log axis: the first, then each at least ``spacing`` decades past the last labelled."""
    out = []
    for v in np.asarray(values, dtype=float):
        if not out or np.log10(v / out[-1]) >= spacing - 1e-9:
            out.append(float(v))
    return out


PULSE_TITLES = {"ricker": "Ricker", "antisymmetric_ricker": "antisymmetric Ricker"}


def _excitation_title(ds, e) -> str:
    """``Ricker, T_p = 1 s`` for a pulse, the record's name with spaces for a record."""
    sub = ds.sel(excitation=e)
    if str(sub["kind"].values) == "pulse":
        shape = str(e).split(" ")[0]
        return rf"{PULSE_TITLES.get(shape, shape.replace('_', ' '))}, $T_p$ = {float(sub['T_p']):g} s"
    return str(e).replace("_", " ")


DRAWERS = {"isolation_bearings": bearings, "isolation_flexible": flexible, "isolation_rigid": rigid,
           "isolation_design": design, "isolation_intensity": intensity}


def _list(da) -> str:
    return ", ".join(f"{float(v):g}" for v in np.asarray(da).ravel())


draw_all = stems_drawer("draw_all", FIGURES, "isolation figures", lambda name, data: (DRAWERS[name], (data,)),
                        "``iso_fp``, ``iso_lrb``, ``iso_flex_base``, ``iso_flex_roof``, ``isolation_rigid``, "
                        "``isolation_design``, ``isolation_bearings``.", log)
