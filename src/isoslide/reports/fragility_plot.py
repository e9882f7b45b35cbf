"""Figures of the fragility study, from its datasets only (``results/datasets/fragility*.nc``).

:func:`draw_curves` draws one panel per intensity measure: the fitted curves
``P(u_max > limit | IM)`` of every limit state, their bootstrap band (the envelope of the curves
at the corners of the theta and beta intervals: a simple, conservative band), the empirical
fractions (per stripe for the scaling IM, per equal-count bin of the analyses for the others)
and, dashed, the fixed-base curves on the ground-motion panels.  :func:`empirical_fractions`
gives the points.
"""

from __future__ import annotations

import itertools

import numpy as np
import xarray as xr

from ..studies.fragility import probability

__all__ = ["IM_LABELS", "band", "caption_text", "draw_curves", "empirical_fractions"]

IM_LABELS = {"pga": "PGA [m/s²]", "pgv": "PGV [m/s]", "pfa": "PFA [m/s²]", "pfv": "PFV [m/s]"}
"""Axis labels of the intensity measures (Unicode: reports render offline, no TeX)."""


def empirical_fractions(ds: xr.Dataset, im: str, limit: float, n_bins: int = 6):
    """Observed exceedance fractions of ``u_max > limit`` against ``im``.

    Parameters
    ----------
    ds : xarray.Dataset
        A fragility dataset.
    im : str
        ``pga``, ``pgv``, ``pfa`` or ``pfv``.
    limit : float
        Limit state, m.
    n_bins : int
        Equal-count bins for an IM that is not the scaling IM.

    Returns
    -------
    (x, fraction, count) : ndarrays
        Stripe level (or bin's median IM), fraction exceeded, analyses behind each point.
    """
    u = ds["u_max"].values
    exc = u > limit
    if im == ds.attrs.get("scaling_im"):
        levels = ds["im_level"].values
        stripe = ds["stripe"].values
        counts = np.array([(stripe == j).sum() for j in range(levels.size)])
        frac = np.array([exc[stripe == j].mean() for j in range(levels.size)])
        return levels, frac, counts
    x = ds[im].values
    order = np.argsort(x, kind="stable")
    parts = np.array_split(order, min(n_bins, x.size))
    return (np.array([np.median(x[p]) for p in parts]), np.array([exc[p].mean() for p in parts]),
            np.array([p.size for p in parts]))


def band(x, theta_low, theta_high, beta_low, beta_high):
    """Lower and upper envelope of the curves at the four corners of the theta and beta intervals."""
    curves = [probability(x, t, b) for t, b in itertools.product((theta_low, theta_high), (beta_low, beta_high))]
    return np.min(curves, axis=0), np.max(curves, axis=0)


def draw_curves(ds: xr.Dataset, outputs, fixed: xr.Dataset | None = None, dpi: int = 150):
    """Draw the fragility curves of ``ds`` (and ``fixed``, dashed) into every path of ``outputs``.

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    ims = [str(v) for v in ds["im"].values]
    fig, axes = plt.subplots(2, 2, figsize=(9.0, 7.0), constrained_layout=True)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for ax, im in zip(axes.ravel(), ims, strict=True):
        x_all = ds[im].values
        hi = float(np.nanmax(x_all)) if x_all.size else 1.0
        if fixed is not None and im in ("pga", "pgv"):
            hi = max(hi, float(np.nanmax(fixed[im].values)))
        x = np.linspace(hi / 200.0, 1.1 * hi, 300)
        for k, limit in enumerate(ds["limit_state"].values):
            c = colours[k % len(colours)]
            sel = ds.sel(limit_state=limit, im=im)
            label = f"{limit:g} m"
            th, be = float(sel["theta"]), float(sel["beta"])
            if np.isfinite(th) and np.isfinite(be):
                ax.plot(x, probability(x, th, be), color=c, label=f"{label}: θ = {th:.3g}, β = {be:.2f}")
                bounds = [float(sel[v]) for v in ("theta_low", "theta_high", "beta_low", "beta_high")]
                if all(np.isfinite(bounds)):
                    lo, up = band(x, *bounds)
                    ax.fill_between(x, lo, up, color=c, alpha=0.15, linewidth=0)
            else:
                status = ds["fit_status"].attrs["flag_meanings"].split()[int(sel["fit_status"])]
                ax.plot([], [], color=c, label=f"{label}: no curve ({status.replace('_', ' ')})")
            px, pf, _ = empirical_fractions(ds, im, float(limit))
            ax.plot(px, pf, "o", color=c, markersize=4)
            if fixed is not None and im in ("pga", "pgv"):
                fs = fixed.sel(limit_state=limit, im=im)
                if np.isfinite(float(fs["theta"])):
                    ax.plot(x, probability(x, float(fs["theta"]), float(fs["beta"])), "--", color=c,
                            label=f"{label} fixed base: θ = {float(fs['theta']):.3g}")
        ax.set_xlabel(IM_LABELS.get(im, im))
        ax.set_ylabel("P(u_max > limit | IM)")
        ax.set_ylim(-0.02, 1.02)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="lower right")
    fig.suptitle("Sliding fragility: fitted curves (bands: bootstrap over records), observed fractions (dots)"
                 + ("; dashed: fixed base" if fixed is not None else ""), fontsize=9)
    caption = caption_text(ds, fixed)
    for path in outputs:
        meta = {"Description": caption} if str(path).endswith(".png") else {"Subject": caption}
        fig.savefig(path, dpi=dpi, metadata=meta)
    return fig


def caption_text(ds: xr.Dataset, fixed: xr.Dataset | None = None) -> str:
    """One-paragraph caption of the figure (stored in the PNG's ``Description``)."""
    a = ds.attrs
    n_rec = len(set(map(str, ds["record"].values)))
    text = (f"Sliding fragility P(u_max > limit | IM) of {a['m_ec']:g} kg contents (mu_k lognormal, median "
            f"{a['mu_k_median']:g}, log std {a['mu_k_log_std']:g}) on a slab isolated at T_b = {a['T_b']:g} s, "
            f"xi_b = {a['xi_b']:g}: {ds.sizes['analysis']} analyses ({n_rec} records x {ds.sizes['im_level']} "
            f"{a['scaling_im'].upper()} stripes x friction draws); maximum-likelihood lognormal curves, bands from "
            f"{a['n_boot']} bootstrap resamples of the records, dots the observed fractions")
    return text + ("; dashed: the same contents on a fixed base." if fixed is not None else ".")
