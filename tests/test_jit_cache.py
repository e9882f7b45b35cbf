"""The kernel cache shipped with the package: current with the sources, seeded safely, loaded by numba."""
from __future__ import annotations

import os
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from types import SimpleNamespace

import pytest

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


def test_the_shipped_kernels_are_compiled_for_the_portable_level_and_load_on_this_machine():
    """Every shipped entry is keyed by the portable processor, and numba here compiles for that one.

    So nothing is compiled on this machine, whichever processor built the cache; fails wherever
    numba would compile the kernels anyway (the README's promise would not hold there).
    """
    rows = jit_cache.status()
    assert jit_cache.TARGET.portable, jit_cache.TARGET.reason
    assert jit_cache.target_in_force() == jit_cache.PORTABLE_KEY
    for index in jit_cache.SHIPPED_DIR.glob("*.nbi"):
        assert {key[1][1:] for key in jit_cache.read_index(index)[2]} == {jit_cache.PORTABLE_KEY}, index.name
    assert [r["index"] for r in rows if r["cpu"] != r["entries"]] == []
    assert jit_cache.ready()


def _env(cache: Path, **extra) -> dict:
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CPU_NAME", "NUMBA_CPU_FEATURES",
                                                             jit_cache.ENV_SWITCH, "ISOSLIDE_CPU_TARGET")}
    return dict(env, NUMBA_CACHE_DIR=str(cache), **extra)


SOLVE = ("from isoslide.solver import warm_up, solve; from isoslide import Scene; warm_up(records=True, "
         "building=True); print(repr(solve(Scene(pi2=0.2, pi3=1.0, pi4=0.1)).pi1))")


def test_an_empty_numba_cache_is_seeded_and_numba_loads_the_shipped_kernels_without_compiling(tmp_path):
    """A fresh interpreter with an empty NUMBA_CACHE_DIR loads every shipped kernel: its cache stays as seeded.

    A cold compile (seeding off) gives the same answer bit for bit.
    """
    out = subprocess.run([sys.executable, "-c", SOLVE], env=_env(tmp_path), check=True, capture_output=True,
                         text=True)
    files = {p.name: p.read_bytes() for p in tmp_path.rglob("*") if p.is_file()}
    shipped = {p.name: p.read_bytes() for p in jit_cache.SHIPPED_DIR.iterdir()
               if p.suffix in (".nbi", ".nbc")}
    assert files == shipped, "numba compiled a kernel the shipped cache holds"
    env = _env(tmp_path / "cold", **{jit_cache.ENV_SWITCH: "0"})
    cold = subprocess.run([sys.executable, "-c", SOLVE.replace("warm_up(records=True, building=True); ", "")],
                          env=env, check=True, capture_output=True, text=True)
    assert float(cold.stdout) == float(out.stdout)


def test_warm_compiles_once_under_a_lock_while_other_callers_wait_and_then_load(tmp_path):
    """Three callers at once where the shipped kernels do not fit: one compiles, one line says so, two wait."""
    calls, lines = [], []

    def compile_all():
        calls.append(1)
        time.sleep(0.3)

    with ThreadPoolExecutor(3) as pool:
        done = list(pool.map(lambda _: jit_cache.warm(log=lines.append, compile_all=compile_all,
                                                      shipped_dir=tmp_path / "none", cache=tmp_path / "numba"),
                             range(3)))
    assert len(calls) == 1
    assert len(lines) == 1 and lines[0].startswith("isoslide: the shipped kernels do not fit here")
    assert sum(d.startswith("compiled for") for d in done) == 1
    assert sum(d.startswith("kernels compiled by another process") for d in done) == 2
    assert jit_cache.warm(log=lines.append, compile_all=compile_all, shipped_dir=tmp_path / "none",
                          cache=tmp_path / "numba").startswith("kernels compiled here earlier")
    assert len(calls) == 1


def test_warm_compiles_nothing_where_the_shipped_kernels_fit():
    """On a machine the shipped kernels fit, warm neither compiles nor prints."""
    lines = []
    assert jit_cache.warm(log=lines.append, compile_all=lambda: lines.append("compiled")).startswith(
        "shipped kernels load here")
    assert lines == []


@pytest.mark.slow
def test_host_tuned_kernels_compile_once_through_warm_and_answer_as_the_portable_ones(tmp_path):
    """ISOSLIDE_CPU_TARGET=host: warm compiles every kernel for this processor once, says so, and the
    next process loads them; the answer agrees with the portable kernels' to round-off."""
    env = _env(tmp_path, ISOSLIDE_CPU_TARGET="host")
    warm = [sys.executable, "-m", "isoslide.jit_cache", "warm"]
    first = subprocess.run(warm, env=env, check=True, capture_output=True, text=True).stdout.splitlines()
    assert first[0].startswith("isoslide: the shipped kernels do not fit here (ISOSLIDE_CPU_TARGET=host)")
    assert first[1].startswith("isoslide kernels: compiled for")
    again = subprocess.run(warm, env=env, check=True, capture_output=True, text=True).stdout
    assert again.startswith("isoslide kernels: kernels compiled here earlier load")
    before = {p: p.stat().st_mtime_ns for p in tmp_path.rglob("*.nb*")}
    host = subprocess.run([sys.executable, "-c", SOLVE], env=env, check=True, capture_output=True, text=True)
    assert {p: p.stat().st_mtime_ns for p in tmp_path.rglob("*.nb*")} == before, "the host kernels compiled again"
    portable = subprocess.run([sys.executable, "-c", SOLVE], env=_env(tmp_path / "portable"), check=True,
                              capture_output=True, text=True)
    assert float(host.stdout) == pytest.approx(float(portable.stdout), rel=1e-12)
