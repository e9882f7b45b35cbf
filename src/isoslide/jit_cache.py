"""The compiled kernels: the processor they are compiled for, the cache that ships with isoslide, one compile.

Compiling the kernels (:mod:`isoslide.engine.kernel`, :mod:`isoslide.engine.building_kernel`,
:mod:`isoslide.engine.piecewise`, :mod:`isoslide.pulses` and the others of :data:`KERNEL_SOURCES`)
takes minutes of CPU; loading them from numba's on-disk cache takes about one second. numba keeps
that cache per source file, in the ``__pycache__`` beside it or under ``NUMBA_CACHE_DIR``, as one
index per function (``<module>.<function>-<line>.py<XY>.nbi``) and one object file per compiled
signature (``<...>.<n>.nbc``). An index is valid only for the numba version that wrote it and for
the source file's exact content (its sha256), and every entry is keyed by the signature, the
processor compiled for (its name and feature string) and the function's bytecode. None of that
depends on where the package sits.

The processor
-------------
numba compiles for the host processor unless told otherwise, so a cache compiled on one processor
is never loaded on another (an AMD ``znver3`` cannot use what a ``znver4`` compiled). isoslide
compiles its kernels for LLVM's ``generic`` x86-64 processor instead: the baseline instruction set
(SSE2) that every x86-64 processor runs, tuned to none of them. Measured side by side
(``python -m isoslide.bench --cpu-targets``), that costs nothing measurable on the solver's scalar,
branchy kernels against code tuned to the host, nor against the x86-64-v3 level (AVX2, FMA), and
the answers agree to the bit. The choice (:func:`choose_target`), in order:

1. ``NUMBA_CPU_NAME`` set in the environment: the user's choice, left as it is (a child process of
   an isoslide process inherits the portable choice this way).
2. ``ISOSLIDE_CPU_TARGET=host``: numba's default, code tuned to this processor (compiled here).
3. Not an x86-64 processor: numba's default (the shipped kernels are x86-64 code).
4. Otherwise the portable baseline: ``NUMBA_CPU_NAME=generic`` and ``NUMBA_CPU_FEATURES=""``, set
   in ``os.environ`` before numba compiles or loads anything.

numba reads its processor once, when it first compiles or loads a function; :func:`select_target`
runs when this module is imported, which every kernel module does first. If numba has already
compiled something in the process (another library did), the host stays in force and
:data:`TARGET` says why.

The shipped cache
-----------------
isoslide ships a cache compiled for the portable processor in ``isoslide/data/kernel_cache``,
built by ``python -m isoslide.jit_cache build`` from :func:`isoslide.solver.warm_up` (every kernel
signature the pipeline compiles), so it loads on every x86-64 processor, whichever one built it.
At import, each kernel module calls :func:`seed`, which copies the shipped files of that module
into the directory numba reads, for every function numba has no index for there yet. numba itself
then decides, entry by entry, whether the shipped code fits (same sources, numba, Python and
target) or compiles as usual and adds its own entry. A user's existing cache is never overwritten.
``ISOSLIDE_SHIPPED_KERNELS=0`` turns seeding off (to measure a truly cold compile).

One compile
-----------
Where the shipped kernels do not fit (another numba, another architecture,
``ISOSLIDE_CPU_TARGET=host``), ``python -m isoslide.jit_cache warm`` (:func:`warm`) compiles them
all once, under a lock in numba's cache directory, and says so in one line; the pipeline runs it
before its first job, so parallel jobs load what it compiled instead of each compiling the same
kernels.

``python -m isoslide.jit_cache check`` tells whether the shipped cache matches the sources, numba
and the processor compiled for here; the test suite fails when a kernel source changed without a
rebuild, and when the shipped kernels do not load on the machine it runs on.
"""
from __future__ import annotations

import argparse
import hashlib
import os
import pickle
import platform
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

from .atomic import atomic_path

PORTABLE_CPU = "generic"
"""LLVM's name of the portable processor the shipped kernels are compiled for (the x86-64 baseline)."""
TARGET_SWITCH = "ISOSLIDE_CPU_TARGET"
"""Environment variable: ``portable`` (default) or ``host``."""
TARGET_CHOICES = ("portable", "host")
X86_64 = ("x86_64", "amd64")


@dataclass(frozen=True)
class Target:
    """The processor numba compiles isoslide's kernels for.

    Attributes
    ----------
    cpu : str
        LLVM processor name (``generic``, or the host's, e.g. ``znver3``).
    portable : bool
        Whether this is the portable processor the shipped kernels are compiled for.
    reason : str
        Why, in a few words.
    """

    cpu: str
    portable: bool
    reason: str


def host_cpu() -> str:
    """LLVM's name of this processor (e.g. ``znver3``)."""
    import llvmlite.binding as ll

    return ll.get_host_cpu_name()


def choose_target(environ=None, machine: str | None = None) -> Target:
    """Decide the processor to compile for, without changing anything (rules in the module docstring).

    Parameters
    ----------
    environ : mapping, optional
        The environment (default ``os.environ``).
    machine : str, optional
        ``platform.machine()`` by default.

    Raises
    ------
    ValueError
        ``ISOSLIDE_CPU_TARGET`` is neither ``portable`` nor ``host``.
    """
    environ = os.environ if environ is None else environ
    user_cpu = environ.get("NUMBA_CPU_NAME")
    if user_cpu:
        # numba's own default features for "generic" are none (""), as isoslide sets them
        portable = user_cpu == PORTABLE_CPU and environ.get("NUMBA_CPU_FEATURES", "") == ""
        return Target(user_cpu, portable, "NUMBA_CPU_NAME is set")
    wish = environ.get(TARGET_SWITCH, "portable").strip().lower() or "portable"
    if wish not in TARGET_CHOICES:
        raise ValueError(f"{TARGET_SWITCH} = {environ.get(TARGET_SWITCH)!r} is not one of {', '.join(TARGET_CHOICES)}")
    if wish == "host":
        return Target(host_cpu(), False, f"{TARGET_SWITCH}=host")
    machine = (platform.machine() if machine is None else machine).lower()
    if machine not in X86_64:
        return Target(host_cpu(), False, f"the shipped kernels are x86-64 code, this is a {machine} processor")
    return Target(PORTABLE_CPU, True, "the x86-64 baseline the shipped kernels are compiled for")


def _numba_started() -> bool:
    """Whether numba's CPU code generator exists in this process (its processor is then fixed)."""
    registry = sys.modules.get("numba.core.registry")
    return registry is not None and "_toplevel_target_context" in vars(registry.cpu_target)


def select_target() -> Target:
    """Apply :func:`choose_target` to this process before numba compiles or loads any kernel.

    Sets ``NUMBA_CPU_NAME`` and ``NUMBA_CPU_FEATURES`` in ``os.environ`` for the portable target (and
    makes an imported numba read them again). Returns the target in force.
    """
    target = choose_target()
    if not target.portable or os.environ.get("NUMBA_CPU_NAME"):
        return target
    if _numba_started():
        return Target(host_cpu(), False, "numba compiled code in this process before isoslide was imported")
    os.environ["NUMBA_CPU_NAME"] = PORTABLE_CPU
    os.environ["NUMBA_CPU_FEATURES"] = ""
    config = sys.modules.get("numba.core.config")
    if config is not None:
        config.reload_config()
    return target


def target_in_force() -> tuple[str, str]:
    """The processor name and feature string numba compiles for in this process (its cache key)."""
    _triple, cpu, features = _host_magic()
    return cpu, features


TARGET = select_target()
"""The processor the kernels are compiled for in this process (chosen before numba compiles or loads any)."""

SHIPPED_DIR = Path(__file__).resolve().parent / "data" / "kernel_cache"
ENV_SWITCH = "ISOSLIDE_SHIPPED_KERNELS"
WARM_UP = "from isoslide.solver import warm_up; warm_up(records=True, building=True, speed_bearing=True)"
"""Python code that compiles every kernel signature the pipeline uses (run in a child interpreter)."""
PORTABLE_KEY = (PORTABLE_CPU, "")
"""The (processor, features) part of numba's cache key of every shipped entry."""
# the source files whose numba functions are cached (cache=True), by numba's file stem, in compile order
KERNEL_SOURCES = {"pulses": "pulses.py", "kernel": "engine/kernel.py", "piecewise": "engine/piecewise.py",
                  "friction": "model/friction.py", "modes": "engine/modes.py", "free_phase": "engine/free_phase.py",
                  "building_kernel": "engine/building_kernel.py", "exponential": "engine/exponential.py",
                  "planar_kernel": "engine/planar_kernel.py",
                  "planar_piecewise": "engine/planar_piecewise.py", "tfp_flow": "engine/tfp_flow.py",
                  "tfp_plane": "engine/tfp_plane.py"}
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
    """The cache key of the code numba compiles in this process: (triple, processor, features)."""
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
    """Compile every kernel signature for the portable level into an empty cache and make it the shipped one.

    Runs :func:`isoslide.solver.warm_up` (records and buildings included) in a fresh interpreter
    with an empty ``NUMBA_CACHE_DIR``, seeding off and the portable processor forced
    (:func:`choose_target`), then replaces the ``.nbi``/``.nbc`` files of ``shipped_dir``
    with the ones it wrote. Returns the names of the files shipped.

    Raises
    ------
    RuntimeError
        There is no portable processor here, or an entry was compiled for another target.
    """
    target = choose_target(environ={})
    if not target.portable:
        raise RuntimeError(f"cannot build the shipped kernels here: {target.reason}")
    with tempfile.TemporaryDirectory(prefix="isoslide-kernels-") as tmp:
        env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CPU_NAME", "NUMBA_CPU_FEATURES")}
        env.update({"NUMBA_CACHE_DIR": tmp, ENV_SWITCH: "0", TARGET_SWITCH: "portable"})
        subprocess.run([sys.executable, "-c", WARM_UP], env=env, check=True)
        written = [p for p in Path(tmp).rglob("*") if p.suffix in (".nbi", ".nbc")]
        stems = {p.name.split(".", 1)[0] for p in written}
        unknown = stems - set(KERNEL_MODULES)
        if unknown:
            raise RuntimeError(f"cached functions outside the kernel modules {KERNEL_MODULES}: {sorted(unknown)}")
        others = {key[1][1:] for p in written if p.suffix == ".nbi" for key in read_index(p)[2]} - {PORTABLE_KEY}
        if others:
            raise RuntimeError(f"entries compiled for {sorted(others)}, not for {PORTABLE_KEY}")
        shipped_dir.mkdir(parents=True, exist_ok=True)
        for old in list(shipped_dir.glob("*.nbi")) + list(shipped_dir.glob("*.nbc")):
            old.unlink()
        for p in written:
            shutil.copy2(p, shipped_dir / p.name)
        return sorted(p.name for p in written)


def ready(shipped_dir: Path = SHIPPED_DIR) -> bool:
    """Whether every shipped kernel fits these sources, this numba and the processor compiled for here."""
    rows = status(shipped_dir)
    return bool(rows) and all(r["source"] and r["numba"] and r["cpu"] == r["entries"] for r in rows)


def _warm_key() -> str:
    """What a kernel compiled here depends on: numba's version, the target and every kernel source."""
    import numba

    here = Path(__file__).resolve().parent
    h = hashlib.sha256(repr((numba.__version__, sys.version_info[:2], _host_magic())).encode())
    for module in KERNEL_MODULES:
        h.update((here / KERNEL_SOURCES[module]).read_bytes())
    return h.hexdigest()[:16]


def _lock_dir() -> Path:
    """Where :func:`warm` keeps its lock and markers: beside numba's cache of the kernels.

    ``NUMBA_CACHE_DIR`` when set; else the kernels' ``__pycache__`` where numba writes it when
    writable; else ``~/.cache/isoslide``.
    """
    if os.environ.get("NUMBA_CACHE_DIR"):
        return Path(os.environ["NUMBA_CACHE_DIR"])
    in_tree = Path(__file__).resolve().parent / "engine" / "__pycache__"
    try:
        in_tree.mkdir(parents=True, exist_ok=True)
        if os.access(in_tree, os.W_OK):
            return in_tree
    except OSError:
        pass
    return Path.home() / ".cache" / "isoslide"


def _compile_in_child() -> None:
    subprocess.run([sys.executable, "-c", WARM_UP], check=True)


def warm(log=print, compile_all=_compile_in_child, shipped_dir: Path = SHIPPED_DIR, cache: Path | None = None) -> str:
    """Have every kernel of the pipeline compiled for this process's target, compiling each at most once.

    When the shipped kernels fit (:func:`ready`), nothing is compiled. Otherwise the first caller
    compiles them all into numba's cache (:data:`WARM_UP`, in a child interpreter with this
    environment) while holding a lock beside that cache, and leaves a marker there; callers that
    come while it compiles wait for the lock and then find the marker, and every later process loads
    what it compiled.

    Parameters
    ----------
    log : callable
        Receives one line when compiling.
    compile_all : callable
        Compiles every kernel.
    shipped_dir : pathlib.Path
        Directory of the shipped cache.
    cache : pathlib.Path, optional
        Directory of the lock and the marker (default :func:`_lock_dir`).

    Returns
    -------
    str
        What was done, in a few words.
    """
    import fcntl

    cpu, _features = target_in_force()
    if ready(shipped_dir):
        return f"shipped kernels load here ({cpu})"
    cache = _lock_dir() if cache is None else cache
    cache.mkdir(parents=True, exist_ok=True)
    marker = cache / f"isoslide-kernels-{_warm_key()}.done"
    if marker.exists():
        return f"kernels compiled here earlier load ({cpu})"
    with open(cache / "isoslide-kernels.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if marker.exists():
            return f"kernels compiled by another process load ({cpu})"
        why = "built from other sources or another numba" if TARGET.portable else TARGET.reason
        log(f"isoslide: the shipped kernels do not fit here ({why}); compiling them once for {cpu} "
            f"(a few minutes of one core); later runs load them from numba's cache")
        t0 = time.perf_counter()
        compile_all()
        with atomic_path(marker) as tmp:
            Path(tmp).write_text(f"{cpu}\n")
        return f"compiled for {cpu} in {time.perf_counter() - t0:.0f} s"


def main(argv=None) -> int:
    """Command line: ``build`` the shipped cache, or ``check`` it (exit 1 when not valid here)."""
    parser = argparse.ArgumentParser(prog="python -m isoslide.jit_cache", description=__doc__.split("\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    sub.add_parser("build", help="recompile every kernel signature and replace the shipped cache")
    sub.add_parser("check", help="is the shipped cache valid for these sources, numba and this CPU?")
    sub.add_parser("warm", help="compile the kernels once where the shipped ones do not fit (the pipeline's start)")
    args = parser.parse_args(argv)
    if args.command == "warm":
        print(f"isoslide kernels: {warm()}")
        return 0
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
    cpu, features = target_in_force()
    print(f"compiling for: {cpu}{' ' + features if features else ''} ({TARGET.reason}); "
          f"shipped for: {PORTABLE_KEY[0]}")
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
