"""Fitted fragility curves as a pelicun (FEMA P-58) damage-model database.

pelicun reads damage models as a table, one row per component (the format of the FEMA P-58 2nd
edition library that ships with pelicun 3.x, ``dlml``): ``ID, Incomplete, Demand-Type,
Demand-Unit, Demand-Offset, Demand-Directional`` and, for each limit state ``LSk``,
``LSk-Family, LSk-Theta_0, LSk-Theta_1, LSk-DamageStateWeights``.  :func:`damage_db` builds that
table from the curves of :func:`isoslide.studies.fragility.fit_lognormal`; :func:`write_damage_db` writes
it (and, on request, the companion ``.json`` of descriptions that the pelicun libraries carry next
to each ``.csv``; pelicun's calculation reads only the ``.csv``).

The components (IDs in :data:`COMPONENT_IDS`, one per floor IM):

* ``isoslide.PFA``: Demand-Type ``Peak Floor Acceleration``, Demand-Unit ``g`` (the fitted medians
  in m/s^2 divided by pelicun's g, 9.80665 m/s^2);
* ``isoslide.PFV``: Demand-Type ``Peak Floor Velocity``, Demand-Unit ``mps`` (m/s, unchanged).

Limit state ``LSk`` is the k-th sliding limit in increasing displacement (``u_max > limit``), one
damage state each; Family ``lognormal``, ``Theta_0`` the median, ``Theta_1`` the dispersion beta.
The ground IMs (pga, pgv) are not exported: pelicun places contents on floors.

How pelicun uses the table (pelicun 3.10, checked by ``tests/test_pelicun_export.py``):

* ``Demand-Directional`` is 0: sliding contents are non-directional components (they slide in
  whatever direction the floor drives them; the curves were fitted on the peak floor motion along
  the line the contents slide on, the peak in any direction of that motion).  Assign them with
  direction ``"0"`` in the component marginals (``Direction: 0``, as FEMA P-58 assigns its
  non-directional components): pelicun then reads the demand of such a component as the largest
  of the directions given at its floor (``PFA-<loc>-1``, ``PFA-<loc>-2``) times the
  non-directional multiplier (``NonDirectionalMultipliers``, 1.2 by default for ``ALL``: the
  FEMA P-58 estimate of the peak in any direction from two orthogonal peaks), whatever direction
  the component was assigned.
* ``Demand-Offset`` is 0: with pelicun's default global offset of -1 for PFA and PFV, a component
  placed at story ``L`` reads the floor demand at location ``L - 1``, the slab it stands on (as the
  floor-mounted contents of FEMA P-58).
* The capacities of the limit states of one component are perfectly correlated (one standard
  normal draw ``z`` per block, capacity ``theta_k exp(beta_k z)``), and the damage state is the
  highest limit state exceeded.  Hence pelicun's ``P(DS >= k | x) = max_{j >= k} P_j(x)``: the fitted
  curve ``P_k`` itself wherever the fitted curves do not cross.  Curves with different ``beta``
  always cross somewhere: ``P_k`` and ``P_{k+1}`` meet at ``ln x* = (beta_{k+1} ln theta_k - beta_k
  ln theta_{k+1}) / (beta_{k+1} - beta_k)``, usually far in a tail.
* Medians must increase from one limit state to the next.  Fitted medians that do not are refused
  (ValueError), never reordered.
"""

from __future__ import annotations

import csv
import io
import json
import math
from pathlib import Path

import numpy as np
import pandas as pd
import xarray as xr

from ..atomic import atomic_path

__all__ = ["COMPONENT_IDS", "DEMANDS", "DIRECTIONAL", "G_PELICUN", "SLIDING_TEXTS", "damage_db", "write_damage_db"]

G_PELICUN = 9.80665
"""pelicun's ``g``, m/s^2 (``pelicun/settings/default_units.json``): the median in g is the fitted one over it."""

COMPONENT_IDS = {"pfa": "isoslide.PFA", "pfv": "isoslide.PFV"}
"""pelicun component ID of each exported floor IM."""

DEMANDS = {"pfa": ("Peak Floor Acceleration", "g", G_PELICUN),
           "pfv": ("Peak Floor Velocity", "mps", 1.0)}
"""Floor IM -> (pelicun Demand-Type, Demand-Unit, size of that unit in the fitted IM unit, m/s^2 or m/s)."""

DIRECTIONAL = 0
"""``Demand-Directional`` of every component: 0, non-directional (sliding contents slide in any direction)."""

KNOWN_IMS = ("pga", "pgv", "pfa", "pfv")
HEAD = ["ID", "Incomplete", "Demand-Type", "Demand-Unit", "Demand-Offset", "Demand-Directional"]
LS_FIELDS = ("Family", "Theta_0", "Theta_1", "DamageStateWeights")


def _check_curves(name: str, arr) -> xr.DataArray:
    if not isinstance(arr, xr.DataArray):
        raise ValueError(f"{name} is a {type(arr).__name__}; allowed: an xarray.DataArray with dims "
                         "(limit_state, im)")
    if set(arr.dims) != {"limit_state", "im"}:
        raise ValueError(f"{name} has dims {arr.dims}; allowed: ('limit_state', 'im')")
    for dim in ("limit_state", "im"):
        if dim not in arr.coords:
            raise ValueError(f"{name} has no coordinate {dim!r}; allowed: dims (limit_state, im) with coordinates")
    ims = [str(v) for v in arr["im"].values]
    unknown = sorted(set(ims) - set(KNOWN_IMS))
    if unknown:
        raise ValueError(f"{name}.im = {ims} has {unknown}; allowed: IMs from {list(KNOWN_IMS)}")
    ls = np.asarray(arr["limit_state"].values, dtype=float)
    if not np.all(np.isfinite(ls) & (ls > 0)) or np.unique(ls).size != ls.size:
        raise ValueError(f"{name}.limit_state = {ls.tolist()} is invalid; allowed: distinct sliding limits "
                         "> 0 m (finite)")
    return arr.transpose("limit_state", "im")


def _fmt(value: float) -> str:
    """Shortest text that reads back to the same float (Python's repr)."""
    return repr(float(value))


def damage_db(theta: xr.DataArray, beta: xr.DataArray, *, component_ids: dict | None = None,
              incomplete: str = "raise") -> pd.DataFrame:
    """The pelicun damage-model table of the fitted curves, one component per floor IM.

    Parameters
    ----------
    theta : xarray.DataArray, dims (limit_state, im)
        Fitted medians: ``limit_state`` the sliding limits (m), ``im`` names from
        ``pga, pgv, pfa, pfv`` with medians in m/s^2 (pga, pfa) or m/s (pgv, pfv).  NaN marks a
        curve the data could not identify.
    beta : xarray.DataArray, dims (limit_state, im)
        Fitted dispersions (-), same coordinates.
    component_ids : dict, optional
        IM -> component ID, replacing :data:`COMPONENT_IDS` for the IMs it names.
    incomplete : {"raise", "flag"}
        A component with a missing curve (NaN): ``"raise"`` a ValueError; ``"flag"`` write it with
        ``Incomplete = 1`` and the limit states that were fitted (pelicun then drops it and, asked
        to, warns that the component has no damage model).

    Returns
    -------
    pandas.DataFrame
        Index ``ID`` (the component IDs, in the order pfa, pfv), the columns of the pelicun
        format; ``Theta_0`` in the Demand-Unit (g or m/s), ``Theta_1`` beta.

    Raises
    ------
    ValueError
        Arrays of other dims or coordinates, limit states not distinct or not > 0, no floor IM,
        medians or dispersions not > 0, medians that do not increase with the limit state, or a
        missing curve with ``incomplete="raise"``.
    """
    theta, beta = _check_curves("theta", theta), _check_curves("beta", beta)
    if incomplete not in ("raise", "flag"):
        raise ValueError(f"incomplete = {incomplete!r} is invalid; allowed: 'raise', 'flag'")
    try:
        beta = beta.sel(limit_state=theta["limit_state"], im=theta["im"])
    except KeyError:
        raise ValueError(f"beta has coordinates limit_state={beta['limit_state'].values.tolist()}, "
                         f"im={beta['im'].values.tolist()}; allowed: those of theta, "
                         f"limit_state={theta['limit_state'].values.tolist()}, "
                         f"im={theta['im'].values.tolist()}") from None
    order = np.argsort(np.asarray(theta["limit_state"].values, dtype=float), kind="stable")
    theta, beta = theta.isel(limit_state=order), beta.isel(limit_state=order)
    limits = np.asarray(theta["limit_state"].values, dtype=float)
    ids = dict(COMPONENT_IDS, **(component_ids or {}))
    floor_ims = [im for im in DEMANDS if im in [str(v) for v in theta["im"].values]]
    if not floor_ims:
        raise ValueError(f"theta.im = {[str(v) for v in theta['im'].values]} has no floor IM; allowed: "
                         f"at least one of {list(DEMANDS)}")
    columns = HEAD[1:] + [f"LS{k + 1}-{f}" for k in range(limits.size) for f in LS_FIELDS]
    rows, index = [], []
    for im in floor_ims:
        demand_type, unit, size = DEMANDS[im]
        med = np.asarray(theta.sel(im=im).values, dtype=float)
        disp = np.asarray(beta.sel(im=im).values, dtype=float)
        missing = np.isnan(med) | np.isnan(disp)
        for name, arr in (("theta", med), ("beta", disp)):
            bad = ~missing & ~(np.isfinite(arr) & (arr > 0))
            if bad.any():
                k = int(np.flatnonzero(bad)[0])
                raise ValueError(f"{name}[limit_state={limits[k]:g}, im={im!r}] = {float(arr[k])!r} is out of range; "
                                 f"allowed range: 0 < {name} < inf")
        if missing.any() and incomplete == "raise":
            k = int(np.flatnonzero(missing)[0])
            raise ValueError(f"theta[limit_state={limits[k]:g}, im={im!r}] = nan: the curve is missing, and "
                             f"pelicun needs every limit state of {ids[im]}; allowed: fitted curves "
                             "(or incomplete='flag' to write the component as incomplete)")
        fitted = np.flatnonzero(~missing)
        steps = np.diff(med[fitted])
        if np.any(steps <= 0):
            k = int(np.flatnonzero(steps <= 0)[0])
            a, b = fitted[k], fitted[k + 1]
            raise ValueError(
                f"theta[im={im!r}] = {float(med[a])!r} at limit_state={limits[a]:g} m and {float(med[b])!r} at "
                f"limit_state={limits[b]:g} m: medians do not increase with the limit state; allowed: "
                f"increasing medians (pelicun's sequential limit states). Not reordered: refit with more "
                f"analyses or merge the limit states")
        row = [int(missing.any()), demand_type, unit, 0, DIRECTIONAL]
        for k in range(limits.size):
            if missing[k]:
                row += ["", math.nan, math.nan, ""]
            else:
                row += ["lognormal", float(med[k] / size), float(disp[k]), ""]
        rows.append(row)
        index.append(ids[im])
    table = pd.DataFrame(rows, index=pd.Index(index, name="ID"), columns=columns)
    table.attrs["limit_states_m"] = limits.tolist()
    return table


def _csv_text(table: pd.DataFrame) -> str:
    buf = io.StringIO()
    out = csv.writer(buf, lineterminator="\n")
    out.writerow(HEAD + list(table.columns[len(HEAD) - 1:]))
    for cid, values in zip(table.index, table.itertuples(index=False), strict=True):
        cells = [cid]
        for v in values:
            if isinstance(v, float):
                cells.append("" if math.isnan(v) else _fmt(v))
            else:
                cells.append(str(v))
        out.writerow(cells)
    return buf.getvalue()


SLIDING_TEXTS = {"short_name": "isoslide sliding contents",
                 "component_text": "Sliding contents on an isolated floor",
                 "comments": "Lognormal curves fitted by maximum likelihood (Baker 2015) to exact sliding analyses "
                             "(isoslide); limit state k: peak sliding displacement above the k-th limit"}
"""The descriptions of the ``.json`` by default: those of the sliding contents' curves."""


def _json_text(table: pd.DataFrame, description: str, short_name: str, component_text: str, comments: str,
               limit_texts) -> str:
    limits = table.attrs["limit_states_m"]
    if limit_texts is None:
        limit_texts = [f"Peak sliding displacement above {lim:g} m" for lim in limits]
    elif len(limit_texts) != len(limits):
        raise ValueError(f"limit_texts = {list(limit_texts)!r} has {len(limit_texts)} entries; allowed: one per limit "
                         f"state ({len(limits)}), in increasing limit_state")
    info = {"_GeneralInformation": {
        "ShortName": short_name,
        "Description": description,
        "Version": "1.0",
    }}
    for cid, row in table.iterrows():
        info[cid] = {
            "Description": f"{component_text}, {row['Demand-Type'].lower()} fragility ({row['Demand-Unit']})",
            "Comments": comments,
            "SuggestedComponentBlockSize": "1 EA",
            "Directional": "non-directional: assign with direction 0; pelicun reads the largest floor demand "
                           "of the directions times its non-directional multiplier",
            "RoundUpToIntegerQuantity": "True",
            "LimitStates": {f"LS{k + 1}": {f"DS{k + 1}": {"Description": text}}
                            for k, text in enumerate(limit_texts)},
        }
    return json.dumps(info, indent=2, sort_keys=False) + "\n"


def _write_atomic(path: Path, text: str) -> None:
    with atomic_path(path) as tmp:
        Path(tmp).write_text(text, encoding="utf-8", newline="")


def write_damage_db(path, theta: xr.DataArray, beta: xr.DataArray, *, json_path=None,
                    component_ids: dict | None = None, incomplete: str = "raise",
                    description: str = "Fragility of sliding contents computed by isoslide",
                    short_name: str = SLIDING_TEXTS["short_name"], component_text: str = SLIDING_TEXTS["component_text"],
                    comments: str = SLIDING_TEXTS["comments"], limit_texts=None) -> Path:
    """Write :func:`damage_db` as pelicun's damage-model CSV (atomically, the same bytes for the same curves).

    Parameters
    ----------
    path : str or os.PathLike
        The ``.csv`` to write (parent folders are created).
    theta, beta, component_ids, incomplete
        As for :func:`damage_db`.
    json_path : str or os.PathLike, optional
        Also write the companion ``.json`` (component and limit-state descriptions) there.
    description : str
        ``_GeneralInformation.Description`` of the ``.json``.
    short_name : str
        ``_GeneralInformation.ShortName`` of the ``.json``.
    component_text : str
        What each component is; its ``Description`` adds the demand and its unit.
    comments : str
        ``Comments`` of each component: how the curves were made.
    limit_texts : sequence of str, optional
        ``Description`` of each limit state's damage state, in increasing ``limit_state``; None:
        ``Peak sliding displacement above <limit> m``.

    Returns
    -------
    pathlib.Path
        ``path``.  Each file is written to a temporary file in its folder and renamed: nothing is
        left half-written, and a table that fails its checks writes nothing.
    """
    table = damage_db(theta, beta, component_ids=component_ids, incomplete=incomplete)
    csv_text = _csv_text(table)
    json_text = None if json_path is None else _json_text(table, description, short_name, component_text, comments,
                                                          limit_texts)
    path = Path(path)
    _write_atomic(path, csv_text)
    if json_text is not None:
        _write_atomic(Path(json_path), json_text)
    return path
