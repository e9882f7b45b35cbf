"""The paper's conclusions as claims, each judged with isoslide's datasets.

Every :class:`Claim` names the study datasets (and complete-similarity
spreads) it needs.  :func:`evaluate` judges every claim in :data:`CLAIMS`; a
claim whose inputs are missing from the run is reported as *not evaluated*
with the missing names, never dropped.

Verdicts: 0 does not hold, 1 holds, 2 holds partly, 3 not evaluated.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

LOW_PI2 = 0.1
"""'Low Pi2' (low friction or strong pulse) means Pi2 <= 0.1 in the claims."""

MATERIAL = 0.02
"""Relative changes of Pi1 below 2% count as 'no change' in the verdicts."""

DOES_NOT_HOLD, HOLDS, HOLDS_PARTLY, NOT_EVALUATED = 0, 1, 2, 3
VERDICT_MEANINGS = "does_not_hold holds holds_partly not_evaluated"
"""CF ``flag_meanings`` of the verdict codes 0..3."""


@dataclass(frozen=True)
class Claim:
    """One conclusion of the paper.

    Attributes
    ----------
    key : str
        Short name.
    text : str
        The paper's claim.
    studies : tuple of str
        Study datasets the claim is judged on (their names in the configuration).
    spreads : tuple of str
        Pi-groups whose complete-similarity spread (``similarity.complete``) it needs.
    judge : callable
        ``judge(datasets, spreads, spread_tolerance) -> dict(finding, verdict, criterion)``.
    """

    key: str
    text: str
    studies: tuple
    judge: Callable
    spreads: tuple = ()


def _ratio_mean(a, b, mask):
    m = mask & (b > 0)
    return float(np.mean(a[m] / b[m])) if m.any() else math.nan


def _integral(pi1, pi2):
    return float(np.trapezoid(pi1, pi2))


def _isolation_amplifies(ds, spreads, tol, study="fig5_pi3"):
    d = ds[study]
    pi2 = d["pi2"].values
    low = pi2 <= LOW_PI2 + 1e-12
    pi3s = d["pi3"].values
    stiff = float(pi3s.min())
    ref = d["pi1"].sel(pi3=stiff).values
    amp = {float(p): _ratio_mean(d["pi1"].sel(pi3=p).values, ref, low) for p in pi3s if p != stiff}
    peaks = {float(p): float(d["pi1"].sel(pi3=p).max()) for p in pi3s}
    best_peak = max((p for p in peaks if p != stiff), key=lambda k: peaks[k])
    above = [p for p in pi3s if p > 1.0]
    sub = d["pi1"].sel(pi3=above).values[:, low] if len(above) > 1 else np.zeros((1, int(low.sum())))
    frac = float(np.mean(np.all(np.diff(sub, axis=0) <= 1e-12, axis=0))) if sub.size else math.nan
    cross = {}
    for p in pi3s:
        if p == stiff:
            continue
        cur = d["pi1"].sel(pi3=p).values
        below = np.flatnonzero((cur < ref * (1 - MATERIAL)) & (ref > 0))
        cross[float(p)] = f"{pi2[below[0]]:.2f}" if below.size else "never"
    amplified = [p for p, r in amp.items() if r > 1 + MATERIAL]
    finding = (f"Mean Pi1 ratio to the stiff system (Pi3 = {stiff:g}) over Pi2 <= {LOW_PI2:g}: "
               + ", ".join(f"Pi3 = {p:g}: {r:.2f}" for p, r in amp.items())
               + ". Peak of each curve: " + ", ".join(f"{p:g}: {v:.3f}" for p, v in peaks.items())
               + f" (largest at Pi3 = {best_peak:g}). For Pi3 > 1, Pi1 decreases with Pi3 at "
               f"{100 * frac:.0f}% of the Pi2 <= {LOW_PI2:g} points. Pi2 from which the isolated curve "
               f"falls below the stiff one: " + ", ".join(f"Pi3 = {p:g}: {c}" for p, c in cross.items()) + ".")
    ok1 = len(amplified) > 0
    ok2 = abs(best_peak - 1.0) <= 0.25
    ok3 = frac >= 0.9
    v = 1 if (ok1 and ok2 and ok3) else (2 if (ok1 or ok2 or ok3) else 0)
    return dict(finding=finding, verdict=v,
                criterion=f"holds if some Pi3 amplifies Pi1 by > {100 * MATERIAL:g}% on average over "
                          f"Pi2 <= {LOW_PI2:g}, the highest curve peaks at a Pi3 within 0.25 of 1, and "
                          f"Pi1 decreases with Pi3 > 1 at >= 90% of the Pi2 <= {LOW_PI2:g} points; "
                          f"partly if some of these hold")


def _damping_at_resonance(ds, spreads, tol, study="fig5_pi4"):
    d = ds[study]
    pi2 = d["pi2"].values
    red = {}
    for p3 in np.atleast_1d(d["pi3"].values) if "pi3" in d.dims else [float(d["pi3"])]:
        cur = d["pi1"].sel(pi3=p3) if "pi3" in d.dims else d["pi1"]
        i0 = _integral(cur.sel(pi4=0.0).values, pi2) if 0.0 in d["pi4"].values else math.nan
        red[float(p3)] = {float(x): 1.0 - _integral(cur.sel(pi4=x).values, pi2) / i0
                          for x in d["pi4"].values}
    r_res = red.get(1.0, {}).get(0.1, math.nan)
    others = {p: r.get(0.1, math.nan) for p, r in red.items() if p != 1.0}
    res = red.get(1.0, {})
    inc = {x: res[x] - res[xp] for xp, x in zip(sorted(res)[:-1], sorted(res)[1:], strict=True)}
    finding = (f"Reduction of the area under Pi1(Pi2) by xi_b = 0.1 relative to xi_b = 0: "
               f"{100 * r_res:.0f}% at resonance (Pi3 = 1)"
               + "".join(f", {100 * r:.0f}% at Pi3 = {p:g}" for p, r in others.items())
               + ". Extra reduction per damping step at Pi3 = 1: "
               + ", ".join(f"xi_b -> {x:g}: {100 * r:+.0f}%" for x, r in inc.items()) + ".")
    ok_res = r_res >= 0.25
    ok_marg = all(r <= 0.5 * r_res for r in others.values()) if others else True
    beyond = [r for x, r in inc.items() if x > 0.15 + 1e-9]
    upto = [r for x, r in inc.items() if x <= 0.15 + 1e-9]
    ok_drop = bool(beyond and upto and max(beyond) < min(upto))
    v = 1 if (ok_res and ok_marg and ok_drop) else (2 if ok_res else 0)
    return dict(finding=finding, verdict=v,
                criterion="holds if xi_b = 0.1 removes >= 25% of the area at Pi3 = 1, at most half as "
                          "much away from resonance, and every damping step beyond 0.15 gains less "
                          "than every step up to 0.15; partly if only the first holds")


def _static_friction(ds, spreads, tol, study="fig6_pi5"):
    d = ds[study]
    pi2 = d["pi2"].values
    low = pi2 <= LOW_PI2 + 1e-12
    parts, okl, okh = [], [], []
    p5min = float(d["pi5"].min())
    for p3 in d["pi3"].values:
        a = d["pi1"].sel(pi3=p3, pi5=p5min).values
        b = d["pi1"].sel(pi3=p3, pi5=1.0).values
        nz = np.flatnonzero(b > 0)
        high = np.zeros_like(low)
        if nz.size:
            high[nz[len(nz) // 2]: nz[-1] + 1] = True
        rl, rh = _ratio_mean(a, b, low), _ratio_mean(a, b, high)
        okl.append(rl > 1.0 + MATERIAL)
        okh.append(rh < 1.0 - MATERIAL)
        parts.append(f"Pi3 = {p3:g}: x{rl:.3f} at Pi2 <= {LOW_PI2:g}, x{rh:.3f} over the upper half "
                     f"of the Coulomb sliding range")
    finding = f"Pi1 at Pi5 = {p5min:g} over Pi1 at Pi5 = 1 (Coulomb): " + "; ".join(parts) + "."
    n_ok = sum(a and b for a, b in zip(okl, okh, strict=True))
    v = 1 if n_ok == len(okl) else (2 if n_ok or any(okl) or any(okh) else 0)
    return dict(finding=finding, verdict=v,
                criterion=f"holds if, for every Pi3, the mean ratio exceeds 1 by > {100 * MATERIAL:g}% "
                          f"for Pi2 <= {LOW_PI2:g} and is below 1 by > {100 * MATERIAL:g}% over the upper "
                          f"half of the sliding range; partly if for some")


def _spread(group):
    def judge(ds, spreads, tol):
        s = spreads[group]
        rel = np.atleast_1d(s["relative"].values).ravel()
        worst = float(np.nanmax(rel)) if rel.size and np.isfinite(rel).any() else math.nan
        where = ""
        if s["relative"].ndim:
            k = int(np.nanargmax(s["relative"].values.ravel()))
            where = ", ".join(f"{dname} = {float(s[dname].values.ravel()[k] if s[dname].ndim else s[dname]):g}"
                              for dname in s["relative"].dims)
            where = f" (at {where})"
        arel = np.atleast_1d(s["area_relative"].values).ravel()
        finding = (f"Largest spread between the curves over {s.attrs.get('range_text', '')}: "
                   f"{100 * worst:.1f}% of the peak Pi1{where}; per case "
                   + ", ".join(f"{100 * float(r):.1f}%" for r in rel)
                   + ". Spread of the areas under the curves: "
                   + ", ".join(f"{100 * float(r):.1f}%" for r in arel) + ".")
        v = 1 if worst <= tol else (2 if np.nanmin(rel) <= tol else 0)
        return dict(finding=finding, verdict=v,
                    criterion=f"holds if the spread is <= {100 * tol:g}% of the peak Pi1 in every case; "
                              f"partly if in some")
    return judge


def _viscous_contact(ds, spreads, tol, study="fig7_pi7"):
    d = ds[study]
    p = d["pi1"].transpose("pi7", "pi2").values
    active = p.max(axis=0) > 0
    mono = np.all(np.diff(p, axis=0) <= 1e-9 * np.maximum(p[:-1], 1e-300) + 1e-12, axis=0)
    frac = float(np.mean(mono[active])) if active.any() else math.nan
    i_lo = _integral(p[0], d["pi2"].values)
    i_hi = _integral(p[-1], d["pi2"].values)
    finding = (f"Pi1 is non-increasing in Pi7 at {100 * frac:.0f}% of the Pi2 points with sliding; the "
               f"area under the curve falls by {100 * (1 - i_hi / i_lo):.0f}% from Pi7 = 0 to "
               f"Pi7 = {float(d['pi7'].max()):g}.")
    v = 1 if frac >= 0.95 else (2 if frac >= 0.5 else 0)
    return dict(finding=finding, verdict=v,
                criterion="holds if Pi1 is non-increasing in Pi7 at >= 95% of the sliding Pi2 points; "
                          "partly if at >= 50%")


def _heavy_contents(ds, spreads, tol, study="fig8_pi8"):
    if 1.0 not in ds[study]["pi8"].values:
        return dict(finding=f"not evaluated: study {study} has no Pi8 = 1 curve", verdict=NOT_EVALUATED,
                    criterion="needs a Pi8 = 1 curve")
    d = ds[study]
    p3 = float(d["pi3"].values[np.argmin(np.abs(d["pi3"].values - 0.1))])
    a = d["pi1"].sel(pi3=p3, pi8=1.0).values
    b = d["pi1"].sel(pi3=p3, pi8=float(d["pi8"].min())).values
    pi2 = d["pi2"].values
    low = pi2 <= LOW_PI2 + 1e-12
    nz = np.flatnonzero((a > 0) | (b > 0))
    high = np.zeros_like(low)
    if nz.size:
        high[nz[len(nz) // 2]: nz[-1] + 1] = True
    rl = _ratio_mean(a, b, low)
    hi_a, hi_b = float(a[high].mean()) if high.any() else math.nan, float(b[high].mean()) if high.any() else math.nan
    finding = (f"At Pi3 = {p3:g}, Pi8 = 1 against Pi8 = {float(d['pi8'].min()):g}: mean ratio {rl:.3f} "
               f"for Pi2 <= {LOW_PI2:g}; mean Pi1 over the upper half of the sliding range {hi_a:.3g} "
               f"against {hi_b:.3g}.")
    dec, inc = rl < 1 - MATERIAL, hi_a > hi_b * (1 + MATERIAL)
    v = 1 if (dec and inc) else (2 if (dec or inc) else 0)
    return dict(finding=finding, verdict=v,
                criterion=f"holds if both the decrease at low Pi2 and the increase at large Pi2 "
                          f"exceed {100 * MATERIAL:g}%; partly if one does")


CLAIMS = (
    Claim("isolation_amplifies",
          "Isolation amplifies peak sliding for low Pi2; the highest amplification is at resonance "
          "(Pi3 ~ 1); for Pi3 > 1, Pi1 decreases with Pi3 (decoupling).",
          ("fig5_pi3",), _isolation_amplifies),
    Claim("damping_at_resonance",
          "About 10% isolation damping is very effective at resonance (Pi3 = 1) and has a marginal effect "
          "away from it; the efficiency drops for xi_b > 0.15.",
          ("fig5_pi4",), _damping_at_resonance),
    Claim("static_friction",
          "Static friction (Pi5 < 1) reduces peak sliding for large Pi2 and amplifies it for low Pi2, so "
          "neglecting it is unconservative for low friction.",
          ("fig6_pi5",), _static_friction),
    Claim("pi5_similarity", "Peak sliding is similar over 0.7 <= Pi5 <= 1 (Pi1 almost independent of Pi5).",
          (), _spread("pi5"), spreads=("pi5",)),
    Claim("pi6_complete_similarity",
          "Pi1 exhibits complete similarity in Pi6 over two decades of beta (10 to 1000 s/m).",
          (), _spread("pi6"), spreads=("pi6",)),
    Claim("pi8_negligible", "The dynamic interaction is negligible up to Pi8 = m_EC/M_b = 0.1.",
          (), _spread("pi8"), spreads=("pi8",)),
    Claim("viscous_contact", "The higher the contact damping (Pi7), the lower the sliding response.",
          ("fig7_pi7",), _viscous_contact),
    Claim("heavy_contents",
          "For Pi3 = 0.1 and contents as heavy as the isolated mass (Pi8 = 1), Pi1 decreases for low Pi2 "
          "(friction dissipation) and increases for large Pi2.",
          ("fig8_pi8",), _heavy_contents),
)
"""The paper's conclusions, in the order of its Sec. 4."""


def evaluate(datasets: dict, spreads: dict, spread_tolerance: float, claims=CLAIMS) -> list:
    """Judge every claim with the study datasets and complete-similarity spreads of a run.

    Parameters
    ----------
    datasets : dict of str -> xarray.Dataset
        Study datasets by study name.
    spreads : dict of str -> xarray.Dataset
        :func:`isoslide.studies.similarity.curve_spread` results by Pi-group.
    spread_tolerance : float
        Spread (relative to the peak Pi1) below which complete similarity holds.
    claims : sequence of Claim

    Returns
    -------
    list of dict
        One per claim, in order: ``key``, ``claim``, ``finding``, ``verdict`` (see module),
        ``criterion``.  Claims with missing inputs have verdict 3 and name what is missing.
    """
    out = []
    for c in claims:
        missing = [f"study {s}" for s in c.studies if s not in datasets]
        missing += [f"complete-similarity range of {g} (similarity.complete.{g})" for g in c.spreads
                    if g not in spreads]
        if missing:
            res = dict(finding="not evaluated: " + ", ".join(missing) + " missing from this run",
                       verdict=NOT_EVALUATED, criterion="needs " + ", ".join(missing))
        else:
            res = c.judge(datasets, spreads, float(spread_tolerance))
        out.append(dict(key=c.key, claim=c.text, **res))
    return out
