"""The processor the kernels are compiled for: the portable level wherever it runs, the host elsewhere."""
from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from isoslide import jit_cache



def test_an_x86_64_processor_compiles_for_the_portable_baseline():
    """Any x86-64 processor gets LLVM's generic x86-64 processor, the one the shipped kernels are built for."""
    for machine in ("x86_64", "AMD64"):
        t = jit_cache.choose_target(environ={}, machine=machine)
        assert (t.cpu, t.portable) == ("generic", True)


def test_other_architectures_and_the_host_switch_compile_for_the_host():
    """An aarch64 machine cannot run x86-64 code; ISOSLIDE_CPU_TARGET=host asks for host-tuned code."""
    t = jit_cache.choose_target(environ={}, machine="aarch64")
    assert (t.cpu, t.portable) == (jit_cache.host_cpu(), False) and "aarch64" in t.reason
    t = jit_cache.choose_target(environ={"ISOSLIDE_CPU_TARGET": " Host "}, machine="x86_64")
    assert (t.cpu, t.portable) == (jit_cache.host_cpu(), False) and "host" in t.reason


def test_a_users_numba_cpu_name_is_kept():
    """NUMBA_CPU_NAME set by the user (or inherited from an isoslide parent) is left in force."""
    t = jit_cache.choose_target(environ={"NUMBA_CPU_NAME": "skylake"}, machine="x86_64")
    assert t == jit_cache.Target("skylake", False, "NUMBA_CPU_NAME is set")
    for inherited in ({"NUMBA_CPU_NAME": "generic", "NUMBA_CPU_FEATURES": ""}, {"NUMBA_CPU_NAME": "generic"}):
        assert jit_cache.choose_target(environ=inherited, machine="x86_64").portable
    assert not jit_cache.choose_target(environ={"NUMBA_CPU_NAME": "generic", "NUMBA_CPU_FEATURES": "+avx2"}).portable


def test_an_unknown_target_switch_is_a_value_error_naming_it():
    """ISOSLIDE_CPU_TARGET must be portable or host."""
    with pytest.raises(ValueError, match=r"ISOSLIDE_CPU_TARGET = 'native' is not one of portable, host"):
        jit_cache.choose_target(environ={"ISOSLIDE_CPU_TARGET": "native"}, machine="x86_64")


def _in_force(env: dict) -> dict:
    script = ("import json, os; from isoslide import jit_cache; "
              "print(json.dumps([jit_cache.target_in_force(), os.environ.get('NUMBA_CPU_NAME')]))")
    out = subprocess.run([sys.executable, "-c", script], env=env, check=True, capture_output=True, text=True)
    return json.loads(out.stdout)


def test_importing_the_kernel_cache_module_sets_the_portable_processor_before_numba_compiles():
    """A fresh interpreter compiles for the x86-64 baseline once isoslide.jit_cache (which every kernel module
    imports first) is imported, and its child processes inherit the choice through the environment."""
    env = {k: v for k, v in os.environ.items()
           if k not in ("NUMBA_CPU_NAME", "NUMBA_CPU_FEATURES", jit_cache.TARGET_SWITCH)}
    (cpu, features), inherited = _in_force(env)
    expected = jit_cache.choose_target(environ={})
    assert cpu == expected.cpu
    if expected.portable:
        assert (cpu, features, inherited) == ("generic", "", "generic")
    host = _in_force(dict(env, ISOSLIDE_CPU_TARGET="host"))
    assert host[0][0] == jit_cache.host_cpu() and host[1] is None


def test_numba_started_by_another_library_keeps_its_host_target():
    """When numba compiled code before isoslide was imported, its processor cannot change, and TARGET says why."""
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CPU_NAME", "NUMBA_CPU_FEATURES")}
    script = ("import numba, json; numba.njit(lambda x: x + 1)(1); from isoslide import jit_cache; "
              "t = jit_cache.TARGET; print(json.dumps([t.cpu, t.portable, t.reason, jit_cache.target_in_force()[0]]))")
    out = subprocess.run([sys.executable, "-c", script], env=env, check=True, capture_output=True, text=True)
    cpu, portable, reason, in_force = json.loads(out.stdout)
    assert (cpu, portable, in_force) == (jit_cache.host_cpu(), False, jit_cache.host_cpu())
    expected = jit_cache.choose_target(environ={})
    assert reason == ("numba compiled code in this process before isoslide was imported" if expected.portable
                      else expected.reason)
