"""The compiled kernels that ship with isoslide: numba's cache, seeded so a fresh install starts warm.

Compiling the kernels (:mod:`isoslide.engine.kernel`, :mod:`isoslide.engine.building_kernel`,
:mod:`isoslide.engine.piecewise`, :mod:`isoslide.pulses`) takes about a minute of CPU; loading them from
numba's on-disk cache takes about one second. numba keeps that cache per source file, in the
``__pycache__`` beside it or under ``NUMBA_CACHE_DIR``, as one index per function
(``<module>.<function>-<line>.py<XY>.nbi``) and one object file per compiled signature
(``<...>.<n>.nbc``). An index is valid only for the numba version that wrote it and for the
source file's exact content (its sha256), and every entry is keyed by the signature, the CPU
(name and features) and the function's bytecode. None of that depends on where the package sits,
so a cache built from the same sources is valid in any checkout on the same kind of CPU.

isoslide ships such a cache in ``isoslide/data/kernel_cache``, built by ``python -m
isoslide.jit_cache build`` from :func:`isoslide.solver.warm_up` (every kernel signature the
pipeline compiles). At import, each kernel module calls :func:`seed`, which copies the shipped
files of that module into the directory numba reads, for every function numba has no index for
there yet. numba itself then decides, entry by entry, whether the shipped code fits (same sources,
numba, Python and CPU) or compiles as usual and adds its own entry. A user's existing cache is never
overwritten. ``ISOSLIDE_SHIPPED_KERNELS=0`` turns seeding off (to measure a truly cold compile).

``python -m isoslide.jit_cache check`` tells whether the shipped cache matches the sources, numba
and this CPU; the test suite fails when a kernel source changed without a rebuild.
"""
from __future__ import annotations

import argparse
import hashlib
import os
import pickle
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from .atomic import atomic_path

SHIPPED_DIR = Path(__file__).resolve().parent / "data" / "kernel_cache"
ENV_SWITCH = "ISOSLIDE_SHIPPED_KERNELS"
# the source files whose numba functions are cached (cache=True), by numba's file stem, in compile order
KERNEL_SOURCES = {"pulses": "pulses.py", "kernel": "engine/kernel.py", "piecewise": "engine/piecewise.py",
                  "friction": "model/friction.py", "modes": "engine/modes.py", "free_phase": "engine/free_phase.py",
                  "building_kernel": "engine/building_kernel.py", "planar_kernel": "engine/planar_kernel.py",
                  "planar_piecewise": "engine/planar_piecewise.py"}
KERNEL_MODULES = tuple(KERNEL_SOURCES)


def enabled() -> bool:
    """Whether :func:`seed` copies the shipped cache (``ISOSLIDE_SHIPPED_KERNELS`` not 0/false/off)."""
    return os.environ.get(ENV_SWITCH, "1").strip().lower() not in ("0", "false", "off", "no")


def _cache_dir(dispatcher) -> Path | None:
    """Directory numba reads and writes the cache of ``dispatcher``'s source file in (None: no cache)."""
    cache = getattr(dispatcher, "_cache", None)
    path = getattr(cache, "_cache_path", None)
    return Path(path) if path else None


def _copy_atomic(src: Path, dest: Path) -> None:
    with atomic_path(dest) as tmp:
        shutil.copyfile(src, tmp)


def seed(dispatcher, shipped_dir: Path = SHIPPED_DIR) -> int:
    """Copy the shipped cache of ``dispatcher``'s module where numba will look for it.

    Parameters
    ----------
    dispatcher : numba.core.registry.CPUDispatcher
        Any ``@njit(cache=True)`` function of the module; all functions of one source file share
        one cache directory.
    shipped_dir : pathlib.Path
        Directory of the shipped ``.nbi``/``.nbc`` files.

    Returns
    -------
    int
        Number of function indexes copied (0 when seeding is off, numba caching is off, the
        directory is not writable or numba already has an index for every function).

    Notes
    -----
    A function is seeded only when numba's directory has no index for it; its object files are
    written before its index, each by an atomic rename, so concurrent jobs seeding the same
    directory never let numba read an index whose data is not there.
    """
    target = _cache_dir(dispatcher)
    if not enabled() or target is None or not shipped_dir.is_dir():
        return 0
    stem = Path(dispatcher.py_func.__code__.co_filename).stem
    copied = 0
    try:
        target.mkdir(parents=True, exist_ok=True)
        for index in sorted(shipped_dir.glob(f"{stem}.*.nbi")):
            if (target / index.name).exists():
                continue
            base = index.name[: -len(".nbi")]
            for data in sorted(shipped_dir.glob(f"{base}.*.nbc")):
                _copy_atomic(data, target / data.name)
            _copy_atomic(index, target / index.name)
            copied += 1
    except OSError:
        return copied  # a read-only install: numba compiles (or caches elsewhere) as usual
    return copied


def read_index(path: Path) -> tuple[str, bytes, dict]:
    """Read the numba version, source stamp (sha256 of the source file) and entries of one ``.nbi`` index."""
    with open(path, "rb") as f:
        version = pickle.load(f)
        stamp, overloads = pickle.loads(f.read())
    return version, stamp, overloads


def _host_magic() -> tuple:
    from numba.core.registry import cpu_target

    return cpu_target.target_context.codegen().magic_tuple()


def status(shipped_dir: Path = SHIPPED_DIR) -> list[dict]:
    """Tell, per shipped function index, whether it is valid for these sources, this numba and this CPU.

    Returns
    -------
    list of dict
        Keys ``index`` (file name), ``module``, ``entries`` (compiled signatures), ``source``
        (the stamp equals the sha256 of the module's current source), ``numba`` (written by the
        installed numba version) and ``cpu`` (entries compiled for this CPU).
    """
    import numba

    here = Path(__file__).resolve().parent
    magic = _host_magic()
    sources = {}  # module -> sha256 of its source, hashed once for all its functions
    rows = []
    for index in sorted(shipped_dir.glob("*.nbi")):
        module = index.name.split(".", 1)[0]
        version, stamp, overloads = read_index(index)
        if module not in sources:
            sources[module] = hashlib.sha256((here / KERNEL_SOURCES[module]).read_bytes()).digest()
        rows.append({"index": index.name, "module": module, "entries": len(overloads),
                     "source": stamp == sources[module], "numba": version == numba.__version__,
                     "cpu": sum(1 for key in overloads if key[1] == magic)})
    return rows


def build(shipped_dir: Path = SHIPPED_DIR) -> list[str]:
    """Compile every kernel signature into an empty cache and make it the shipped one.

    Runs :func:`isoslide.solver.warm_up` (records and buildings included) in a fresh interpreter
    with an empty ``NUMBA_CACHE_DIR`` and seeding off, then replaces the ``.nbi``/``.nbc`` files
    of ``shipped_dir`` with the ones it wrote. Returns the names of the files shipped.
    """
    with tempfile.TemporaryDirectory(prefix="isoslide-kernels-") as tmp:
        env = dict(os.environ, NUMBA_CACHE_DIR=tmp, **{ENV_SWITCH: "0"})
        subprocess.run([sys.executable, "-c",
                        "from isoslide.solver import warm_up; warm_up(records=True, building=True)"],
                       env=env, check=True)
        written = [p for p in Path(tmp).rglob("*") if p.suffix in (".nbi", ".nbc")]
        stems = {p.name.split(".", 1)[0] for p in written}
        unknown = stems - set(KERNEL_MODULES)
        if unknown:
            raise RuntimeError(f"cached functions outside the kernel modules {KERNEL_MODULES}: {sorted(unknown)}")
        shipped_dir.mkdir(parents=True, exist_ok=True)
        for old in list(shipped_dir.glob("*.nbi")) + list(shipped_dir.glob("*.nbc")):
            old.unlink()
        for p in written:
            shutil.copy2(p, shipped_dir / p.name)
        return sorted(p.name for p in written)


def main(argv=None) -> int:
    """Command line: ``build`` the shipped cache, or ``check`` it (exit 1 when not valid here)."""
    parser = argparse.ArgumentParser(prog="python -m isoslide.jit_cache", description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    sub.add_parser("build", help="recompile every kernel signature and replace the shipped cache")
    sub.add_parser("check", help="is the shipped cache valid for these sources, numba and this CPU?")
    args = parser.parse_args(argv)
    if args.command == "build":
        names = build()
        size = sum((SHIPPED_DIR / n).stat().st_size for n in names)
        print(f"shipped {len(names)} files ({size / 2**20:.1f} MiB) in {SHIPPED_DIR}")
        return 0
    rows = status()
    if not rows:
        print(f"no shipped kernel cache in {SHIPPED_DIR}")
        return 1
    ok = True
    print(f"{'index':48s} entries source numba this-cpu")
    for r in rows:
        print(f"{r['index']:48s} {r['entries']:7d} {'ok' if r['source'] else 'STALE':6s} "
              f"{'ok' if r['numba'] else 'OTHER':5s} {r['cpu']:8d}")
        ok &= r["source"] and r["numba"] and r["cpu"] == r["entries"]
    print("shipped kernels valid here" if ok else
          "shipped kernels not (all) valid here: numba compiles what does not fit "
          "(python -m isoslide.jit_cache build refreshes them)")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
