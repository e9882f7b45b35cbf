"""Optional peer: the paper's model and the general building (any number of storeys) in OpenSees.

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
from dataclasses import dataclass

import numpy as np

from ..model.shear_building import stiffness_matrix
from ..store.history import History, phase_of
from ..scene import Scene
from .result import PeerResult

__all__ = ["opensees_available", "opensees_model", "solve_opensees"]


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


@dataclass(frozen=True)
class OpenSeesModel:
    """The OpenSees model of a scene (dimensionless: masses ``M_b``, lengths ``a_p T_p^2``, time ``T_p``).

    Attributes
    ----------
    mb, mst, m : float
        Slab, superstructure and block masses (``mst = 0`` for a rigid superstructure; ``m`` at
        least ``1e-6`` so that the block node has a mass).
    kd, cb : float
        Isolator's linear stiffness and viscous coefficient (``Elastic`` with damping tangent).
    q, d_iso : float
        Isolator's ``ElasticPP`` part: yield force and yield displacement (``Pi10`` for a bilinear
        bearing, the stick displacement for a sliding bearing); ``q = 0``: none.
    ks, cs : float
        Single-storey superstructure's spring and dashpot (``Elastic`` with damping tangent); 0
        when rigid or with several storeys (see ``stiffnesses`` and ``damping``).
    thr, d_block : float
        Block's ``ElasticPP`` friction spring: yield force ``m thr`` and yield displacement.
    fixed, flexible, roof : bool
        Fixed base (the slab is the ground), flexible superstructure, contents on its top floor.
    storeys : int
        Floors above the slab (1 for a rigid superstructure).
    floor : int
        The contents' floor: 0 the slab, ``storeys`` the top floor (0 when rigid).
    masses : tuple of float
        Floor masses ``m_j = Pi11 w_j`` bottom to top (units ``M_b``; empty when rigid).
    stiffnesses : tuple of float
        Storey stiffnesses ``kappa r_j`` bottom to top, storey ``j`` joining floors ``j - 1`` and
        ``j`` (units ``M_b / T_p^2``; empty when rigid).
    damping : tuple of tuple of float
        Rows of the fixed-base damping matrix ``C_s = M_s Phi diag(2 Pi13 omega_i) Phi^T M_s``
        (units ``M_b / T_p``; empty when rigid).
    """

    mb: float
    mst: float
    m: float
    kd: float
    cb: float
    q: float
    d_iso: float
    ks: float
    cs: float
    thr: float
    d_block: float
    fixed: bool
    flexible: bool
    roof: bool
    storeys: int = 1
    floor: int = 0
    masses: tuple = ()
    stiffnesses: tuple = ()
    damping: tuple = ()

    def matrices(self) -> tuple:
        """Fixed-base mass, stiffness and damping matrices ``(M_s, K_s, C_s)`` of the floors.

        Returns
        -------
        (ndarray, ndarray, ndarray)
            ``storeys x storeys`` (units ``M_b``, ``M_b / T_p^2``, ``M_b / T_p``), floor 1 first;
            empty arrays for a rigid superstructure.
        """
        return (np.diag(self.masses), stiffness_matrix(self.stiffnesses),
                np.array(self.damping, dtype=float).reshape(len(self.masses), len(self.masses)))

    def links(self) -> list:
        """The superstructure's two-node elements: ``(i, j, k, c)`` for floors ``i < j`` (0 the slab).

        Storey ``j`` is a spring ``k`` between floors ``j - 1`` and ``j``; ``c`` is the dashpot
        that realises ``C_s`` exactly: ``-C_s[i, j]`` between two floors, the row sum of ``C_s``
        between floor ``j`` and the slab.  Pairs with neither a spring nor a dashpot are left out;
        the bottom storey comes first.

        Returns
        -------
        list of (int, int, float, float)
        """
        n = len(self.masses)
        out = []
        for i in range(n):
            for j in range(i + 1, n + 1):
                k = self.stiffnesses[j - 1] if j == i + 1 else 0.0
                c = math.fsum(self.damping[j - 1]) if i == 0 else -self.damping[i - 1][j - 1]
                if k != 0.0 or c != 0.0:
                    out.append((i, j, k, c))
        return out

    def periods(self) -> list:
        """Shortest natural periods of the model's stiff parts (units ``T_p``), for the time step."""
        out = [2.0 * math.pi * math.sqrt(self.d_block / self.thr)]       # block on its stick spring
        if not self.fixed:
            k = self.kd + (self.q / self.d_iso if self.q > 0.0 else 0.0)
            out.append(2.0 * math.pi * math.sqrt(self.mb / k))
        if self.flexible and self.storeys == 1:                         # slab and superstructure
            out.append(2.0 * math.pi * math.sqrt(self.mst * self.mb / (self.ks * (self.mst + self.mb))))
        elif self.flexible:                           # the building's highest mode, slab free unless held
            M, K, _ = self.matrices()
            if not self.fixed:
                k0 = self.stiffnesses[0]
                K = np.pad(K, ((1, 0), (1, 0)))
                K[0, 0] += k0 + self.kd + (self.q / self.d_iso if self.q > 0.0 else 0.0)
                K[0, 1] = K[1, 0] = -k0
                M = np.diag(np.concatenate(([self.mb], self.masses)))
            out.append(2.0 * math.pi / math.sqrt(max(_modes(M, K)[0])))
        return out


def _modes(M: np.ndarray, K: np.ndarray) -> tuple:
    """Eigenvalues ``omega^2`` (ascending) and mass-normalised modes of ``K phi = omega^2 M phi``, ``M`` diagonal."""
    s = 1.0 / np.sqrt(np.diag(M))
    lam, V = np.linalg.eigh(s[:, None] * K * s[None, :])
    return lam, s[:, None] * V


def _superstructure(scene: Scene) -> tuple:
    """Floor masses, storey stiffnesses and damping rows of a flexible superstructure (see :class:`OpenSeesModel`)."""
    n, mst = scene.storeys, scene.pi11
    ws = 2.0 * math.pi / scene.pi12
    if n == 1:                                   # closed forms of the single superstructure mass
        return (mst,), (mst * ws * ws,), ((2.0 * scene.pi13 * ws * mst,),)
    w = np.full(n, 1.0 / n) if scene.floor_masses is None else np.asarray(scene.floor_masses, dtype=float)
    r = np.ones(n) if scene.storey_stiffnesses is None else np.asarray(scene.storey_stiffnesses, dtype=float)
    M = np.diag(mst * w)
    lam, _ = _modes(M, stiffness_matrix(r))
    k = r * (ws * ws / lam[0])                   # fundamental fixed-base period T_s = Pi12
    lam, phi = _modes(M, stiffness_matrix(k))
    Mphi = M @ phi
    C = Mphi @ np.diag(2.0 * scene.pi13 * np.sqrt(lam)) @ Mphi.T
    C = 0.5 * (C + C.T)
    return tuple(float(v) for v in mst * w), tuple(float(v) for v in k), tuple(tuple(float(v) for v in row) for row in C)


def _positive(name: str, value) -> float:
    v = float(value)
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name} = {value!r} is out of range; allowed range: 0 < value < inf")
    return v


def opensees_model(scene: Scene, stiffness: float = 1e6, stick_displacement: float | None = None) -> OpenSeesModel:
    """The parameters of the OpenSees model of a scene (see :func:`solve_opensees`).

    Parameters
    ----------
    scene : Scene
        A scene with rate-independent friction (any isolator, superstructure and floor).
    stiffness : float
        Block's regularising stiffness ``K = k_r T_p^2 / m_EC``; its stick displacement is
        ``(Pi2/Pi5) / K`` (units ``a_p T_p^2``).
    stick_displacement : float or None
        Yield displacement (units ``a_p T_p^2``) of every frictional interface: the block's spring
        (then ``K = (Pi2/Pi5) / stick_displacement``, ``stiffness`` is not read) and a sliding
        bearing's.  None: the block's ``(Pi2/Pi5) / K``, for both.

    Returns
    -------
    OpenSeesModel
    """
    if not scene.rate_independent:
        raise ValueError("the OpenSees peer models Coulomb friction only (Pi7 = 0 and Pi5 = 1 or Pi6 = 0)")
    thr = scene.static_level
    if stick_displacement is None:
        d = thr / _positive("stiffness", stiffness)
    else:
        d = _positive("stick_displacement", stick_displacement)
    flexible = scene.pi12 > 0.0
    mst = scene.pi11 if flexible else 0.0
    fixed = scene.pi3 == 0.0
    kd = cb = q = 0.0
    d_iso = math.nan
    if not fixed:
        w = 2.0 * math.pi / scene.pi3
        kd, cb = w * w, 2.0 * scene.pi4 * w
        if scene.pi9 > 0.0:
            q, d_iso = scene.pi9, (scene.pi10 if scene.pi10 > 0.0 else d)
    ks = cs = 0.0
    storeys, floor, masses, stiffnesses, damping = 1, 0, (), (), ()
    if flexible:
        storeys, floor = scene.storeys, scene.floor_index
        masses, stiffnesses, damping = _superstructure(scene)
        if storeys == 1:
            ks, cs = stiffnesses[0], damping[0][0]
    return OpenSeesModel(mb=1.0 - mst, mst=mst, m=max(scene.pi8, 1e-6), kd=kd, cb=cb, q=q, d_iso=d_iso,
                         ks=ks, cs=cs, thr=thr, d_block=d, fixed=fixed, flexible=flexible,
                         roof=flexible and floor == storeys, storeys=storeys, floor=floor, masses=masses,
                         stiffnesses=stiffnesses, damping=damping)


GROUND, SLAB, TOP, BLOCK = 1, 2, 3, 4
"""Node tags: the ground (fixed), the slab, the superstructure's top floor and the block."""

FLOOR_TAG, LINK_TAG = 10, 10
"""Tags of floor ``j`` between the slab and the top floor (``FLOOR_TAG + j``), and of the
superstructure's links after the bottom storey (material and element ``LINK_TAG + l``; the
bottom storey is material and element 3)."""


def _floor_node(M: OpenSeesModel, j: int, slab: int) -> int:
    """Node tag of floor ``j`` (0 the slab, whose node is ``slab``)."""
    return slab if j == 0 else (TOP if j == M.storeys else FLOOR_TAG + j)


def _build(ops, M: OpenSeesModel) -> tuple:
    """Nodes, materials and elements of ``M``; returns the slab's and the floor's node tags."""
    ops.wipe()
    ops.model("basic", "-ndm", 1, "-ndf", 1)
    ops.node(GROUND, 0.0)
    ops.fix(GROUND, 1)
    slab = GROUND
    if not M.fixed:
        slab = SLAB
        ops.node(SLAB, 0.0)
        ops.mass(SLAB, M.mb)
        ops.uniaxialMaterial("Elastic", 1, M.kd, M.cb)          # k_d x + c_b x'
        ops.element("zeroLength", 1, GROUND, SLAB, "-mat", 1, "-dir", 1)
        if M.q > 0.0:                                            # hysteretic part f_h
            ops.uniaxialMaterial("ElasticPP", 2, M.q / M.d_iso, M.d_iso)
            ops.element("zeroLength", 2, GROUND, SLAB, "-mat", 2, "-dir", 1)
    floor = slab
    if M.flexible:
        for j in range(1, M.storeys + 1):
            ops.node(_floor_node(M, j, slab), 0.0)
            ops.mass(_floor_node(M, j, slab), M.masses[j - 1])
        for n, (i, j, k, c) in enumerate(M.links()):            # k (z_j - z_i) + c (z_j' - z_i')
            tag = 3 if n == 0 else LINK_TAG + n
            ops.uniaxialMaterial("Elastic", tag, k, c)
            ops.element("zeroLength", tag, _floor_node(M, i, slab), _floor_node(M, j, slab), "-mat", tag, "-dir", 1)
        floor = _floor_node(M, M.floor, slab)
    ops.node(BLOCK, 0.0)
    ops.mass(BLOCK, M.m)
    k_r = M.m * M.thr / M.d_block
    ops.uniaxialMaterial("ElasticPP", 4, k_r, M.d_block)        # the block's friction, yield force m thr
    ops.element("zeroLength", 4, floor, BLOCK, "-mat", 4, "-dir", 1)
    return slab, floor


def _disp(ops, node: int) -> float:
    return ops.nodeDisp(node, 1) if node != GROUND else 0.0


def _vel(ops, node: int) -> float:
    return ops.nodeVel(node, 1) if node != GROUND else 0.0


def _at_limit(force: float, limit: float, rate: float) -> int:
    """+1 / -1 when an ``ElasticPP`` force is at its yield ``limit`` and moving that way, else 0."""
    if abs(force) >= limit * (1.0 - 1e-9) and force * rate > 0.0:
        return 1 if force > 0.0 else -1
    return 0


TOL, ITERATIONS = 1e-14, 50
"""Newton's convergence test: displacement increment norm (units ``a_p T_p^2``) and most iterations."""

RETRIES = (("NewtonLineSearch",), ("ModifiedNewton", "-initial"))
"""Algorithms a step whose Newton iterations cycle between elastic-plastic branches is retried with
(the initial-stiffness iteration with ``20 ITERATIONS``: slow, but it does not cycle)."""

SUBSTEPS, SUBSTEP_LEVELS = 10, 2
"""A step that still fails is split into ``SUBSTEPS`` substeps (the ground acceleration interpolated
linearly), at most ``SUBSTEP_LEVELS`` times over."""


def refuse_unmodelled_contents_and_motion(scene: Scene, peer: str, vertical: str) -> None:
    """``ValueError`` naming the group for what a one-component OpenSees peer of a rigid building does not model.

    Contents whose friction depends on speed (``Pi7 > 0``, or Stribeck ``Pi5 < 1`` with ``Pi6 > 0``),
    vertical ground motion (the peer's ``vertical`` normal force) and ground motion off the
    building's x axis; ``peer`` names the peer in the message.
    """
    if scene.pi7 != 0.0:
        raise ValueError(f"pi7 = {scene.pi7!r} (viscous contact) is not modelled by the {peer}; allowed: pi7 = 0 "
                         "(Coulomb friction of the contents)")
    if scene.pi5 != 1.0 and scene.pi6 != 0.0:
        raise ValueError(f"pi6 = {scene.pi6!r} with pi5 = {scene.pi5!r} (Stribeck friction of the contents) is not "
                         f"modelled by the {peer}; allowed: pi5 = 1 or pi6 = 0 (Coulomb)")
    if scene.vertical:
        raise ValueError(f"pi17 = {scene.pi17!r} (vertical ground motion) is not modelled by the {peer} ({vertical}); "
                         "allowed: pi17 = 0")
    if not scene.in_line:
        raise ValueError(f"pulse_y / angle (ground motion off the building's x axis) is not modelled by the {peer}; "
                         "allowed: the main pulse alone, angle = 0")


def _hold_static_load(ops, what: str) -> None:
    """Apply the loads of the current patterns in one static step and hold them constant from time 0.

    Newton on the full system (tolerance :data:`TOL`); on failure the model is wiped and a
    RuntimeError names ``what`` (the loads applied).
    """
    ops.constraints("Plain")
    ops.numberer("Plain")
    ops.system("FullGeneral")
    ops.test("NormDispIncr", TOL, ITERATIONS)
    ops.algorithm("Newton")
    ops.integrator("LoadControl", 1.0)
    ops.analysis("Static")
    if ops.analyze(1) != 0:
        ops.wipe()
        raise RuntimeError(f"OpenSees: the static analysis of {what} failed")
    ops.loadConst("-time", 0.0)
    ops.wipeAnalysis()


def _newmark_analysis(ops) -> None:
    """The transient analysis of the peers: average-acceleration Newmark, Newton on the full system."""
    ops.constraints("Plain")
    ops.numberer("Plain")
    ops.system("FullGeneral")
    ops.test("NormDispIncr", TOL, ITERATIONS)
    ops.algorithm("Newton")
    ops.integrator("Newmark", 0.5, 0.25)
    ops.analysis("Transient")


def _step(ops, dtau: float, level: int = 0) -> bool:
    """One Newmark step of ``dtau``, with the retries of :data:`RETRIES` and :data:`SUBSTEPS`."""
    if ops.analyze(1, dtau) == 0:
        return True
    ok = False
    for alg in RETRIES:
        ops.algorithm(*alg)
        ops.test("NormDispIncr", TOL, ITERATIONS * (20 if alg[0] == "ModifiedNewton" else 1))
        ok = ops.analyze(1, dtau) == 0
        ops.algorithm("Newton")
        ops.test("NormDispIncr", TOL, ITERATIONS)
        if ok:
            return True
    if level >= SUBSTEP_LEVELS:
        return False
    return all(_step(ops, dtau / SUBSTEPS, level + 1) for _ in range(SUBSTEPS))


def solve_opensees(scene: Scene, stiffness: float = 1e6, tau_max: float | None = None,
                   dtau: float | None = None, history: bool = False,
                   stick_displacement: float | None = None) -> PeerResult:
    """Pi1 of a Coulomb scene with OpenSees (elastic-perfectly-plastic springs, Newmark).

    Model in dimensionless units (masses ``M_b``, lengths ``a_p T_p^2``, time ``T_p``), one
    ``zeroLength`` element per spring, excitation ``UniformExcitation`` by the ground acceleration
    ``p`` (so node displacements are relative to the ground):

    * slab (mass ``1 - mst``) on the isolator: ``Elastic(k_d)`` with damping tangent ``c_b``
      (``k_d = (2 pi / Pi3)^2``, ``c_b = 2 Pi4 sqrt(k_d)``) in parallel with, for ``Pi9 > 0``, an
      ``ElasticPP`` of yield force ``Pi9`` and yield displacement ``Pi10`` (bilinear bearing) or the
      stick displacement (sliding bearing: true stick regularised); a fixed base (``Pi3 = 0``)
      ties the slab to the ground;
    * flexible superstructure (``Pi12 > 0``) of one storey: a mass ``mst = Pi11`` on ``Elastic(k_s)``
      with damping tangent ``c_s`` from the slab (``k_s = mst (2 pi / Pi12)^2``,
      ``c_s = 2 Pi13 mst 2 pi / Pi12``);
    * of ``N = storeys > 1`` storeys: floor masses ``m_j = Pi11 w_j`` (``w_j`` the scene's
      ``floor_masses``, or ``1/N``), storey ``j`` an ``Elastic(kappa r_j)`` between floors ``j - 1``
      and ``j`` (``r_j`` its ``storey_stiffnesses``, or 1; ``kappa`` sets the fixed-base fundamental
      period to ``Pi12``), and classical damping of ratio ``Pi13`` in every fixed-base mode,
      ``C_s = M_s Phi diag(2 Pi13 omega_i) Phi^T M_s``, realised exactly by ``Elastic`` dashpots:
      ``-C_s[i, j]`` between floors ``i`` and ``j``, the row sum of ``C_s`` between floor ``i`` and
      the slab (:meth:`OpenSeesModel.links`);
    * block (mass ``Pi8``, at least ``1e-6``) on its floor (``scene.floor_index``: the slab, a floor
      between, or the top floor; the slab when the superstructure is rigid) by an ``ElasticPP`` of
      yield force ``Pi8 Pi2/Pi5`` and yield displacement the stick displacement (the paper's
      bilinear regularisation).

    The ground acceleration is sampled every ``dtau`` (a ``Path`` series); average-acceleration
    Newmark with Newton iterations (a step whose iterations cycle between the springs' branches is
    retried as :data:`RETRIES` and :data:`SUBSTEPS` say).  The paper's model (``Pi9 = Pi12 = 0``) is the same model
    without the isolator's and superstructure's extra elements.

    Parameters
    ----------
    scene : Scene
        A scene with rate-independent friction (``Pi7 = 0`` and ``Pi5 = 1`` or ``Pi6 = 0``);
        starts at rest at ``pulse.tau_start``.
    stiffness : float
        Block's regularising stiffness ``K = k_r T_p^2 / m_EC`` (stick displacement
        ``(Pi2/Pi5) / K``).
    tau_max : float or None
        End time (units ``T_p``); default ``tau_end + 50 max(1, Pi3, Pi12)``.
    dtau : float or None
        Time step (units ``T_p``); default ``min(1e-3, T_min / 10)``, ``T_min`` the shortest
        period of :meth:`OpenSeesModel.periods` (block's stick spring, isolator's initial
        stiffness, slab with superstructure: its highest mode).
    history : bool
        Also return the step-by-step :class:`~isoslide.store.history.History` (``phase``: the block's
        spring at its yield force in the direction of ``u'``; for a bilinear or sliding bearing
        ``fh`` = its ``ElasticPP`` force and ``iso_phase`` likewise; ``xs, xsd`` for a flexible
        superstructure: relative to the slab, of its mass for one storey, else of every floor,
        one column per floor bottom to top; ``u, u'`` relative to the contents' floor).
    stick_displacement : float or None
        Yield displacement (units ``a_p T_p^2``) of the block's spring and of a sliding bearing's;
        None: ``(Pi2/Pi5) / K`` (see :func:`opensees_model`).

    Returns
    -------
    PeerResult
        ``method = "opensees"``, ``integrator = "Newmark"``, ``stiffness = K`` (the block's, also
        when set by ``stick_displacement``); cost in ``n_steps``; ``settled`` is False (the run
        always goes to ``tau_max``).
    """
    M = opensees_model(scene, stiffness, stick_displacement)
    ops = _opensees()
    pulse = scene.pulse
    if dtau is None:
        dtau = min(1e-3, min(M.periods()) / 10.0)
    dtau = _positive("dtau", dtau)
    end = tau_max if tau_max is not None else pulse.tau_end + 50.0 * max(1.0, scene.pi3, scene.pi12)
    n = int(math.ceil((end - pulse.tau_start) / dtau))
    if n < 1:
        raise ValueError(f"tau_max = {tau_max!r} is out of range; allowed range: > pulse.tau_start "
                         f"= {pulse.tau_start!r}")
    tt = pulse.tau_start + dtau * np.arange(n + 1)
    acc = pulse.accel(tt)
    slab, floor = _build(ops, M)
    ops.logFile(os.devnull, "-noEcho")     # the retries of _step are expected; a failure raises
    ops.timeSeries("Path", 1, "-dt", dtau, "-values", *acc.tolist())
    ops.pattern("UniformExcitation", 1, 1, "-accel", 1)
    _newmark_analysis(ops)
    iso = M.q > 0.0
    umax, tau_peak, u = 0.0, float(pulse.tau_start), 0.0
    rows = [] if history else None
    tops = [_floor_node(M, j, slab) for j in range(1, M.storeys + 1)] if M.flexible else []
    several = len(tops) > 1
    floors = [] if history and several else None      # every floor's (xs, xs') with several storeys
    if rows is not None:
        rows.append((tau_peak,) + (0.0,) * 7 + (0, 0))
        if floors is not None:
            floors.append(np.zeros((2, len(tops))))
    for i in range(n):
        if not _step(ops, dtau):
            ops.wipe()
            raise RuntimeError(f"OpenSees analysis failed at tau = {tt[i]:.6g} (dtau = {dtau!r})")
        u = ops.nodeDisp(BLOCK, 1) - _disp(ops, floor)
        if abs(u) > umax:
            umax, tau_peak = abs(u), float(tt[i + 1])
        if rows is not None:
            x, xd = _disp(ops, slab), _vel(ops, slab)
            fd = _vel(ops, floor)
            ud = ops.nodeVel(BLOCK, 1) - fd
            xs = _disp(ops, TOP) - x if M.flexible else 0.0
            xsd = _vel(ops, TOP) - xd if M.flexible else 0.0
            if floors is not None:
                floors.append(np.array([[_disp(ops, t) - x for t in tops], [_vel(ops, t) - xd for t in tops]]))
            fh = ops.eleResponse(2, "material", 1, "stress")[0] if iso else 0.0
            force = ops.eleResponse(4, "material", 1, "stress")[0]
            rows.append((float(tt[i + 1]), x, xd, u, ud, xs, xsd, fh,
                         _at_limit(force, M.m * M.thr, ud), _at_limit(fh, M.q, xd) if iso else 0))
    ops.wipe()
    h = None
    if rows is not None:
        a = np.array(rows, dtype=float)
        xs, xsd = (a[:, 5], a[:, 6]) if M.flexible else (None, None)
        if floors is not None:
            f = np.array(floors)
            xs, xsd = f[:, 0, :], f[:, 1, :]
        h = History(tau=a[:, 0], x=a[:, 1], xd=a[:, 2], u=a[:, 3], ud=a[:, 4],
                    phase=phase_of(a[:, 8] != 0.0, a[:, 4]), xs=xs, xsd=xsd,
                    fh=a[:, 7] if iso else None, iso_phase=a[:, 9].astype(np.int8) if iso else None)
    return PeerResult(method="opensees", pi1=umax, pi1_residual=float(u), tau_peak=tau_peak,
                      settled=False, tau_end=float(tt[-1]), n_steps=n, stiffness=M.thr / M.d_block,
                      integrator="Newmark", history=h)
