"""The checks behind the similarity report (``reports/similarity.html``).

(a) **Buckingham self-similarity.**  For sampled grid points of each study,
    random physical realisations ``(a_p, T_p, M_b)`` are built with the same
    Pi-groups and integrated *in SI units* by :func:`simulate_si`, a plain
    SciPy event-driven solver written here independently of the compiled
    kernel; ``Pi1 = u_max / (a_p T_p^2)`` must not depend on the realisation.
    Each point is realised under two conventions for the groups: isoslide's
    (``Pi7 = gamma g T_p``) and the paper's printed Eq. 5 (``Pi7 = gamma a_p
    T_p``); they differ only where ``Pi7 != 0``.
(b) **Complete similarity** claimed by the paper (Pi5 over 0.7-1, Pi6 over two
    decades of beta, Pi8 up to 0.1): the spread between the curves, relative
    to the largest Pi1 of those curves (:func:`curve_spread`).
(c) **Conclusions** of the paper restated with our numbers
    (:mod:`isoslide.studies.claims`).

Everything is written to one dataset (:func:`similarity_dataset`) that the
report notebook only reads.
"""

from __future__ import annotations

import math
import zlib

import numpy as np
import xarray as xr

from . import claims
from ..datasets import global_attrs, open_dataset, pi_attrs
from ..groups import BEARING_FRICTION_NAMES, BUILDING_NAMES, EXCITATION_NAMES, INPUT_NAMES, INPUTS, TFP_NAMES
from ..groups import group as registry_group
from ..peers.si import simulate_si
from ..scene import FLOORS, G_STANDARD

CONVENTIONS = ("isoslide", "paper")
"""Group definitions used to realise a point physically: isoslide's, and the paper's printed Eq. 5."""

DEFINITIONS = {g.name: (g.definition, g.printed) for g in INPUTS}
"""Definition of each input group: (isoslide, paper as printed), from :mod:`isoslide.groups`."""

GROUPS = INPUT_NAMES
BUCKINGHAM_KEYS = ("seed", "points", "realisations", "a_p_g", "T_p", "M_b")
"""The keys of the ``similarity`` section that :func:`buckingham_study` reads."""
VERDICT_FLAGS = dict(flag_values=np.array([0, 1, 2], dtype=np.int8),
                     flag_meanings="does_not_hold holds holds_partly")


# ----------------------------------------------------------------------------------------------
# (a) an independent solver in SI units
# ----------------------------------------------------------------------------------------------

def physical_parameters(pis: dict, a_p: float, T_p: float, M_b: float, convention: str = "isoslide",
                        g: float = G_STANDARD, floor: str = FLOORS[0]) -> dict:
    """Physical (SI) parameters realising the Pi-groups ``pis`` at scales ``a_p, T_p, M_b``.

    Parameters
    ----------
    pis : dict
        ``pi2 .. pi8``, and optionally the building's ``pi9 .. pi13`` (absent: 0).
    a_p, T_p, M_b : float
        Pulse amplitude (m/s^2), pulse period (s), isolated mass (kg).
    convention : {"isoslide", "paper"}
        ``"paper"`` inverts the printed ``Pi7 = gamma a_p T_p``; ``"isoslide"`` inverts
        ``Pi7 = gamma g T_p``.  All other groups are defined alike.
    g : float
        Gravitational acceleration, m/s^2.
    floor : {"base", "roof"}
        The contents' floor (a study dataset's ``floor`` attribute).

    Returns
    -------
    dict
        ``a_p, T_p, M_b, T_b, xi_b, m_ec, mu_s, mu_k, beta, gamma, g``, the building's
        ``Q_d, D_y, m_st, T_s, xi_s`` and ``floor`` (keywords of
        :meth:`isoslide.Scene.from_physical`; the input of :func:`simulate_si`).
    """
    if convention not in CONVENTIONS:
        raise ValueError(f"convention = {convention!r} is invalid; allowed: {CONVENTIONS}")
    if floor not in FLOORS:
        raise ValueError(f"floor = {floor!r} is invalid; allowed: {FLOORS}")
    mu_k = pis["pi2"] * a_p / g
    gamma = pis["pi7"] / ((g if convention == "isoslide" else a_p) * T_p)
    building = {k: pis[k] if k in pis else 0.0 for k in BUILDING_NAMES}
    return dict(a_p=a_p, T_p=T_p, M_b=M_b, T_b=pis["pi3"] * T_p, xi_b=pis["pi4"], m_ec=pis["pi8"] * M_b,
                mu_s=mu_k / pis["pi5"], mu_k=mu_k, beta=pis["pi6"] / (a_p * T_p), gamma=gamma, g=g,
                Q_d=building["pi9"] * M_b * a_p, D_y=building["pi10"] * a_p * T_p**2,
                m_st=building["pi11"] * M_b, T_s=building["pi12"] * T_p, xi_s=building["pi13"], floor=floor)


# ----------------------------------------------------------------------------------------------
# (a) Buckingham realisations of one study
# ----------------------------------------------------------------------------------------------

def _study_seed(seed: int, study: str) -> int:
    return (int(seed) * 1_000_003 + zlib.crc32(study.encode())) % (2**32)


def _point_pis(ds: xr.Dataset, index: tuple) -> dict:
    """Every input group at one grid point.

    A building, bearing-friction or excitation group the dataset lacks takes the value of the
    paper's model: 0 for the building's and the vertical group, the registry's default for the
    bearing's friction law (constant) and the second horizontal component's (which have no effect
    without one).
    """
    sel = {d: i for d, i in zip(ds["pi1"].dims, index, strict=True)}
    pt = ds.isel(sel)
    optional = BUILDING_NAMES + BEARING_FRICTION_NAMES + TFP_NAMES + EXCITATION_NAMES
    return {g: float(pt[g]) if g in pt.variables or g not in optional else
            (registry_group(g).default if g not in BUILDING_NAMES and registry_group(g).default is not None else 0.0)
            for g in GROUPS}


def study_floor(ds: xr.Dataset) -> str:
    """The contents' floor of a study dataset: its ``floor`` attribute (or coordinate), else ``"base"``."""
    floor = ds.attrs.get("floor")
    if floor is None and "floor" in ds.variables and ds["floor"].ndim == 0:
        floor = ds["floor"].item()
    floor = FLOORS[0] if floor in (None, "", "None") else str(floor)
    if floor not in FLOORS:
        raise ValueError(f"floor = {floor!r} of study {ds.attrs.get('study')!r} is invalid; allowed: {FLOORS}")
    return floor


def sample_points(ds: xr.Dataset, n: int, rng, max_tau_end: float = 40.0) -> list:
    """Indices (tuples over ``ds.pi1.dims``) of ``n`` random grid points that slide and settle.

    Points are drawn so that the values of the swept groups other than ``pi2`` are as varied as
    possible: a point whose combination of those values was not drawn yet is preferred.
    """
    pi1 = ds["pi1"].values
    ok = (pi1 > 0) & np.isfinite(pi1)
    if "settled" in ds:
        ok &= ds["settled"].values == 1
    if "tau_end" in ds:
        ok &= ds["tau_end"].values <= max_tau_end
    flat = np.flatnonzero(ok.ravel())
    if flat.size == 0:
        return []
    order = rng.permutation(flat)
    curve = [np.unravel_index(f, pi1.shape)[:-1] for f in order]     # indices of the swept groups
    picked, seen = [], set()
    for f, c in zip(order, curve, strict=True):
        if len(picked) < n and c not in seen:
            picked.append(f)
            seen.add(c)
    for f in order:
        if len(picked) >= n:
            break
        if f not in picked:
            picked.append(f)
    pick = np.sort(np.asarray(picked[:n]))
    return [tuple(int(i) for i in np.unravel_index(f, pi1.shape)) for f in pick]


def buckingham_study(ds: xr.Dataset, settings: dict) -> xr.Dataset:
    """Realise sampled points of a study physically and integrate them in SI units.

    Parameters
    ----------
    ds : xarray.Dataset
        A study dataset (the paper's model or a general building: its Pi9 .. Pi13 and its
        ``floor`` attribute are realised too, see :func:`physical_parameters`).
    settings : dict
        The ``similarity`` section of the configuration, or its :data:`BUCKINGHAM_KEYS`
        (``seed``, ``points``, ``realisations``, ``a_p_g``, ``T_p``, ``M_b``).

    Returns
    -------
    xarray.Dataset
        Dimensions ``sample``, ``realisation``, ``convention``; ``pi1_grid`` (the
        study dataset's value), ``pi1_si`` (SI integration) and the realisations.
    """
    study = ds.attrs.get("study", "study")
    pulse = ds.attrs.get("pulse", "ricker")
    floor = study_floor(ds)
    rng = np.random.default_rng(_study_seed(settings["seed"], study))
    idx = sample_points(ds, int(settings["points"]), rng)
    R = int(settings["realisations"])
    ns = len(idx)
    lo_hi = {k: tuple(float(x) for x in settings[k]) for k in ("a_p_g", "T_p", "M_b")}

    def draw(k, size):
        lo, hi = lo_hi[k]
        return np.exp(rng.uniform(math.log(lo), math.log(hi), size))

    a_p = draw("a_p_g", (ns, R)) * G_STANDARD
    T_p = draw("T_p", (ns, R))
    M_b = draw("M_b", (ns, R))
    pis = {g: np.zeros(ns) for g in GROUPS}
    pi1_grid = np.zeros(ns)
    tau_end = np.zeros(ns)
    pi1_si = np.full((ns, R, len(CONVENTIONS)), np.nan)
    gamma = np.zeros((ns, R, len(CONVENTIONS)))
    recomputed = np.zeros((ns, len(CONVENTIONS)), dtype=np.int8)
    for i, ix in enumerate(idx):
        pt = _point_pis(ds, ix)
        for g in GROUPS:
            pis[g][i] = pt[g]
        sel = dict(zip(ds["pi1"].dims, ix, strict=True))
        pi1_grid[i] = float(ds["pi1"].isel(sel))
        tau_end[i] = float(ds["tau_end"].isel(sel)) if "tau_end" in ds else math.nan
        for j in range(R):
            for c, conv in enumerate(CONVENTIONS):
                phys = physical_parameters(pt, a_p[i, j], T_p[i, j], M_b[i, j], conv, floor=floor)
                gamma[i, j, c] = phys["gamma"]
                if c > 0 and pt["pi7"] == 0.0:
                    # identical physical parameters: the conventions differ only through Pi7
                    pi1_si[i, j, c] = pi1_si[i, j, 0]
                    continue
                recomputed[i, c] = 1
                t_end = (tau_end[i] + 1.0) * T_p[i, j] if math.isfinite(tau_end[i]) else None
                pi1_si[i, j, c] = simulate_si(phys, pulse, t_end=t_end).pi1
        print(f"{study} sample {i}: {pt} pi1 grid {pi1_grid[i]:.6g}, SI {pi1_si[i].ravel().tolist()}",
              flush=True)

    dims = ("sample",)
    out = xr.Dataset(
        {
            "pi1_grid": (dims, pi1_grid, {"long_name": "Pi1 of the study dataset (isoslide solver)", "units": "1"}),
            "pi1_si": (("sample", "realisation", "convention"), pi1_si,
                       {"long_name": "Pi1 = u_max / (a_p T_p^2) from the SI-units integration "
                                     "(isoslide.studies.similarity.simulate_si)", "units": "1"}),
            "a_p": (("sample", "realisation"), a_p, {"long_name": "pulse acceleration amplitude a_p",
                                                      "units": "m s-2"}),
            "T_p": (("sample", "realisation"), T_p, {"long_name": "pulse period T_p", "units": "s"}),
            "M_b": (("sample", "realisation"), M_b, {"long_name": "isolated mass M_b", "units": "kg"}),
            "gamma": (("sample", "realisation", "convention"), gamma,
                      {"long_name": "viscous contact constant gamma realising Pi7 under the convention",
                       "units": "s m-1"}),
            "tau_end": (dims, tau_end, {"long_name": "t_end / T_p of the dataset's solution", "units": "1"}),
            "recomputed": (("sample", "convention"), recomputed,
                           {"long_name": "1: integrated for this convention; 0: physical parameters "
                                         "identical to the isoslide convention's (Pi7 = 0), result reused",
                            "units": "1"}),
        },
        coords={
            "sample": ("sample", np.arange(ns), {"long_name": "sampled grid point", "units": "1"}),
            "realisation": ("realisation", np.arange(R), {"long_name": "random physical realisation",
                                                          "units": "1"}),
            "convention": ("convention", np.array(CONVENTIONS),
                           {"long_name": "definition of the Pi-groups used to realise the point: isoslide "
                                         "(Pi7 = gamma g T_p) or paper (printed Eq. 5, Pi7 = gamma a_p T_p)"}),
            **{g: ("sample", pis[g], pi_attrs(g)) for g in GROUPS},
        },
    )
    swept = [d for d in ds["pi1"].dims]
    out.attrs = global_attrs(
        title=f"isoslide Buckingham realisations of study {study}",
        history=f"isoslide.studies.similarity.buckingham_study: {ns} points x {R} realisations x "
                f"{len(CONVENTIONS)} conventions, SI-units integration",
        config={"settings": settings}, study=study, pulse=pulse, floor=floor, swept=" ".join(swept))
    return out


# ----------------------------------------------------------------------------------------------
# (b) complete similarity
# ----------------------------------------------------------------------------------------------

def curve_spread(ds: xr.Dataset, group: str, lo: float, hi: float) -> xr.Dataset:
    """Spread of Pi1 between the curves with ``lo <= group <= hi``, per other swept dimension.

    Returns
    -------
    xarray.Dataset
        ``spread`` (max over Pi2 of max - min over the curves), ``peak`` (largest Pi1 of those
        curves), ``relative`` = spread / peak, ``pi2_at`` (where the spread is largest), over the
        remaining swept dimensions.
    """
    vals = ds[group].values
    tol = 1e-9 * max(1.0, abs(hi))
    keep = (vals >= lo - tol) & (vals <= hi + tol)
    sub = ds["pi1"].isel({group: np.flatnonzero(keep)})
    spread_pi2 = sub.max(group) - sub.min(group)
    spread = spread_pi2.max("pi2")
    peak = sub.max((group, "pi2"))
    at = spread_pi2.idxmax("pi2")
    rel = spread / peak.where(peak > 0)
    area = sub.integrate("pi2")
    area_rel = (area.max(group) - area.min(group)) / area.max(group).where(area.max(group) > 0)
    return xr.Dataset({"spread": spread, "peak": peak, "relative": rel, "pi2_at": at,
                       "area_relative": area_rel, "n_curves": int(keep.sum())})


# ----------------------------------------------------------------------------------------------
# the report dataset
# ----------------------------------------------------------------------------------------------

def _verdict_var(values, long_name, meanings=None):
    attrs = {"long_name": long_name, "units": "1"}
    attrs.update(VERDICT_FLAGS)
    if meanings:
        attrs["flag_meanings"] = meanings
        attrs["flag_values"] = np.arange(len(meanings.split()), dtype=np.int8)
    return np.asarray(values, dtype=np.int8), attrs


def buckingham_tables(checks: list, tolerance: float) -> xr.Dataset:
    """Per-study and per-group worst differences of the Buckingham realisations.

    ``between`` is the largest relative difference of Pi1 between realisations of the same
    point (the similarity test proper); ``vs_grid`` the largest relative difference from the
    study dataset's Pi1 (solver agreement).
    """
    studies = [c.attrs.get("study", f"study{k}") for k, c in enumerate(checks)]
    nc = len(CONVENTIONS)
    between = np.full((len(checks), nc), np.nan)
    vs_grid = np.full((len(checks), nc), np.nan)
    n = np.zeros(len(checks), dtype=np.int32)
    for k, c in enumerate(checks):
        n[k] = c.sizes["sample"]
        if not n[k]:
            continue
        si = c["pi1_si"].transpose("sample", "realisation", "convention").values
        ref = np.maximum(np.abs(c["pi1_grid"].values), 1e-300)[:, None]
        for j in range(nc):
            x = si[:, :, j]
            between[k, j] = float(np.max((x.max(1) - x.min(1)) / ref[:, 0]))
            vs_grid[k, j] = float(np.max(np.abs(x - c["pi1_grid"].values[:, None]) / ref))
    # per group.  isoslide column: the studies that sweep the group (pi2: all).  paper column: the
    # same number where the printed definition equals isoslide's; where it differs (Pi7), the
    # worst paper-convention difference over the studies whose samples have the group non-zero.
    g_between = np.full((len(GROUPS), nc), np.nan)
    g_studies = []
    for gi, g in enumerate(GROUPS):
        rows = [k for k, c in enumerate(checks)
                if n[k] and (g == "pi2" or g in c.attrs.get("swept", "").split())]
        if rows:
            g_between[gi, 0] = np.nanmax(between[rows, 0])
        if DEFINITIONS[g][0] == DEFINITIONS[g][1]:
            g_between[gi, 1:] = g_between[gi, 0]
        else:
            rows = [k for k, c in enumerate(checks) if n[k] and float(np.max(np.abs(c[g].values))) > 0]
            if rows:
                g_between[gi, 1:] = np.nanmax(between[rows, 1:], axis=0)
        g_studies.append(" ".join(studies[k] for k in rows))
    verdict_s = (between <= tolerance).astype(np.int8)
    verdict_g = np.where(np.isnan(g_between), 2, g_between <= tolerance).astype(np.int8)
    vs, vsa = _verdict_var(verdict_s, f"self-similarity holds: Pi1 differs by <= {tolerance:g} (relative) "
                                      f"between realisations", meanings="fails holds")
    vga = {"long_name": f"group is a similarity group: Pi1 differs by <= {tolerance:g} (relative) between "
                        f"realisations", "units": "1", "flag_values": np.array([0, 1, 2], dtype=np.int8),
           "flag_meanings": "fails holds not_tested"}
    vg = verdict_g
    return xr.Dataset(
        {
            "buckingham_between": (("study", "convention"), between,
                                   {"long_name": "largest relative difference of Pi1 between physical "
                                                 "realisations of the same grid point", "units": "1"}),
            "buckingham_vs_grid": (("study", "convention"), vs_grid,
                                   {"long_name": "largest relative difference of the SI-units Pi1 from the "
                                                 "study dataset's Pi1", "units": "1"}),
            "buckingham_samples": ("study", n, {"long_name": "grid points realised", "units": "1"}),
            "buckingham_verdict": (("study", "convention"), vs, vsa),
            "group_between": (("group", "convention"), g_between,
                              {"long_name": "largest relative difference of Pi1 between realisations, over "
                                            "the studies that sweep the group", "units": "1"}),
            "group_definition": (("group", "convention"),
                                 np.array([[DEFINITIONS[g][0], DEFINITIONS[g][1]] for g in GROUPS], dtype=object),
                                 {"long_name": "definition of the group"}),
            "group_studies": ("group", np.array(g_studies, dtype=object),
                              {"long_name": "studies whose samples test the group"}),
            "group_verdict": (("group", "convention"), vg, vga),
        },
        coords={"study": ("study", np.array(studies, dtype=object), {"long_name": "study"}),
                "convention": ("convention", np.array(CONVENTIONS, dtype=object),
                               {"long_name": "group definitions: isoslide or the paper's printed Eq. 5"}),
                "group": ("group", np.array(GROUPS, dtype=object), {"long_name": "input Pi-group"})},
    )


def similarity_dataset(check_paths, dataset_paths, settings: dict) -> xr.Dataset:
    """Everything the similarity report shows, in one dataset.

    Parameters
    ----------
    check_paths : sequence of path
        Outputs of :func:`buckingham_study` (``results/similarity/<study>.nc``).
    dataset_paths : sequence of path
        Study datasets (``results/datasets/<study>.nc``).
    settings : dict
        The ``similarity`` section of the configuration.
    """
    checks = [open_dataset(p) for p in check_paths]
    studies = {}
    for p in dataset_paths:
        d = open_dataset(p)
        studies[d.attrs.get("study", str(p))] = d
    tol = float(settings["tolerance"])
    out = buckingham_tables(checks, tol)

    # raw samples, all studies, for the report's detail table
    rows = []
    for c in checks:
        if not c.sizes["sample"]:
            continue
        r = c[["pi1_grid", "pi1_si", "a_p", "T_p", "M_b", "gamma"]].reset_coords([g for g in GROUPS])
        r = r.assign(sample_study=("sample", np.array([c.attrs.get("study")] * c.sizes["sample"], dtype=object)))
        rows.append(r.drop_vars("sample"))
    if rows:
        raw = xr.concat(rows, dim="sample", data_vars="all", coords="minimal", compat="override",
                        combine_attrs="drop_conflicts", join="outer")
        raw = raw.rename({v: f"sample_{v}" for v in raw.data_vars if not v.startswith("sample_")})
        raw = raw.rename({"sample_pi1_grid": "sample_pi1_grid"})
        for g in GROUPS:
            raw[f"sample_{g}"].attrs = {"long_name": f"{g} of the sampled grid point", "units": "1"}
        raw["sample_study"].attrs = {"long_name": "study of the sampled point"}
        out = out.merge(raw.rename_dims({"sample": "sample_row"}), compat="override", join="outer")

    # (b) complete similarity
    spreads = {}
    groups, cases, rel, spread, peak, at, ranges, arel = [], [], [], [], [], [], [], []
    tol_s = float(settings["spread_tolerance"])
    for group, c in settings["complete"].items():
        d = studies.get(c["study"])
        if d is None or group not in d.dims:
            continue
        lo, hi = (float(x) for x in c["range"])
        s = curve_spread(d, group, lo, hi)
        s.attrs["range_text"] = f"{lo:g} <= {group} <= {hi:g}"
        spreads[group] = s
        st = s["relative"].stack(case=list(s["relative"].dims)) if s["relative"].ndim else None
        n = 1 if st is None else st.sizes["case"]
        for k in range(n):
            if st is None:
                label, sel = "all", {}
            else:
                sel = {dname: st["case"].values[k][i] if isinstance(st["case"].values[k], tuple)
                       else st["case"].values[k] for i, dname in enumerate(s["relative"].dims)}
                label = ", ".join(f"{dn} = {float(v):g}" for dn, v in sel.items())
            groups.append(group)
            cases.append(label)
            pick = s.sel(sel) if sel else s
            rel.append(float(pick["relative"]))
            spread.append(float(pick["spread"]))
            peak.append(float(pick["peak"]))
            at.append(float(pick["pi2_at"]))
            arel.append(float(pick["area_relative"]))
            ranges.append(f"{lo:g} <= {group} <= {hi:g} (study {c['study']}, {int(s['n_curves'])} curves)")
    v, va = _verdict_var([1 if r <= tol_s else 0 for r in rel],
                         f"complete similarity holds: spread <= {tol_s:g} of the peak Pi1",
                         meanings="does_not_hold holds")
    out = out.merge(xr.Dataset(
        {
            "complete_group": ("claim_case", np.array(groups, dtype=object), {"long_name": "Pi-group of the claim"}),
            "complete_case": ("claim_case", np.array(cases, dtype=object),
                              {"long_name": "values of the other swept groups"}),
            "complete_range": ("claim_case", np.array(ranges, dtype=object), {"long_name": "range tested"}),
            "complete_relative": ("claim_case", np.array(rel), {"long_name": "largest spread between the curves "
                                                                             "over the peak Pi1", "units": "1"}),
            "complete_spread": ("claim_case", np.array(spread), {"long_name": "largest spread between the curves "
                                                                              "(max - min of Pi1 at one Pi2)",
                                                                 "units": "1"}),
            "complete_peak": ("claim_case", np.array(peak), {"long_name": "largest Pi1 of the curves",
                                                             "units": "1"}),
            "complete_pi2_at": ("claim_case", np.array(at), {"long_name": "Pi2 where the spread is largest",
                                                             "units": "1"}),
            "complete_area_relative": ("claim_case", np.array(arel),
                                       {"long_name": "spread of the areas under the curves (integral of Pi1 "
                                                     "over Pi2) over the largest area", "units": "1"}),
            "complete_verdict": ("claim_case", v, va),
        }), join="outer")

    # (c) conclusions
    concl = claims.evaluate(studies, spreads, tol_s)
    cv, cva = _verdict_var([c["verdict"] for c in concl], "verdict on the paper's conclusion",
                           meanings=claims.VERDICT_MEANINGS)
    out = out.merge(xr.Dataset(
        {
            "conclusion_key": ("conclusion", np.array([c["key"] for c in concl], dtype=object),
                               {"long_name": "short name"}),
            "conclusion_claim": ("conclusion", np.array([c["claim"] for c in concl], dtype=object),
                                 {"long_name": "the paper's conclusion"}),
            "conclusion_finding": ("conclusion", np.array([c["finding"] for c in concl], dtype=object),
                                   {"long_name": "what isoslide's datasets show"}),
            "conclusion_criterion": ("conclusion", np.array([c["criterion"] for c in concl], dtype=object),
                                     {"long_name": "criterion of the verdict"}),
            "conclusion_verdict": ("conclusion", cv, cva),
        }), join="outer")
    out.attrs = global_attrs(
        title="isoslide similarity checks: Buckingham self-similarity, complete similarity, the paper's "
              "conclusions",
        history=f"isoslide.studies.similarity.similarity_dataset from {len(checks)} realisation file(s) and "
                f"{len(studies)} study dataset(s)",
        config=settings, low_pi2=f"'low Pi2' means Pi2 <= {claims.LOW_PI2:g}",
        tolerance=f"{tol:g}", spread_tolerance=f"{tol_s:g}")
    return out
