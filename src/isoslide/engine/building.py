"""The general building (the paper's Fig. 1-a) and the smallest exact model a scene requires.

Physics (dimensional; ground acceleration ``a_g(t) = a_p p(t/T_p)``, displacements
relative to the ground):

* **Isolated mass** ``M_b = m_b + m_st`` (slab and superstructure; the contents
  excluded), on an isolator ``F_iso = k_d x_b + c_b x_b' + f_h`` with
  ``T_b = 2 pi sqrt(M_b/k_d)`` and ``xi_b = c_b / (2 sqrt(k_d M_b))`` (``M_b``
  alone, as in the paper).  The hysteretic part ``f_h`` of strength ``Q``
  and yield displacement ``D_y``:

  - ``Q = 0``: ``f_h = 0``, the paper's linear isolator;
  - ``Q > 0, D_y > 0``, a **bilinear bearing** (lead-rubber): an
    elastic-perfectly-plastic spring of stiffness ``k_e = Q / D_y`` and yield
    force ``Q`` (initial stiffness ``k_d + k_e``, post-yield ``k_d``);
  - ``Q > 0, D_y = 0``, a **sliding bearing** (friction pendulum of radius
    ``R`` and friction ``mu_b``: ``k_d = M_b g / R``, ``Q = mu_b M_b g``, see
    :func:`isoslide.friction_pendulum`), rigid-plastic with true stick: the
    slab stays still while the force that holds it is within ``Q``.  A
    PTFE-type surface's friction rises with speed, ``mu(v) = mu_fast -
    (mu_fast - mu_slow) exp(-a |v|)`` (``Pi22 = mu_slow/mu_fast``, ``Pi23 = a
    a_p T_p``): the slab is held while that force is within the breakaway
    strength ``Q_s = Pi22 Q`` and slides against ``Q (1 - (1 - Pi22)
    exp(-Pi23 |x'|))``.  Every friction force and stick limit scales with the
    normal force ``1 + Pi17 p_z`` (vertical ground motion).

* **Superstructure**: rigid, or a mass ``m_st`` on the slab through ``k_s`` and
  ``c_s`` (``T_s = 2 pi sqrt(m_st/k_s)``, ``xi_s = c_s / (2 sqrt(k_s m_st))``).
* **Contents** on the slab ("base") or on the superstructure ("roof"), with the
  paper's Eq. 1 friction and true stick; the friction acts back on that floor.

Equations: slab ``m_b (a_g + x_b'') = -F_iso + (k_s x_s + c_s x_s') + [R on
the base]``; superstructure ``m_st (a_g + x_b'' + x_s'') = -(k_s x_s + c_s
x_s') + [R on the roof]``; block ``m (a_F + u'') = -F_f`` with ``R = F_f``.
The groups ``Pi9 = Q/(M_b a_p)``, ``Pi10 = D_y/(a_p T_p^2)``, ``Pi11 =
m_st/M_b``, ``Pi12 = T_s/T_p``, ``Pi13 = xi_s`` join the paper's ``Pi2 ..
Pi8`` (:mod:`isoslide.groups`); the compiled solver is
:mod:`isoslide.engine.building_kernel`.

The smallest exact model (:func:`reduction`)
--------------------------------------------
``paper``
    ``Pi9 = 0`` and ``Pi12 = 0``: the paper's model, solved by
    :mod:`isoslide.engine.kernel` (the contents' floor makes no difference).
``fixed-base``
    ``Pi3 = 0`` with the contents on the slab (or a rigid superstructure): the slab moves with
    the ground, so neither the isolator nor the superstructure acts on the contents.
``bearing-stuck``
    A sliding bearing (or a triple pendulum, whose first breakaway is its inner surfaces'
    ``Pi9 Pi26``) under a rigid superstructure that provably never slips:
    the force holding the slab is ``-(p + R)`` with ``|R| <= Pi8 max|p|`` for
    speed-independent contact (``Pi7 = 0``; a stuck block needs ``Pi8 |p|``,
    a sliding one ``Pi8 phi <= Pi8 mu_s g/a_p < Pi8 max|p|``), so
    ``(1 + Pi8) max|p| <= Q_s`` (the breakaway strength, ``Pi9`` or ``Pi9
    Pi22``) proves it; the scene runs as the paper's fixed base.
``bearing-elastic``
    A bilinear bearing under a rigid superstructure that provably never
    yields: the slab obeys ``x'' + c_b x' + (k_d + k_e) x = -p + R`` with
    ``|R| <= Pi8 max|p|`` (as above), so ``|x| <= ||h||_1 (1 + Pi8) max|p|``
    with ``h`` the impulse response of that oscillator; when ``k_e`` times this
    is within ``Q`` the scene runs as the paper's linear isolator of stiffness
    ``k_d + k_e`` (``Pi3' = Pi3 sqrt(k_d/(k_d + k_e))``, ``Pi4' = Pi4
    sqrt(k_d/(k_d + k_e))``).
``general``
    Vertical ground motion (the normal forces vary: no reduction holds), and anything else: :func:`isoslide.engine.building_kernel.run`, with the superstructure
    integrated only when flexible (``Pi12 > 0``) and the back-reaction dropped
    when ``Pi8 = 0``.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from . import building_kernel as bk
from . import free_phase
from ..groups import GROUPS, TFP_NAMES
from ..model.parts import building_of
from ..pulses import SAMPLED
from ..scene import Scene

REDUCTIONS = ("paper", "fixed-base", "bearing-stuck", "bearing-elastic", "general")
"""The models :func:`reduction` can choose, smallest first (see the module docstring)."""


def peak_accel(scene: Scene) -> float:
    """``max |p|`` of the scene's excitation (units of a_p).

    The analytic pulses of :mod:`isoslide.pulses` are normalised to a peak of 1; a sampled
    record is linear between samples, so its peak is the largest sample.
    """
    pulse = scene.pulse
    if pulse.code == SAMPLED:
        return float(np.max(np.abs(pulse.param_array[2:])))
    return 1.0


def impulse_l1(stiffness: float, damping: float) -> float:
    """``int_0^inf |h(t)| dt`` of a unit-mass oscillator ``x'' + c x' + k x = delta``.

    Under-damped: ``coth(pi a / (2 w_d)) / k`` with ``a = c/2``, ``w_d = sqrt(k - a^2)``;
    critically or over-damped (``h >= 0``): ``1 / k``; undamped: ``inf``.
    """
    if damping <= 0.0:
        return math.inf
    a = 0.5 * damping
    if a * a >= stiffness:
        return 1.0 / stiffness
    wd = math.sqrt(stiffness - a * a)
    return 1.0 / (math.tanh(math.pi * a / (2.0 * wd)) * stiffness)


def reduction(scene: Scene) -> tuple[str, Scene | None]:
    """The smallest exact model for ``scene`` and, where it is the paper's, the paper scene to solve.

    Returns
    -------
    (str, Scene or None)
        A name from :data:`REDUCTIONS` and the equivalent paper-model scene (``None`` for
        ``"general"``).
    """
    paper_keys = {"pi9": 0.0, "pi10": 0.0, "pi11": 0.0, "pi12": 0.0, "pi13": 0.0, "floor": "base", "storeys": 1,
                  "floor_masses": None, "storey_stiffnesses": None, **{n: GROUPS[n].default for n in TFP_NAMES}}
    parts = building_of(scene)
    iso, contents = parts.isolator, parts.contents
    if scene.paper_model:
        return "paper", replace(scene, **paper_keys)
    if scene.vertical or contents.tips:   # the reductions below hold for a sliding block with constant limits only
        return "general", None
    if iso.kind == "fixed" and contents.floor == 0:
        return "fixed-base", replace(scene, **paper_keys)
    if parts.superstructure.flexible:
        return "general", None
    if contents.viscous == 0.0:
        demand = (1.0 + contents.mass) * peak_accel(scene)
        if iso.kind in ("sliding", "tfp") and demand <= iso.breakaway:
            return "bearing-stuck", replace(scene, pi3=0.0, pi4=0.0, **paper_keys)
        if iso.kind == "bilinear":
            kd, ke = iso.stiffness, iso.elastic_stiffness
            k = kd + ke
            if ke * impulse_l1(k, iso.viscous) * demand <= iso.strength:
                f = math.sqrt(kd / k)
                return "bearing-elastic", replace(scene, pi3=scene.pi3 * f, pi4=scene.pi4 * f, **paper_keys)
    return "general", None


def superstructure(scene: Scene) -> tuple:
    """Floor masses, fixed-base stiffness and damping matrices of a flexible superstructure.

    Units ``M_b``, ``M_b / T_p^2`` and ``M_b / T_p``; see
    :meth:`isoslide.model.parts.Superstructure.matrices`.

    Returns
    -------
    (masses, Ks, Cs) : ndarrays of shapes ``(N,)``, ``(N, N)``, ``(N, N)``
    """
    return building_of(scene).superstructure.matrices()


def parameters(scene: Scene, pi8: float | None = None, coulomb: bool = False, rocking: bool | None = None) -> np.ndarray:
    """Model parameters of :func:`isoslide.engine.building_kernel.run` for a general scene.

    The scene's parts (:func:`isoslide.model.parts.building_of`) assembled into the kernel's
    array.  ``pi8`` overrides the contents' mass (0: one-way coupling); ``coulomb`` skips the
    Stribeck terms (friction at the static level ``Pi2/Pi5`` at every speed).  A rigid
    superstructure is one floor that moves with the slab.  A vertical ground motion
    (:attr:`isoslide.Scene.vertical`) appends its pulse's parameters, read by
    :func:`isoslide.engine.building_kernel.normal`.  ``rocking`` as for
    :func:`isoslide.model.parts.building_of` (default: a block that tips before it can slide).
    """
    parts = building_of(scene, rocking)
    iso, sup, contents = parts.isolator, parts.superstructure, parts.contents
    flex = sup.flexible
    n = sup.storeys if flex else 1
    zparams = scene.pulse_z.param_array if scene.vertical else np.zeros(0)
    n_t = bk.TFP_SIZE if iso.kind == "tfp" else 0
    P = np.zeros(bk.n_parameters(n, zparams.size, n_t))
    P[bk.P_MB] = 1.0 - sup.mass
    P[bk.P_MST] = sup.mass
    P[bk.P_M] = contents.mass if pi8 is None else pi8
    P[bk.P_KD] = iso.stiffness if iso.kind != "tfp" else 0.0   # a triple pendulum's force is all hysteretic
    P[bk.P_CB] = iso.viscous
    P[bk.P_N] = n
    if flex:
        masses, Ks, Cs = sup.matrices()
        P[bk.P_ARRAYS:bk.P_ARRAYS + n] = masses
        P[bk.P_ARRAYS + n:bk.P_ARRAYS + n + n * n] = Ks.ravel()
        P[bk.P_ARRAYS + n + n * n:bk.P_ARRAYS + n + 2 * n * n] = Cs.ravel()
        P[bk.P_KS] = Ks[0, 0]
        P[bk.P_CS] = Cs[0, 0]
        P[bk.P_FLOOR] = contents.floor
    P[bk.P_Q] = iso.strength
    P[bk.P_QS] = iso.breakaway
    if n_t:
        P[bk.P_TFP] = bk.n_parameters(n)
        P[bk.n_parameters(n):bk.n_parameters(n, 0, n_t)] = np.concatenate(iso.surfaces())
    P[bk.P_QA] = iso.rate if iso.speed_dependent else 0.0
    P[bk.P_KE] = iso.elastic_stiffness
    P[bk.P_THR] = contents.static
    P[bk.P_HOLD] = contents.static
    P[bk.P_PI2] = contents.kinetic
    P[bk.P_PI6] = contents.sharpness
    P[bk.P_PI7] = contents.viscous
    P[bk.P_COULOMB] = 1.0 if coulomb else 0.0
    P[bk.P_ROOF] = 1.0 if contents.floor > 0 else 0.0
    P[bk.P_KIND] = float(KINDS[iso.kind])
    P[bk.P_FLEX] = 1.0 if flex else 0.0
    P[bk.P_ZOFF] = bk.n_parameters(n, 0, n_t)
    if contents.rocks:
        g = contents.gravity
        P[bk.P_ROCK] = contents.aspect
        P[bk.P_RG] = g
        P[bk.P_RR] = contents.radius
        P[bk.P_RK] = 0.75 / contents.radius
        P[bk.P_RE] = contents.restitution
        P[bk.P_REPS] = CASCADE_END * math.atan(contents.aspect)
        P[bk.P_RMUS] = contents.static / g
        P[bk.P_RMUK] = contents.static / g
        if contents.tips:
            P[bk.P_HOLD] = g * contents.aspect
    if scene.vertical:
        P[bk.P_ZAMP] = scene.pi17
        P[bk.P_ZCODE] = scene.pulse_z.code
        P[bk.n_parameters(n, 0, n_t):] = zparams
    return P


CASCADE_END = 1e-3
"""A rocking block whose impacts provably keep it within this fraction of ``alpha`` comes to rest."""

KINDS = {"linear": bk.KIND_LINEAR, "bilinear": bk.KIND_BILINEAR, "sliding": bk.KIND_SLIDING, "fixed": bk.KIND_FIXED,
         "tfp": bk.KIND_TFP}
"""The kernel's code of each isolator kind (:data:`isoslide.model.parts.ISOLATOR_KINDS`)."""


def shortest_period(scene: Scene) -> float:
    """Shortest fixed-base period of a flexible superstructure (units of T_p); ``Pi12`` for one floor."""
    return building_of(scene).superstructure.shortest_period


def free_step(scene: Scene) -> float:
    """Longest step after the pulse (units of T_p): an eighth of the shortest period followed.

    The periods are the isolation period (the bilinear bearing's elastic one,
    ``Pi3 sqrt(k_d / (k_d + k_e))``, when shorter) and the superstructure's shortest fixed-base
    one (:func:`shortest_period`); a pulse period when there is none.
    """
    parts = building_of(scene)
    periods = [1.0] + [p for p in (parts.isolator.period, parts.isolator.shortest_period,
                                   parts.superstructure.shortest_period) if p > 0.0]
    return min(periods) / 8.0


def _empty_modal(ny: int) -> tuple:
    return (np.zeros((0, ny), dtype=np.complex128), np.zeros((0, 0), dtype=np.complex128),
            np.zeros((ny, 0), dtype=np.complex128), np.zeros(0, dtype=np.complex128))


def free_states(P: np.ndarray, held: bool) -> list[int]:
    """Indices of the states that move in the free linear phase after the pulse (block stuck).

    The slab's ``x, x'`` unless the isolator holds it (``held``), a flexible superstructure's floors,
    and an elastic bilinear bearing's force; the system they obey is
    :func:`isoslide.engine.building_kernel.free_system`.
    """
    kind = int(P[bk.P_KIND])
    n = int(P[bk.P_N])
    idx = [] if held else [bk.Y_X, bk.Y_XD]
    if P[bk.P_FLEX] != 0.0:
        idx += list(range(bk.Y_XS, bk.Y_XS + 2 * n))
    if kind == bk.KIND_BILINEAR and not held:
        idx.append(bk.state_size(n) - 1)
    return idx


def modal_data(scene: Scene, P: np.ndarray) -> tuple:
    """Modal data of the free linear phase of :func:`isoslide.engine.building_kernel.run`.

    For the free linear system after the pulse (block stuck; the isolator elastic, ``Wm, Cm, Vm,
    Lm``, or holding the slab, ``Wh, Ch, Vh, Lh``): ``W`` maps the state ``y`` to modal coordinates
    (rows: modes, columns: the states), ``C[j, k] = c_j . v_k`` gives demand ``j`` (0: the block's
    floor acceleration; 1: the bilinear bearing's force, or the force holding a sliding bearing) per
    unit of mode ``k``, ``V`` maps the modes back to the states (zero rows for the states that do not
    move) and ``L`` holds the eigenvalues (units ``1/T_p``), the modes ordered from the fastest to the
    slowest (:mod:`isoslide.engine.free_phase`).  ``W, C`` prove settlement; all four propagate the
    phase exactly.  Empty where the configuration cannot occur, has no moving state, or its
    eigenvectors are too ill-conditioned (condition number above
    :data:`isoslide.engine.building_kernel.FREE_MODES_COND`) for a trustworthy bound
    (:func:`isoslide.engine.building_kernel.spread_modes`).  The system's matrix is decomposed once
    for every scene that shares it (:func:`isoslide.engine.free_phase.modes`).

    Returns
    -------
    tuple of ndarray
        ``(Wm, Cm, Vm, Lm, Wh, Ch, Vh, Lh)``, complex128.
    """
    kind = int(P[bk.P_KIND])
    n = int(P[bk.P_N])
    ny = bk.state_size(n)
    code, params = scene.pulse.code, scene.pulse.param_array
    n_rows = 2 if kind in (bk.KIND_BILINEAR, bk.KIND_SLIDING, bk.KIND_TFP) else 1
    out = []
    for held in (False, True):
        idx = free_states(P, held)
        if held != (kind in (bk.KIND_SLIDING, bk.KIND_FIXED, bk.KIND_TFP)) or not idx:
            out.extend(_empty_modal(ny))
            continue
        idx = np.array(idx, dtype=np.int64)
        A, c = bk.free_system(P, code, params, held, idx, ny, n_rows)
        out.extend(bk.spread_modes(*free_phase.modes(A), c, idx, ny)[:4])
    return tuple(out)
