"""Datasets that explain themselves: naming, CF metadata, provenance, atomic writes, merging.

Every dataset written by the pipeline carries

* CF-style global attributes: ``Conventions``, ``title``, ``history``,
  ``source`` (package version and git commit), ``references`` (the paper),
  plus ``isoslide_config``, the JSON text of the configuration it was made from;
* ``long_name`` (for a Pi-group: its definition) and ``units`` (``"1"`` for
  Pi-groups) on every coordinate and variable;
* the groups held fixed as scalar coordinates.

Nothing here embeds a wall-clock time, so the same configuration and code
give byte-identical files; :func:`assert_same_data` compares two datasets on
data and stable attributes (everything except ``source``/``history``).

Writes are atomic (:func:`write_netcdf`): a temporary file in the target
directory, then :func:`os.replace`, so a killed job never leaves a truncated
output under the final name.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import xarray as xr

from .atomic import atomic_path
from .groups import RESULT, group
from .models import FACETS, Facets
from .store.provenance import code_hash, git_commit, source_text  # noqa: F401 - re-exported

CONVENTIONS = "CF-1.10"

REFERENCES = (
    "Nikfar, F. and Konstantinidis, D.: Dimensional analysis of sliding contents in seismically "
    "isolated buildings under pulse-type excitation (the paper reproduced by isoslide); "
    "Newmark, N. M. (1965): Effects of earthquakes on dams and embankments, Geotechnique 15(2), 139-160."
)

VAR_META = {
    "pi1": RESULT.attrs(),
    "pi1_residual": dict(long_name="residual sliding displacement u_s(t_end) / (a_p T_p^2)", units="1",
                         comment="signed permanent displacement of the contents relative to the floor "
                                 "when the response has settled"),
    "tau_peak": dict(long_name="time of the peak sliding displacement, t_peak / T_p", units="1",
                     comment="dimensionless time tau = t / T_p on the pulse's own time axis "
                             "(Ricker: tau = 0 at the centre of the main lobe)"),
    "settled": dict(long_name="response settled: no further sliding possible at tau_end", units="1",
                    flag_values=np.array([0, 1], dtype=np.int8), flag_meanings="not_settled settled"),
    "tau_end": dict(long_name="dimensionless time t_end / T_p up to which the response was followed",
                    units="1"),
    "n_steps": dict(long_name="number of integration steps (solver diagnostic)", units="1"),
    "n_events": dict(long_name="number of stick/slip transitions located (solver diagnostic)", units="1"),
}

SOLUTION_FIELDS = ("pi1", "pi1_residual", "tau_peak", "settled", "tau_end", "n_steps", "n_events")

FACET_VARIABLES = {name: f"model_{name}" for name in FACETS}
"""Dataset variable of each facet of the model that ran (:data:`isoslide.models.FACETS`)."""


def encode_facets(facets, dims, shape=None) -> dict:
    """Facets of the models that ran -> one int8 CF flag variable per facet.

    Parameters
    ----------
    facets : sequence of Facets
        One :class:`isoslide.models.Facets` per scene.
    dims : tuple of str
        Dimensions of the variables.
    shape : tuple of int, optional
        Shape to give the codes (default: that of ``facets``).

    Returns
    -------
    dict
        ``{variable: (dims, codes, attrs)}`` for :data:`FACET_VARIABLES`; a facet's code is its
        value's position in :data:`isoslide.models.FACETS` (append-only).
    """
    arr = np.asarray(facets, dtype=object)
    bad = [f for f in arr.ravel() if not isinstance(f, Facets)]
    if bad:
        raise ValueError(f"facets = {bad[0]!r} is not an isoslide.models.Facets")
    out = {}
    for name, meanings in FACETS.items():
        codes = np.array([meanings.index(getattr(f, name)) for f in arr.ravel()], dtype=np.int8)
        attrs = {"long_name": f"model the solver ran: {name}", "units": "1",
                 "flag_values": np.arange(len(meanings), dtype=np.int8), "flag_meanings": " ".join(meanings)}
        out[FACET_VARIABLES[name]] = (dims, codes.reshape(arr.shape if shape is None else shape), attrs)
    return out


def decode_facets(ds: xr.Dataset) -> np.ndarray:
    """The facet variables of ``ds`` -> an object array of :class:`isoslide.models.Facets` (shape of the variables)."""
    names = list(FACETS)
    values = []
    for name in names:
        da = ds[FACET_VARIABLES[name]]
        meanings = np.array(da.attrs["flag_meanings"].split(), dtype=object)
        values.append(meanings[np.asarray(da.values, dtype=int)])
    shape = values[0].shape
    out = np.empty(shape, dtype=object)
    for idx in np.ndindex(shape):
        out[idx] = Facets(**{n: v[idx] for n, v in zip(names, values, strict=True)})
    return out


def model_labels(ds: xr.Dataset, result: str = "pi1") -> xr.DataArray:
    """Display labels of the models that ran (:meth:`isoslide.models.Facets.label`).

    From the facet variables and whether the contents slid: ``ds[result] > 0`` (``pi1``, or
    ``u_max`` in metres).
    """
    facets = decode_facets(ds)
    da = ds[FACET_VARIABLES["solver"]]
    slid = np.asarray(ds[result].values) > 0.0
    labels = np.vectorize(lambda f, s: f.label(bool(s)), otypes=[object])(facets, slid)
    return xr.DataArray(labels.astype(str), dims=da.dims, coords=da.coords,
                        attrs={"long_name": "model the solver ran (label)"})


# ----------------------------------------------------------------------------------------------
# provenance
# ----------------------------------------------------------------------------------------------

def pi_attrs(name: str) -> dict:
    """``long_name``/``units``/``comment`` of an input or output Pi-group (from the registry)."""
    return group(name).attrs()


def global_attrs(title: str, history: str, config: dict | None = None, **extra) -> dict:
    """CF-style global attributes; ``config`` is stored as JSON in ``isoslide_config``."""
    attrs = {
        "Conventions": CONVENTIONS,
        "title": title,
        "history": history,
        "source": source_text(),
        "references": REFERENCES,
    }
    if config is not None:
        attrs["isoslide_config"] = json.dumps(config, sort_keys=True)
    for k, v in extra.items():
        if v is not None:
            attrs[k] = v
    return attrs


# ----------------------------------------------------------------------------------------------
# chunk and study datasets
# ----------------------------------------------------------------------------------------------

def _solution_vars(batch, dims, shape=None) -> dict:
    out = {}
    for f in SOLUTION_FIELDS:
        val = np.asarray(getattr(batch, f))
        if shape is not None:
            val = val.reshape(shape)
        if f == "settled":
            out[f] = (dims, val.astype(np.int8), dict(VAR_META[f]))
        elif f in ("n_steps", "n_events"):
            out[f] = (dims, val.astype(np.int32), dict(VAR_META[f]))
        else:
            out[f] = (dims, val.astype(np.float64), dict(VAR_META[f]))
    out.update(encode_facets(batch.facets, dims, shape))
    return out


def chunk_dataset(grid, indices, batch) -> xr.Dataset:
    """Dataset of one chunk: dimension ``scene`` (flat grid index) with the Pi values as coordinates.

    Parameters
    ----------
    grid : isoslide.studies.sweep.Grid
    indices : array_like of int
        Flat indices of the chunk's scenes.
    batch : isoslide.Batch
        The solver's results for those scenes, in order.
    """
    idx = np.asarray(indices, dtype=np.int64)
    pts = grid.points(idx)
    coords = {"scene": ("scene", idx, {"long_name": f"flat C-order index of the scene in the grid of "
                                                    f"study {grid.name} (dims {', '.join(grid.dim_names)})",
                                       "units": "1"})}
    for name in grid.dim_names:
        coords[name] = ("scene", pts[name], pi_attrs(name))
    ds = xr.Dataset(_solution_vars(batch, ("scene",)), coords=coords)
    ds.attrs = global_attrs(
        title=f"isoslide chunk of study {grid.name}",
        history=f"isoslide.studies.sweep.solve_chunk: {idx.size} scenes (flat indices {idx[0]}..{idx[-1]}) "
                f"of study {grid.name}" if idx.size else "isoslide.studies.sweep.solve_chunk: empty chunk",
        config=grid.spec, study=grid.name)
    return ds


def merge_chunks(chunks, grid) -> xr.Dataset:
    """Merge chunk datasets into the labelled study dataset.

    The chunks are combined along ``scene`` with an exact coordinate join
    (:func:`xarray.combine_by_coords`, ``join="exact"``); every scene of the
    grid must appear exactly once and carry exactly the grid's Pi values,
    otherwise ``ValueError``.  The result has the grid's dimensions (``pi2``
    last), the fixed groups as scalar coordinates and CF metadata.

    Parameters
    ----------
    chunks : sequence of xarray.Dataset
        As written by :func:`chunk_dataset`, any order.
    grid : isoslide.studies.sweep.Grid
    """
    chunks = [c.copy() for c in chunks]
    for c in chunks:
        c.attrs = {}  # global attributes are set afresh below; variable attributes are kept
    every = np.concatenate([np.asarray(c["scene"].values) for c in chunks]) if chunks else np.array([])
    uniq, counts = np.unique(every, return_counts=True)
    if np.any(counts > 1):
        raise ValueError(f"chunks of study {grid.name} overlap: flat indices {uniq[counts > 1][:10].tolist()} "
                         f"appear more than once (stale chunks from another chunk_size?)")
    flat = xr.combine_by_coords(chunks, join="exact", combine_attrs="override", data_vars="all",
                                coords="different", compat="equals")
    expect = np.arange(grid.size)
    if flat.sizes["scene"] != grid.size or not np.array_equal(flat["scene"].values, expect):
        got = flat["scene"].values
        missing = np.setdiff1d(expect, got)
        raise ValueError(f"chunks of study {grid.name} do not cover its grid exactly: "
                         f"{got.size} scenes for {grid.size}; missing flat indices {missing[:10].tolist()}")
    pts = grid.points(expect)
    for name in grid.dim_names:
        if not np.array_equal(flat[name].values, pts[name]):
            raise ValueError(f"chunk coordinate {name} of study {grid.name} does not match the grid "
                             f"exactly (stale chunks from another configuration?)")

    dims = grid.dim_names
    shape = grid.shape
    data_vars = {}
    for var in flat.data_vars:
        da = flat[var]
        data_vars[var] = (dims, da.values.reshape(shape), dict(da.attrs))
    coords = {name: (name, np.asarray(grid.dims[name], dtype=float), pi_attrs(name)) for name in dims}
    for name, value in grid.fixed.items():
        coords[name] = ((), float(value), pi_attrs(name))
    if grid.beta is not None:
        battrs = {"long_name": "Stribeck transition constant beta = Pi6 / (a_p T_p)_ref",
                  "units": "s m-1",
                  "comment": f"reference a_p T_p = {grid.a_p_T_p:g} m/s turns beta into Pi6"}
        if np.ndim(grid.beta):
            coords["beta"] = ("pi6", np.asarray(grid.beta, dtype=float), battrs)
        else:
            coords["beta"] = ((), float(grid.beta), battrs)
    ds = xr.Dataset(data_vars, coords=coords)
    spec = grid.spec
    ds.attrs = global_attrs(
        title=f"isoslide master curves: {spec.get('title', grid.name)}",
        history=(f"isoslide.studies.sweep: {grid.size} scenes of study {grid.name} "
                 f"({' x '.join(f'{d}[{n}]' for d, n in zip(dims, shape, strict=True))}), solved in "
                 f"{len(chunks)} chunk(s) of at most {spec.get('chunk_size')} scenes and merged by "
                 f"isoslide.datasets.merge_chunks (exact coordinate join); no timestamps are stored "
                 f"so that identical inputs give identical files"),
        config=spec, study=grid.name, pulse=str(spec.get("pulse")), floor=spec.get("floor"),
        figure=None if spec.get("figure") is None else str(spec["figure"]),
        panel=spec.get("panel"),
        reference_a_p_T_p=f"{grid.a_p_T_p:g} m/s (turns beta in s/m into Pi6 = beta a_p T_p)",
        comment="Pi-groups use the repeating variables a_p, T_p, M_b (Buckingham); every curve is "
                "the same for all a_p, T_p, M_b. Pi1 = 0 means no sliding.")
    return ds


# ----------------------------------------------------------------------------------------------
# files
# ----------------------------------------------------------------------------------------------

def encoding_for(ds: xr.Dataset, complevel: int = 4) -> dict:
    """Compression (zlib with shuffle) for every numeric variable and non-scalar coordinate."""
    enc = {}
    for name, var in ds.variables.items():
        if var.dtype.kind in "fiub" and var.ndim > 0:
            enc[name] = {"zlib": True, "complevel": complevel, "shuffle": True}
    return enc


def write_netcdf(ds: xr.Dataset, path, complevel: int = 4) -> Path:
    """Write ``ds`` to ``path`` atomically (temporary file in the same directory + ``os.replace``).

    Numeric variables are zlib-compressed.  Returns the path.
    """
    path = Path(path)
    with atomic_path(path) as tmp:
        ds.to_netcdf(tmp, engine="netcdf4", format="NETCDF4", encoding=encoding_for(ds, complevel))
    return path


def open_dataset(path) -> xr.Dataset:
    """Open a dataset fully into memory and close the file."""
    with xr.open_dataset(path, engine="netcdf4") as ds:
        return ds.load()


UNSTABLE_ATTRS = ("source", "history")
"""Global attributes that may legitimately differ between two runs of the same configuration
(``source`` names the git commit)."""


def assert_same_data(a: xr.Dataset, b: xr.Dataset) -> None:
    """Assert two datasets are identical in data, coordinates and every stable attribute.

    This is how equality between an interrupted-and-resumed run and an uninterrupted one is
    checked when the code commit differs; with the same commit the files are byte-identical.
    """
    a2, b2 = a.copy(), b.copy()
    for d in (a2, b2):
        for k in UNSTABLE_ATTRS:
            d.attrs.pop(k, None)
    xr.testing.assert_identical(a2, b2)
