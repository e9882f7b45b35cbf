"""Exact event-driven stick-slip solver (work in progress: kernel lands next)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Solution:
    pi1: float
    u_max: float
    pi1_residual: float
    u_residual: float
    tau_peak: float
    t_peak: float
    settled: bool
    model: str
    tau_end: float
    n_steps: int
    n_events: int
    history: object = None


@dataclass(frozen=True)
class Batch:
    pi1: np.ndarray
    pi1_residual: np.ndarray
    tau_peak: np.ndarray
    settled: np.ndarray
    model: np.ndarray
    tau_end: np.ndarray
    n_steps: np.ndarray
    n_events: np.ndarray


def solve(scene, rtol=None, history=False, method="exact", **options):
    raise NotImplementedError("solver kernel not landed yet")


def solve_many(scenes, rtol=None, method="exact", **options):
    raise NotImplementedError("solver kernel not landed yet")
