"""Figures of the isolation studies (:mod:`isoslide.studies.isolation_study`), from their datasets only.

* ``isolation_bearings`` -- master curves Pi1(Pi2) of the friction pendulum (``iso_fp``) and the
  lead-rubber bearing (``iso_lrb``), one panel per Pi3, one curve per strength Pi9;
* ``isolation_flexible`` -- master curves over Pi12 = T_s/T_p, contents on the base and on the roof;
* ``isolation_rigid`` -- the map of the rigid-superstructure reduction's error over Pi12 and Pi2;
* ``isolation_design`` -- peak sliding over the contents' friction under linear, bilinear and
  friction-pendulum isolation of equal effective period and damping;
* ``isolation_intensity`` -- the contents' peak sliding, the floor's peak acceleration and the
  bearing's displacement over the pulse's amplitude, under a lead-rubber bearing, friction
  pendulums of constant and speed-dependent friction and a triple friction pendulum, whose regime
  reached (I..V) and displacement capacity are marked (``isolation_bearings``).

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
                                              "label": r"pendulum, $\mu$ rising with speed"},
                  "triple_friction_pendulum": {"color": 2, "ls": "-", "marker": "^",
                                               "label": "triple pendulum (regime I-V marked)"}}
"""Line of each isolator of the bearing study: the two pendulums share a colour, the speed-dependent one dashed."""

TRIPLE = "triple_friction_pendulum"
ROMAN = {1: "I", 2: "II", 3: "III", 4: "IV", 5: "V"}


def _mark_regimes(ax, a_p, y, stage, capacity, color):
    """Roman numeral of the triple pendulum's regime above each point; ``capacity`` points as a cross at the top.

    ``stage`` and ``capacity`` per ``a_p``; where the bearing reached its capacity ``y`` is NaN and
    a cross at the top of the panel says so.
    """
    from matplotlib.transforms import blended_transform_factory

    if np.any(capacity):              # room at the top for the crosses
        lo, hi = ax.get_ylim()
        ax.set_ylim(lo, lo + 1.2 * (hi - lo))
    for a, v, st, cap in zip(a_p, y, stage, capacity, strict=True):
        if cap:
            tr = blended_transform_factory(ax.transData, ax.transAxes)
            ax.plot([a], [0.97], marker="X", ms=5.0, color=color, transform=tr, clip_on=False, ls="none")
            ax.text(a, 0.9, "cap.", transform=tr, fontsize=5.0, color=color, ha="center", va="top")
        elif st > 0 and np.isfinite(v):
            ax.annotate(ROMAN[int(st)], (a, v), textcoords="offset points", xytext=(0, 4), fontsize=5.0,
                        color=color, ha="center", va="bottom")


def intensity(datasets):
    """The bearing study over the pulse's intensity, two rows of panels per building.

    First row: u_max over a_p, one panel per mu_k (and the legend); second row: the floor's peak
    acceleration, the bearing's displacement over D, the speed-dependent pendulum's u_max and PFA over
    the constant one's, the triple pendulum's over the constant one's.  The triple pendulum's
    points carry the regime reached (roman numerals; its floor and displacement panels at the
    largest mu_k, the history's), a cross where it reached its displacement capacity.
    """
    import matplotlib.pyplot as plt
    from matplotlib.ticker import NullLocator

    ds = _open(datasets["isolation_bearings"])
    G = 9.80665
    mus, buildings = ds["mu_k"].values, ds["building"].values
    isolators = [str(i) for i in ds["isolator"].values]
    has_triple = TRIPLE in isolators
    ncol = max(mus.size + 1, 4 if has_triple else 3)
    fig, axs = plt.subplots(2 * buildings.size, ncol, figsize=(WIDTH, 3.3 * buildings.size + 0.5), squeeze=False,
                            layout="constrained")
    colors = _colors(3)
    a_p, D = ds["a_p"].values, float(ds.attrs["D"])
    ticks = _log_ticks(a_p, spacing=0.25 * ncol / 3.0)      # narrower panels, fewer labels

    def line(ax, iso, y, **kw):
        st = BEARING_STYLES.get(str(iso), {"color": 0, "ls": ":", "marker": ".", "label": str(iso)})
        ax.plot(a_p, y, color=colors[st["color"]], ls=st["ls"], marker=st["marker"], ms=3.0, lw=1.0,
                label=st["label"], **kw)

    tcolor = tuple(0.55 * c for c in colors[BEARING_STYLES[TRIPLE]["color"]][:3])   # darker: legible numerals
    for r, b in enumerate(buildings):
        sub = ds.sel(building=b)
        where = "slab (rigid)" if str(b) == "rigid" else "roof (flexible)"
        top, bottom = axs[2 * r], axs[2 * r + 1]
        tri = sub.sel(isolator=TRIPLE) if has_triple else None
        for j, m in enumerate(mus):
            ax = top[j]
            for iso in isolators:
                line(ax, iso, sub["u_max"].sel(isolator=iso, mu_k=m).values * 100.0)
            ax.set_title(rf"{where}: $\mu_k = {float(m):g}$", fontsize=7)
            ax.set_ylabel(r"$u_{max}$ [cm]" if j == 0 else "")
            ax.set_ylim(bottom=0.0)
            if has_triple:
                t = tri.sel(mu_k=m)
                _mark_regimes(ax, a_p, t["u_max"].values * 100.0, t["peak_stage"].values,
                              t["capacity_reached"].values > 0, tcolor)
        for ax in top[mus.size:]:
            ax.axis("off")
        for iso in isolators:
            line(bottom[0], iso, sub["pfa"].sel(isolator=iso).values / G)
            line(bottom[1], iso, sub["bearing_disp"].sel(isolator=iso).values / D)
        if has_triple:
            t = tri.isel(mu_k=-1)          # the probe's scene: the contents at the largest mu_k
            for ax, y in ((bottom[0], t["pfa"].values / G), (bottom[1], t["bearing_disp"].values / D)):
                _mark_regimes(ax, a_p, y, t["peak_stage"].values, t["capacity_reached"].values > 0, tcolor)
            cap = float(ds.attrs["tfp_capacity"]) / D
            stiff = float(ds["tfp_regime_start"].sel(regime=4)) / D
            for level, text in ((stiff, "IV"), (cap, "capacity")):
                bottom[1].axhline(level, color=tcolor, lw=0.6, ls=":")
                bottom[1].text(a_p[0], level, f" triple: {text}", color=tcolor, fontsize=5.0, va="bottom")
        bottom[0].set_ylabel("peak floor accel. [g]")
        bottom[0].set_title(f"{where}: floor", fontsize=7)
        bottom[0].set_ylim(bottom=0.0)
        bottom[1].axhline(1.0, color="0.6", lw=0.8, ls=":")
        bottom[1].set_ylabel(r"bearing displacement / $D$")
        bottom[1].set_title(f"{where}: bearing", fontsize=7)
        const, speed = sub.sel(isolator="friction_pendulum"), sub.sel(isolator="friction_pendulum_speed")
        mcolors = _colors(mus.size + 1)
        ratio_panels = [(bottom[2], speed, "speed-dependent / constant", f"{where}: pendulums")]
        if has_triple:
            ratio_panels.append((bottom[3], tri, "triple / single pendulum", f"{where}: triple pendulum"))
        for ax, other, ylabel, title in ratio_panels:
            for j, m in enumerate(mus):
                uc, uo = const["u_max"].sel(mu_k=m).values, other["u_max"].sel(mu_k=m).values
                ratio = np.where(uc > 0, uo / np.where(uc > 0, uc, 1.0), np.nan)
                _ratio_line(ax, a_p, ratio, color=mcolors[j], marker="o", label=rf"$u_{{max}}$, $\mu_k = {float(m):g}$")
            _ratio_line(ax, a_p, other["pfa"].values / const["pfa"].values, color="k", ls="--",
                        label="peak floor accel.")
            shown = [np.nanmax(np.append(ln.get_ydata(), 1.0)) for ln in ax.get_lines()]
            ax.set_ylim(0.0, 1.1 * max(shown))
            ax.axhline(1.0, color="0.6", lw=0.8, ls=":")
            ax.set_ylabel(ylabel)
            ax.set_title(title, fontsize=7)
            if ax is bottom[2]:                 # the triple pendulum's panel: the same lines
                ax.legend(fontsize=5.5, loc="best")
        for ax in bottom[len(ratio_panels) + 2:]:
            ax.set_visible(False)
        for ax in (*top[:mus.size], *bottom[:len(ratio_panels) + 2]):
            ax.set_xscale("log")
            ax.set_xlim(a_p[0] / 1.25, a_p[-1] * 1.25)
            ax.set_xticks(ticks, [f"{v:g}" for v in ticks])
            ax.xaxis.set_minor_locator(NullLocator())     # the grid's a_p are the ticks
            ax.set_xlabel(r"$a_p$ [m/s$^2$]")
    handles, labels = axs[0][0].get_legend_handles_labels()
    if ncol > mus.size:
        axs[0][ncol - 1].legend(handles, labels, fontsize=6, loc="center", frameon=False)
    else:
        axs[0][0].legend(fontsize=5.5, loc="upper left")
    fs = ds.sel(isolator="friction_pendulum_speed")
    caption = (f"What the bearing does to the contents, from service-level shaking to beyond the design. Peak sliding "
               f"u_max of Coulomb contents (mu_k = {_list(ds['mu_k'])}), peak floor acceleration and peak bearing "
               f"displacement against the amplitude a_p = {_list(ds['a_p'])} m/s^2 of a {ds.attrs['pulse']} pulse of "
               f"T_p = {ds.attrs['T_p']:g} s, under a lead-rubber bearing (D_y = {ds.attrs['D_y_bilinear']:g} m) and a "
               f"friction pendulum designed to the same T_eff = {ds.attrs['T_eff_target']:g} s and beta_eff = "
               f"{ds.attrs['beta_eff_target']:g} at D = {D:g} m (mu = {float(ds['Q_over_W'].sel(isolator='friction_pendulum')):.4f}, "
               f"R = {float(ds['R'].sel(isolator='friction_pendulum')):.2f} m), that pendulum with friction rising "
               f"with speed (dashed: mu_slow = {float(fs['mu_slow']):.4f}, a = {float(fs['rate']):g} s/m)"
               + (_triple_caption(ds) if has_triple else "")
               + "; contents on the slab of a rigid superstructure"
               + (f" and on the roof of a flexible one (Pi11 = {ds.attrs['pi11_flexible']:g}, Pi12 = T_s/T_p = "
                  f"{ds.attrs['pi12_flexible']:g}, xi_s = {ds.attrs['pi13_flexible']:g})" if "flexible" in buildings else "")
               + ". Bottom rows: the speed-dependent pendulum's u_max and peak floor acceleration over the constant "
               "one's" + (", and the triple pendulum's over the constant single pendulum's" if has_triple else "")
               + f" (ratios above {RATIO_TOP:g}, over a tiny u_max, on the panel's top edge with their value).")
    return fig, caption


RATIO_TOP = 3.0
"""Ratios above this are drawn on the top edge of their panel, their value written next to them."""


def _ratio_line(ax, x, ratio, color, label, ls="-", marker=None):
    """A ratio over ``x``; values above :data:`RATIO_TOP` (a tiny denominator) on the top edge, with their value."""
    ratio = np.asarray(ratio, dtype=float)
    high = ratio > RATIO_TOP
    ax.plot(x, np.where(high, RATIO_TOP, ratio), color=color, ls=ls, marker=marker, ms=3.0, lw=1.0, label=label)
    for xv, r in zip(np.asarray(x)[high], ratio[high], strict=True):
        ax.annotate(f"{r:.0f}×", (xv, RATIO_TOP), textcoords="offset points", xytext=(3, -2), fontsize=5.0,
                    color=color, ha="left", va="top")


def _triple_caption(ds) -> str:
    """The triple friction pendulum's part of the intensity figure's caption."""
    (L1, L2, L3), (m1, m2, m3), (d1, d2, d3) = (np.asarray(ds.attrs[k], dtype=float) for k in ("tfp_L", "tfp_mu", "tfp_d"))
    D = float(ds.attrs["D"])
    return (f", and a triple friction pendulum of the same T_eff and beta_eff at D (constant friction; L1 = {L1:.3f} m, "
            f"L2 = L3 = {L2:.3f} m, mu1 = {m1:.4f}, mu2 = {m2:.4f}, mu3 = {m3:.4f}, d1 = {d1:.3f} m, d2 = d3 = {d2:.3f} m: "
            f"D in regime III, regime IV from {float(ds['tfp_regime_start'].sel(regime=4)) / D:.2f} D, capacity "
            f"{float(ds.attrs['tfp_capacity']) / D:.2f} D), its regime reached written above its points (I: the inner "
            f"slider, II-III: the outer surfaces, IV-V: on the restrainers; the floor and bearing panels at the largest "
            f"mu_k) and a cross (cap.) where it reached its displacement capacity (no value: the model stops there)")


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
