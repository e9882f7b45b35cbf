"""Optional peer: the paper's model and the general building in OpenSees.

Needs ``pip install -e .[peers]`` (``openseespy``; on Linux its binary ``openseespylinux``, pinned in
``environment.lock``: openseespy 3.8 needs Python >= 3.12, Python 3.11 gets 3.7.1.2).
:func:`opensees_available` says whether it imports.  The Linux wheel ships BLAS and LAPACK in
``openseespylinux/lib`` but its LAPACK finds BLAS only on the system's library path, so
:func:`_opensees` loads the bundled BLAS first: no system ``libblas3`` / ``liblapack3`` is needed.
"""

from __future__ import annotations

import ctypes
import importlib.util
import math
import os

import numpy as np

from ..history import History, phase_of
from ..scene import Scene
from .result import PeerResult

__all__ = ["opensees_available", "solve_opensees"]


def _opensees():
    """The ``openseespy.opensees`` module, after loading the wheel's own BLAS (see the module doc)."""
    spec = importlib.util.find_spec("openseespylinux")
    if spec is not None and spec.origin:
        blas = os.path.join(os.path.dirname(spec.origin), "lib", "libblas.so.3")
        if os.path.exists(blas):
            ctypes.CDLL(blas, mode=ctypes.RTLD_GLOBAL)
    import openseespy.opensees as ops

    return ops


def opensees_available() -> bool:
    """True when ``openseespy`` imports (``pip install -e .[peers]``)."""
    try:
        _opensees()
    except Exception:
        return False
    return True


def solve_opensees(scene: Scene, stiffness: float = 1e6, tau_max: float | None = None,
                   dtau: float | None = None, history: bool = False) -> PeerResult:
    """Pi1 of a Coulomb scene with OpenSees (elastic-perfectly-plastic friction spring, Newmark).

    Two-DOF model in dimensionless units (masses 1 and Pi8, lengths a_p T_p^2, time T_p):
    the base on a linear spring ``w^2`` with a dashpot ``2 z w`` (``Elastic`` material with
    damping tangent), the block on an ``ElasticPP`` spring of stiffness ``K Pi8`` and yield
    force ``Pi8 Pi2/Pi5`` (the paper's bilinear regularisation with a very large initial
    stiffness), under ``UniformExcitation`` by the ground acceleration ``p`` sampled every
    ``dtau`` (default ``min(1e-3, T_r / 10)``, ``T_r = 2 pi / sqrt(K)``), average-acceleration
    Newmark with Newton iterations.  A fixed base ties the block to the ground.  Coulomb
    friction only (``Pi7 = 0`` and ``Pi5 = 1`` or ``Pi6 = 0``).

    Parameters
    ----------
    scene : Scene
        A scene with rate-independent friction; starts at rest at ``pulse.tau_start``.
    stiffness : float
        Dimensionless regularising stiffness ``K = k_r T_p^2 / m_EC``.
    tau_max : float or None
        End time (units ``T_p``); default ``tau_end + 50 max(1, Pi3)``.
    dtau : float or None
        Time step (units ``T_p``), see above.
    history : bool
        Also return the step-by-step :class:`~isoslide.history.History` (``phase``:
        the spring at its yield force, in the direction of ``u'``).

    Returns
    -------
    PeerResult
        ``method = "opensees"``, ``integrator = "Newmark"``, ``stiffness = K``; cost in
        ``n_steps``; ``settled`` is False (the run always goes to ``tau_max``).
    """
    ops = _opensees()

    if not scene.rate_independent:
        raise ValueError("the OpenSees peer models Coulomb friction only")
    pulse = scene.pulse
    mu = scene.static_level
    K = float(stiffness)
    if dtau is None:
        dtau = min(1e-3, 2.0 * math.pi / math.sqrt(K) / 10.0)
    end = tau_max if tau_max is not None else pulse.tau_end + 50.0 * max(1.0, scene.pi3)
    n = int(math.ceil((end - pulse.tau_start) / dtau))
    tt = pulse.tau_start + dtau * np.arange(n + 1)
    acc = pulse.accel(tt)
    m_c = max(scene.pi8, 1e-6)
    ops.wipe()
    ops.model("basic", "-ndm", 1, "-ndf", 1)
    ops.node(1, 0.0)
    ops.fix(1, 1)
    ops.node(3, 0.0)
    ops.mass(3, m_c)
    floor = 1
    if not scene.fixed_base:
        w = 2.0 * math.pi / scene.pi3
        ops.node(2, 0.0)
        ops.mass(2, 1.0)
        ops.uniaxialMaterial("Elastic", 1, w * w, 2.0 * scene.pi4 * w)
        ops.element("zeroLength", 1, 1, 2, "-mat", 1, "-dir", 1)
        floor = 2
    k_r = K * m_c
    ops.uniaxialMaterial("ElasticPP", 2, k_r, mu * m_c / k_r)
    ops.element("zeroLength", 2, floor, 3, "-mat", 2, "-dir", 1)
    ops.timeSeries("Path", 1, "-dt", dtau, "-values", *acc.tolist())
    ops.pattern("UniformExcitation", 1, 1, "-accel", 1)
    ops.constraints("Plain")
    ops.numberer("Plain")
    ops.system("FullGeneral")
    ops.test("NormDispIncr", 1e-14, 50)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")
    umax, tau_peak, u = 0.0, float(pulse.tau_start), 0.0
    rows = [] if history else None
    if rows is not None:
        rows.append((tau_peak, 0.0, 0.0, 0.0, 0.0, False))
    for i in range(n):
        if ops.analyze(1, dtau) != 0:
            ops.wipe()
            raise RuntimeError("OpenSees analysis failed")
        u = ops.nodeDisp(3, 1) - (ops.nodeDisp(floor, 1) if floor != 1 else 0.0)
        if abs(u) > umax:
            umax, tau_peak = abs(u), float(tt[i + 1])
        if rows is not None:
            x = ops.nodeDisp(floor, 1) if floor != 1 else 0.0
            xd = ops.nodeVel(floor, 1) if floor != 1 else 0.0
            ud = ops.nodeVel(3, 1) - xd
            force = ops.eleResponse(2, "material", 1, "stress")[0]
            yielding = abs(force) >= mu * m_c * (1.0 - 1e-9) and force * ud > 0.0
            rows.append((float(tt[i + 1]), x, xd, u, ud, yielding))
    ops.wipe()
    h = None
    if rows is not None:
        a = np.array([r[:5] for r in rows], dtype=float)
        h = History(tau=a[:, 0], x=a[:, 1], xd=a[:, 2], u=a[:, 3], ud=a[:, 4],
                    phase=phase_of([r[5] for r in rows], a[:, 4]))
    return PeerResult(method="opensees", pi1=umax, pi1_residual=float(u), tau_peak=tau_peak,
                      settled=False, tau_end=float(tt[-1]), n_steps=n, stiffness=K,
                      integrator="Newmark", history=h)
