"""The kernel cache shipped with the package: current with the sources, seeded safely, loaded by numba."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

from isoslide import jit_cache


def _fake_dispatcher(cache_dir: Path, source: str = "/somewhere/kernel.py"):
    code = SimpleNamespace(co_filename=source)
    return SimpleNamespace(_cache=SimpleNamespace(_cache_path=str(cache_dir)),
                           py_func=SimpleNamespace(__code__=code))


def test_shipped_kernel_cache_was_built_from_the_current_kernel_sources_by_the_installed_numba():
    """Every shipped index is stamped with the sha256 of its module's source and the installed numba.

    Fails after any edit of a kernel module until ``python -m isoslide.jit_cache build`` is run.
    """
    rows = jit_cache.status()
    assert {r["module"] for r in rows} == set(jit_cache.KERNEL_MODULES)
    stale = [r["index"] for r in rows if not (r["source"] and r["numba"])]
    assert stale == [], f"rebuild with `python -m isoslide.jit_cache build`: {stale}"
    assert all(r["entries"] >= 1 for r in rows)


def test_seed_copies_each_function_once_data_first_and_never_overwrites_an_existing_index(tmp_path, monkeypatch):
    """Seeding copies index and object files of the module's functions only where numba has no index."""
    monkeypatch.delenv(jit_cache.ENV_SWITCH, raising=False)
    shipped = tmp_path / "shipped"
    shipped.mkdir()
    for name, body in [("kernel.run-10.py311.nbi", b"index-run"), ("kernel.run-10.py311.1.nbc", b"run-1"),
                       ("kernel.run-10.py311.2.nbc", b"run-2"), ("kernel.deriv-5.py311.nbi", b"index-deriv"),
                       ("kernel.deriv-5.py311.1.nbc", b"deriv-1"), ("pulses.accel_at-3.py311.nbi", b"other")]:
        (shipped / name).write_bytes(body)
    target = tmp_path / "numba" / "isoslide_abc"
    target.mkdir(parents=True)
    (target / "kernel.deriv-5.py311.nbi").write_bytes(b"user's own index")
    disp = _fake_dispatcher(target)

    assert jit_cache.seed(disp, shipped) == 1
    assert sorted(p.name for p in target.iterdir()) == [
        "kernel.deriv-5.py311.nbi", "kernel.run-10.py311.1.nbc", "kernel.run-10.py311.2.nbc", "kernel.run-10.py311.nbi"]
    assert (target / "kernel.deriv-5.py311.nbi").read_bytes() == b"user's own index"
    assert (target / "kernel.run-10.py311.2.nbc").read_bytes() == b"run-2"
    assert jit_cache.seed(disp, shipped) == 0  # already seeded

    fresh = tmp_path / "fresh"
    monkeypatch.setenv(jit_cache.ENV_SWITCH, "0")
    assert jit_cache.seed(_fake_dispatcher(fresh), shipped) == 0
    assert not fresh.exists()


def test_seed_does_nothing_without_a_numba_cache_or_a_shipped_directory(tmp_path):
    """A dispatcher without caching (or no shipped files) is left to numba."""
    no_cache = SimpleNamespace(py_func=SimpleNamespace(__code__=SimpleNamespace(co_filename="kernel.py")))
    assert jit_cache.seed(no_cache, tmp_path) == 0
    assert jit_cache.seed(_fake_dispatcher(tmp_path / "c"), tmp_path / "missing") == 0


def test_an_empty_numba_cache_is_seeded_and_numba_compiles_only_what_the_shipped_cache_lacks(tmp_path):
    """A fresh interpreter with an empty NUMBA_CACHE_DIR loads the shipped kernels instead of compiling.

    On a CPU the shipped cache was built for, warm-up leaves the seeded files as they are (nothing
    compiled); on another CPU numba compiles and adds its own entries beside them, and the answer is
    the same either way.
    """
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path))
    env.pop(jit_cache.ENV_SWITCH, None)
    script = ("from isoslide.solver import warm_up, solve; from isoslide import Scene; warm_up(records=True, "
              "building=True); print(repr(solve(Scene(pi2=0.2, pi3=1.0, pi4=0.1)).pi1))")
    out = subprocess.run([sys.executable, "-c", script], env=env, check=True, capture_output=True, text=True)
    files = {p.name: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    shipped = {p.name: p.read_bytes() for p in jit_cache.SHIPPED_DIR.iterdir()
               if p.suffix in (".nbi", ".nbc")}
    assert set(shipped) <= set(files)
    on_this_cpu = all(r["cpu"] == r["entries"] for r in jit_cache.status())
    if on_this_cpu:
        assert files == shipped, "numba compiled a kernel the shipped cache holds"
    else:
        assert len(files) > len(shipped), "numba neither loaded nor compiled the kernels"
    env[jit_cache.ENV_SWITCH] = "0"
    env["NUMBA_CACHE_DIR"] = str(tmp_path / "cold")
    cold = subprocess.run([sys.executable, "-c", script.replace("warm_up(records=True, building=True); ", "")],
                          env=env, check=True, capture_output=True, text=True)
    assert float(cold.stdout) == float(out.stdout)
