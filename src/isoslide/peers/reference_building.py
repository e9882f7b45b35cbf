"""Independent event-driven reference solver of the general building (plain Python + SciPy).

The general building extends the paper's model (Fig. 1-b) to Fig. 1-a: a nonlinear isolator
(bilinear bearing, or sliding bearing with true stick), a flexible superstructure, and contents on
the base slab or on the roof.  Like :mod:`isoslide.peers.reference` it integrates phase by phase
with :func:`scipy.integrate.solve_ivp` (``DOP853``) and locates every transition with
``solve_ivp``'s events; it is written from the equations below only, independently of the compiled
kernel, to cross-check it.

Model (dimensionless: ``tau = t/T_p``, lengths ``a_p T_p**2``, masses ``M_b``, forces ``M_b a_p``)
------------------------------------------------------------------------------------------------
Parameters: ``mst = Pi11`` if ``Pi12 > 0`` else 0, ``mb = 1 - mst``, ``m = Pi8``,
``kd = (2 pi/Pi3)**2``, ``cb = 2 Pi4 (2 pi/Pi3)``, ``ks = mst (2 pi/Pi12)**2``,
``cs = 2 Pi13 (2 pi/Pi12) mst``, ``q = Pi9``, ``ke = Pi9/Pi10`` (bilinear), ``thr = Pi2/Pi5`` and
the friction level ``phi(v) = thr sech(Pi6 v) + Pi2 (1 - sech(Pi6 v)) + Pi7 |v|``.

States ``y = (x, x', xs, xs', u, u', fh)``: slab rel. ground, superstructure rel. slab, block rel.
its floor, hysteretic isolator force.  ``Ab = p + x''`` and ``As = Ab + xs''`` are absolute
accelerations, ``A_F`` that of the block's floor (``Ab`` on the base, ``As`` on the roof of a
flexible superstructure; a rigid superstructure's roof is the base)::

    F = kd x + cb x' + fh          (isolator on the slab)
    S = ks xs + cs xs'             (superstructure on the slab)
    slab:            mb Ab  = -F + S + [R on the base]
    superstructure:  mst As = -S + [R on the roof]
    block:           m (A_F + u'') = -R

Block: stuck ``u' = 0``, ``R = -m A_F`` while ``|A_F| <= thr``; sliding in ``s = sgn(u')``,
``R = m s phi(|u'|)``.  Isolator: linear ``fh = 0``; bilinear (elastic-perfectly-plastic,
stiffness ``ke``, strength ``q``) ``fh' = ke x'`` while elastic, ``fh = +-q`` while yielding (from
``|fh| = q`` until ``x'`` changes sign); sliding bearing ``fh = q sgn(x')`` while sliding, held
(``x' = x'' = 0``, ``Ab = p``) while the force it must supply,
``fh_needed = -mb p - kd x + S + [R on the base]``, is within ``|fh_needed| <= q``.  A fixed base
(``Pi3 = 0``) is a bearing held for ever.  Every acceleration is explicit in the mode (no linear
solve): with the slab held ``Ab = p``; moving, ``Ab = (-F + S)/(mb + m)`` (block stuck on the
base), ``(-F + S + R)/mb`` (sliding on the base) or ``(-F + S)/mb`` (block on the roof); the
superstructure ``As = -S/mst``, on the roof ``-S/(mst + m)`` (stuck) or ``(-S + R)/mst``
(sliding).

Mode selection
--------------
The block and a sliding bearing are frictional interfaces.  At every phase start (pulse
breakpoints and events) the interfaces at zero relative velocity (a stuck one, or one that just
stopped) get their modes chosen together: the combinations of (stuck, +1, -1) are tried in the
order all stuck; block stuck & bearing sliding; block sliding & bearing stuck; both sliding, and
the first *consistent* one is taken: every stuck interface's needed force within its limit
(``|A_F| <= thr``, ``|fh_needed| <= q``) and every sliding one accelerating in its own direction
(``s u'' > 0``, ``s x'' > 0``).  An interface whose stick limit was just reached (a breakaway
event) slides in the direction of its needed force; breakaways are force-continuous
(``phi(0) = thr``), so the other interface keeps its mode unless it is inconsistent by itself.
The bilinear bearing's yield (``|fh| = q``) and unloading (``x' = 0``) are force-continuous too.
``Pi1 = max |u|``, taken at the block's stops and at the end (``|u|`` peaks only there).
A stop (a sliding velocity ``v`` back to zero) is located as the root of ``s v / (t - t0)``, which
has the sign of ``s v`` but not its trivial root at a phase start ``t0`` from rest: a reversal
that starts with a tiny acceleration and ends within one step is still found.

Settlement bound
----------------
After the pulse, with the block stuck and the bearing held, elastic or linear, the system is free
and linear: ``M z'' + C z' + K z = f`` with ``z = (x, xs)`` (only ``xs`` with the slab held; none
for a held slab under a rigid superstructure).  About its equilibrium ``z*`` the energy
``E = (dz' M dz' + dz K dz)/2`` never increases (``C >= 0``), and every demand (the floor
acceleration ``A_F``, the bilinear force ``fh``, the held bearing's ``fh_needed``) is affine,
``d = d0 + c . w`` with ``w = (z - z*, z')``; so for all later times
``|d| <= |d0| + sqrt(2 E c^T P^-1 c)``, ``P = diag(K, M)`` (Cauchy-Schwarz).  The run settles
(``settled = True``) at the first moment every bound is within its limit: this is a terminal
event of the free phase, and changes only where the run stops, never ``Pi1``.  A run that has not
settled by the horizon (default ``tau_end + max(50 max(1, Pi3, Pi12), 50/rate)``, ``rate`` the
slowest decay rate of the free system, 0 for an undamped one) ends with ``settled = False``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp

from ..history import History
from ..pulses import accel_at
from ..scene import Scene
from .result import PeerResult, counted

__all__ = ["LEDGER_NAMES", "Building", "BuildingRun", "building_of", "default_horizon", "energies", "run_building",
           "solve_reference_building"]

# state indices
X, XD, XS, XSD, U, UD, FH = range(7)
N_STATE = 7
LEDGER_NAMES = ("work", "viscous", "isolator", "friction")
"""Ledger integrals appended to the state when requested: input work, viscous, isolator
(hysteretic or bearing friction) and contents-friction dissipation, units ``M_b a_p**2 T_p**2``."""

_ULP4 = 4e-15   # relative slack of the stick limits (see isoslide.peers.reference)


@dataclass(frozen=True)
class Building:
    """The scene's parameters in the model's units (see the module docstring).

    Attributes
    ----------
    mst, mb, m : float
        Superstructure, slab and block masses (units ``M_b``).
    kd, cb : float
        Isolator post-yield (linear) stiffness and viscous coefficient.
    ks, cs : float
        Superstructure stiffness and viscous coefficient.
    q, ke : float
        Isolator strength and elastic stiffness (``ke = 0`` unless bilinear).
    thr : float
        Static friction level ``Pi2/Pi5`` (units ``a_p``).
    kind : {"linear", "bilinear", "sliding", "fixed"}
        Isolator; ``"fixed"`` is a fixed base (``Pi3 = 0``).
    flexible, roof : bool
        Flexible superstructure; contents on its mass (flexible and ``floor == "roof"``).
    """

    mst: float
    mb: float
    m: float
    kd: float
    cb: float
    ks: float
    cs: float
    q: float
    ke: float
    thr: float
    kind: str
    flexible: bool
    roof: bool
    pi2: float = field(repr=False, default=0.0)
    pi6: float = field(repr=False, default=0.0)
    pi7: float = field(repr=False, default=0.0)

    @property
    def holds(self) -> bool:
        """True when the isolator can hold the slab still (sliding bearing or fixed base)."""
        return self.kind in ("sliding", "fixed")

    def phi(self, v: float) -> float:
        """Friction level ``phi(|v|)`` per unit block weight, units ``a_p``."""
        v = abs(v)
        a = self.pi6 * v
        sh = 0.0 if a > 700.0 else 1.0 / math.cosh(a)
        return self.thr * sh + self.pi2 * (1.0 - sh) + self.pi7 * v


def building_of(scene: Scene) -> Building:
    """The model parameters of a scene.

    Parameters
    ----------
    scene : Scene
        Any scene (the paper's model included).

    Returns
    -------
    Building
    """
    flexible = scene.pi12 > 0.0
    mst = scene.pi11 if flexible else 0.0
    if scene.pi3 == 0.0:
        kind, kd, cb = "fixed", 0.0, 0.0
    else:
        w = 2.0 * math.pi / scene.pi3
        kd, cb = w * w, 2.0 * scene.pi4 * w
        kind = "linear" if scene.pi9 == 0.0 else ("bilinear" if scene.pi10 > 0.0 else "sliding")
    if flexible:
        ws = 2.0 * math.pi / scene.pi12
        ks, cs = mst * ws * ws, 2.0 * scene.pi13 * ws * mst
    else:
        ks = cs = 0.0
    q = math.inf if kind == "fixed" else scene.pi9
    ke = scene.pi9 / scene.pi10 if kind == "bilinear" else 0.0
    return Building(mst=mst, mb=1.0 - mst, m=scene.pi8, kd=kd, cb=cb, ks=ks, cs=cs, q=q, ke=ke,
                    thr=scene.pi2 / scene.pi5, kind=kind, flexible=flexible,
                    roof=flexible and scene.floor == "roof", pi2=scene.pi2, pi6=scene.pi6, pi7=scene.pi7)


def _dynamics(B: Building, p: float, y, sb: int, si: int):
    """Accelerations and forces in the mode ``(sb, si)``.

    Parameters
    ----------
    B : Building
    p : float
        Ground acceleration (units ``a_p``).
    y : sequence
        State ``(x, x', xs, xs', u, u', fh, ...)``.
    sb : int
        Block mode: 0 stuck, +-1 sliding.
    si : int
        Isolator mode: 0 held (sliding bearing, fixed base) or elastic (bilinear), +-1 sliding or
        yielding; ignored for a linear isolator.

    Returns
    -------
    tuple
        ``(x'', xs'', u'', fh', A_F, fh_needed, R, fh)``; ``fh_needed`` is nan unless the slab is held.
    """
    held = B.holds and si == 0
    x, xd, xs, xsd, ud = y[X], y[XD], y[XS], y[XSD], y[UD]
    S = B.ks * xs + B.cs * xsd if B.flexible else 0.0
    if B.kind == "bilinear":
        fh = y[FH]
    elif B.kind == "sliding":
        fh = si * B.q
    else:
        fh = 0.0
    F = B.kd * x + B.cb * xd + fh
    m = B.m
    if sb != 0:
        ph = B.phi(ud)
        R = m * sb * ph
    if B.roof:
        Ab = p if held else (-F + S) / B.mb
        if sb == 0:
            As = -S / (B.mst + m)
            R = -m * As
            udd = 0.0
        else:
            As = (-S + R) / B.mst
            udd = -As - sb * ph
        AF = As
    else:
        if held:
            Ab = p
            if sb == 0:
                R = -m * p
                udd = 0.0
            else:
                udd = -p - sb * ph
        elif sb == 0:
            Ab = (-F + S) / (B.mb + m)
            R = -m * Ab
            udd = 0.0
        else:
            Ab = (-F + S + R) / B.mb
            udd = -Ab - sb * ph
        As = -S / B.mst if B.flexible else Ab
        AF = Ab
    if held:
        xdd = 0.0
        fh_need = -B.mb * p - B.kd * x + S + (0.0 if B.roof else R)
        fh = fh_need
    else:
        xdd = Ab - p
        fh_need = math.nan
    xsdd = As - Ab if B.flexible else 0.0
    fhd = B.ke * xd if (B.kind == "bilinear" and si == 0) else 0.0
    return xdd, xsdd, udd, fhd, AF, fh_need, R, fh


def _sign(a: float) -> int:
    return 1 if a > 0.0 else (-1 if a < 0.0 else 0)


def _choose(B: Building, p: float, y, sb: int, si: int, forced_b: int = 0, forced_i: int = 0):
    """Consistent modes of the frictional interfaces at a phase start (module docstring).

    Parameters
    ----------
    B, p, y
        Model, ground acceleration, state.
    sb, si : int
        Current modes.
    forced_b, forced_i : int
        Nonzero: the block (bearing) just broke away and slides in this direction.

    Returns
    -------
    (sb, si) : tuple of int
    """
    lim_b = B.thr * (1.0 + _ULP4)
    lim_q = B.q * (1.0 + _ULP4)
    if forced_b:
        cb_modes, free_b = [forced_b], False
    elif sb == 0 or y[UD] == 0.0:
        cb_modes, free_b = [0, 1, -1], True
    else:
        cb_modes, free_b = [_sign(y[UD])], False
    if B.kind == "sliding":
        if forced_i:
            ci_modes, free_i = [forced_i], False
        elif si == 0 or y[XD] == 0.0:
            ci_modes, free_i = [0, 1, -1], True
        else:
            ci_modes, free_i = [_sign(y[XD])], False
    elif B.kind == "fixed":
        ci_modes, free_i = [0], False
    else:
        ci_modes, free_i = [si], False
    combos = sorted(((b, i) for b in cb_modes for i in ci_modes),
                    key=lambda c: (c[0] != 0, B.kind == "sliding" and c[1] != 0))
    for b, i in combos:
        xdd, _, udd, _, AF, fh_need, _, _ = _dynamics(B, p, y, b, i)
        if b == 0 and abs(AF) > lim_b:
            continue
        if b != 0 and free_b and not b * udd > 0.0:
            continue
        if B.kind == "sliding":
            if i == 0 and abs(fh_need) > lim_q:
                continue
            if i != 0 and free_i and not i * xdd > 0.0:
                continue
        return b, i
    raise RuntimeError(f"no consistent stick/slip mode at the state {list(y[:N_STATE])!r}, p = {p!r}")


def _stop_event(s: int, k: int, t0: float, y0, acc0: float):
    """Event function of the velocity ``y[k]`` (moving in direction ``s``) returning to zero.

    ``s y[k] / (t - t0)``: the sign of ``s y[k]`` for ``t > t0`` but, for a phase that starts at
    rest, without the trivial root at ``t0`` itself (there it is ``s`` times the acceleration
    ``acc0``), so a slip that starts with a tiny acceleration and ends soon is still located.
    """
    v0 = s * y0[k]

    def g(t, yy):
        dt = t - t0
        if dt > 0.0:
            return s * yy[k] / dt
        return v0 if v0 != 0.0 else s * acc0

    return g


def _bilinear_mode(B: Building, p: float, y, sb: int, si: int) -> int:
    """Elastic (0) or yielding (+-1) mode of a bilinear bearing at a phase start (not an event)."""
    fh, xd = y[FH], y[XD]
    if si == 0:
        if abs(fh) >= B.q * (1.0 - _ULP4):
            s = _sign(fh)
            v = xd if xd != 0.0 else _dynamics(B, p, y, sb, s)[0]
            if s * v > 0.0:
                return s
        return 0
    v = xd if xd != 0.0 else _dynamics(B, p, y, sb, si)[0]
    return si if si * v > 0.0 else 0


def _free_system(B: Building, y, si: int):
    """The free linear system (``p = 0``, block stuck, bearing held/elastic/linear).

    Returns
    -------
    tuple
        ``(M, C, K, z_eq, idx, demands)``: mass, damping and stiffness matrices of the moving
        coordinates ``y[idx]`` (displacements; velocities are ``idx + 1``), their equilibrium, and
        a list of ``(limit, d0, c)``: each demand is ``d0 + c . (z - z_eq, z')``.
    """
    held = B.holds and si == 0
    m = B.m
    dem = []
    if held:
        if not B.flexible:
            if B.kind == "sliding":
                dem.append((B.q, -B.kd * y[X], np.zeros(0)))
            return np.zeros((0, 0)), np.zeros((0, 0)), np.zeros((0, 0)), np.zeros(0), [], dem
        mass = B.mst + (m if B.roof else 0.0)
        M, C, K = np.array([[mass]]), np.array([[B.cs]]), np.array([[B.ks]])
        idx = [XS]
        if B.roof:
            dem.append((B.thr, 0.0, -np.array([B.ks, B.cs]) / mass))
        if B.kind == "sliding":
            dem.append((B.q, -B.kd * y[X], np.array([B.ks, B.cs])))
        return M, C, K, np.zeros(1), idx, dem
    k1 = B.kd + B.ke
    off = y[FH] - B.ke * y[X] if B.kind == "bilinear" else 0.0   # fh = off + ke x while elastic
    x_eq = -off / k1
    fh_x = np.array([B.ke, 0.0])                     # d fh / d (x, x')
    if not B.flexible:
        M, C, K = np.array([[1.0 + m]]), np.array([[B.cb]]), np.array([[k1]])
        dem.append((B.thr, 0.0, -np.array([k1, B.cb]) / (1.0 + m)))
        if B.kind == "bilinear":
            dem.append((B.q, off + B.ke * x_eq, fh_x))
        return M, C, K, np.array([x_eq]), [X], dem
    m_slab = B.mb + (0.0 if B.roof else m)
    m_st = B.mst + (m if B.roof else 0.0)
    M = np.array([[m_slab + m_st, m_st], [m_st, m_st]])
    C = np.diag([B.cb, B.cs])
    K = np.diag([k1, B.ks])
    # w = (x - x_eq, xs, x', xs')
    if B.roof:
        dem.append((B.thr, 0.0, -np.array([0.0, B.ks, 0.0, B.cs]) / m_st))
    else:
        dem.append((B.thr, 0.0, np.array([-k1, B.ks, -B.cb, B.cs]) / m_slab))
    if B.kind == "bilinear":
        dem.append((B.q, off + B.ke * x_eq, np.array([B.ke, 0.0, 0.0, 0.0])))
    return M, C, K, np.array([x_eq, 0.0]), [X, XS], dem


def _settle_margin_fn(B: Building, y0, si: int):
    """``g(y)``: the smallest margin ``limit - (|d0| + sqrt(2 E c^T P^-1 c))`` over the demands.

    Non-decreasing along the free response; ``g >= 0`` means no interface can slip or yield again.
    Returns None when there is no demand (nothing can ever slip).
    """
    M, C, K, z_eq, idx, dem = _free_system(B, y0, si)
    if not dem:
        return None
    n = len(idx)
    P = np.zeros((2 * n, 2 * n))
    P[:n, :n], P[n:, n:] = K, M
    scale = [math.sqrt(float(c @ np.linalg.solve(P, c))) if n else 0.0 for _, _, c in dem]
    vel = [i + 1 for i in idx]

    def g(t, yy):
        if n:
            dz = np.array([yy[i] for i in idx]) - z_eq
            v = np.array([yy[i] for i in vel])
            two_e = float(dz @ K @ dz + v @ M @ v)
        else:
            two_e = 0.0
        r = math.sqrt(max(two_e, 0.0))
        return min(lim - (abs(d0) + r * s) for (lim, d0, _), s in zip(dem, scale, strict=True))

    return g


def _slowest_rate(B: Building) -> float:
    """Slowest decay rate of the free linear systems (0 if one of them is undamped)."""
    rates = []
    for si in ([0] if B.kind == "fixed" else [0, 1] if B.kind == "sliding" else [0]):
        y = np.zeros(N_STATE)
        if B.kind == "sliding" and si == 1:   # moving slab on kd alone
            Bl = Building(**{**B.__dict__, "kind": "linear", "q": 0.0})
            M, C, K, _, idx, _ = _free_system(Bl, y, 0)
        else:
            M, C, K, _, idx, _ = _free_system(B, y, si)
        n = len(idx)
        if n == 0:
            continue
        A = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(M, K), -np.linalg.solve(M, C)]])
        lam = np.linalg.eigvals(A)
        rate = float(np.min(np.abs(lam.real)))
        rates.append(0.0 if rate <= 1e-9 * float(np.max(np.abs(lam))) else rate)   # round-off of 0
    return min(rates) if rates else math.inf


def _periods(B: Building) -> list:
    """Natural periods of the structure's parts (units ``T_p``), to bound the integration step."""
    out = []
    if B.kd > 0.0:
        out.append(2.0 * math.pi * math.sqrt(1.0 / (B.kd + B.ke)))
    if B.flexible:
        out.append(2.0 * math.pi * math.sqrt(B.mst / B.ks))
    return out


def default_horizon(scene: Scene) -> float:
    """Default end of a run that does not settle, units of ``T_p`` (see the module docstring)."""
    B = building_of(scene)
    base = 50.0 * max(1.0, scene.pi3, scene.pi12)
    rate = _slowest_rate(B)
    extra = base if rate == 0.0 or not math.isfinite(rate) else max(base, 50.0 / rate)
    return float(scene.pulse.tau_end) + extra


@dataclass(frozen=True)
class BuildingRun:
    """A reference solve of the general building.

    Attributes
    ----------
    result : PeerResult
        As :func:`solve_reference_building` returns it.
    ledger : dict or None
        With ``ledger=True``: ``"work"``, ``"viscous"``, ``"isolator"``, ``"friction"`` (the
        integrals of :data:`LEDGER_NAMES` at the history's times) and ``"kinetic"``,
        ``"potential"`` (energies at those times), units ``M_b a_p**2 T_p**2``.
    """

    result: PeerResult
    ledger: dict | None = None


def energies(scene: Scene, h: History) -> tuple:
    """Kinetic and potential energy along a history (units ``M_b a_p**2 T_p**2``).

    Velocities are relative to the ground; the potential energy holds the springs ``kd``,
    ``ks`` and the bilinear bearing's elastic part ``fh**2 / (2 ke)``.

    Parameters
    ----------
    scene : Scene
    h : History
        From this module (building states present where the scene has them).

    Returns
    -------
    (kinetic, potential) : tuple of ndarray
    """
    B = building_of(scene)
    xs = h.xs if h.xs is not None else np.zeros_like(h.x)
    xsd = h.xsd if h.xsd is not None else np.zeros_like(h.x)
    v_st = h.xd + xsd
    v_blk = h.xd + (xsd if B.roof else 0.0) + h.ud
    kin = 0.5 * (B.mb * h.xd ** 2 + B.mst * v_st ** 2 + B.m * v_blk ** 2)
    pot = 0.5 * B.kd * h.x ** 2 + 0.5 * B.ks * xs ** 2
    if B.kind == "bilinear":
        pot = pot + h.fh ** 2 / (2.0 * B.ke)
    return kin, pot


def solve_reference_building(scene: Scene, rtol: float = 1e-12, history: bool = False,
                             atol: float = 1e-15, tau_max: float | None = None,
                             max_events: int = 100_000, max_work: int | None = None) -> PeerResult:
    """Solve one general-building scene with the event-driven DOP853 reference integrator.

    Parameters
    ----------
    scene : Scene
        Any scene (also the paper's model, solved with the general equations).  Starts at rest at
        ``scene.pulse.tau_start``.
    rtol, atol : float
        Tolerances passed to ``solve_ivp`` (DOP853); ``atol`` in the state's units.
    history : bool
        Also return the :class:`~isoslide.history.History` (with ``xs, xsd`` for a flexible
        superstructure, ``fh, iso_phase`` for a bilinear or sliding bearing).
    tau_max : float or None
        Horizon in units of ``T_p``; default :func:`default_horizon`.
    max_events : int
        Safety cap on the number of transitions (raises ``RuntimeError``).
    max_work : int or None
        Most right-hand-side evaluations (raises :class:`~isoslide.peers.result.WorkLimitError`).

    Returns
    -------
    PeerResult
        ``method = "reference"``, ``integrator = "DOP853"``; ``n_events`` counts the block's
        and the isolator's transitions.
    """
    return run_building(scene, rtol=rtol, history=history, atol=atol, tau_max=tau_max,
                        max_events=max_events, max_work=max_work).result


def run_building(scene: Scene, rtol: float = 1e-12, history: bool = False, atol: float = 1e-15,
                 tau_max: float | None = None, max_events: int = 100_000, max_work: int | None = None,
                 ledger: bool = False, settle: bool = True) -> BuildingRun:
    """:func:`solve_reference_building`, optionally with the energy ledger.

    Parameters
    ----------
    scene, rtol, history, atol, tau_max, max_events, max_work
        As :func:`solve_reference_building`.
    ledger : bool
        Integrate the input work and the dissipations along with the state and return them
        (implies ``history=True``); see :class:`BuildingRun`.
    settle : bool
        Stop at settlement (default); ``False`` follows the scene to the horizon (``settled``
        stays False), to check the settlement bound.

    Returns
    -------
    BuildingRun
    """
    B = building_of(scene)
    pulse = scene.pulse
    code = int(pulse.code)
    params = pulse.param_array
    history = history or ledger
    tau_end = float(pulse.tau_end)
    horizon = default_horizon(scene) if tau_max is None else float(tau_max)
    bps = [float(b) for b in pulse.breakpoint_array if b < horizon]
    periods = _periods(B)
    hmax_pulse = min([1.0 / 64.0] + [T / 32.0 for T in periods])
    hmax_free = min([max(1.0, scene.pi3) / 64.0] + [T / 32.0 for T in periods])
    lim_b = B.thr * (1.0 + _ULP4)
    lim_q = B.q * (1.0 + _ULP4)
    nl = len(LEDGER_NAMES) if ledger else 0

    tau = float(pulse.tau_start)
    y = np.zeros(N_STATE + nl)
    sb, si = 0, 0
    forced_b = forced_i = 0
    event_transition = False
    peak, tau_peak = 0.0, tau
    n_events = 0
    nfev = 0
    used = [0]
    settled = False
    zero_len = 0
    hist = [] if history else None

    def p_at(t):
        return accel_at(code, params, t)

    while True:
        if n_events > max_events:
            raise RuntimeError(f"more than {max_events} transitions; scene={scene!r}")
        # ---- modes at the phase start ---------------------------------------------------------
        # (an event was counted where it was located; elsewhere every mode change counts)
        p0 = p_at(tau)
        if B.kind == "bilinear" and not event_transition:
            new_si = _bilinear_mode(B, p0, y, sb, si)
            if new_si != si:
                n_events += 1
                si = new_si
                if si:
                    y[FH] = si * B.q
        nb, ni = _choose(B, p0, y, sb, si, forced_b, forced_i)
        if not event_transition:
            n_events += (nb != sb) + (B.kind == "sliding" and ni != si)
        sb, si = nb, ni
        forced_b = forced_i = 0
        event_transition = False
        if sb == 0:
            y[UD] = 0.0
        if B.holds and si == 0:
            y[XD] = 0.0
        free = tau >= tau_end and sb == 0 and si == 0
        settle_g = None
        if free and settle:
            settle_g = _settle_margin_fn(B, y, si)
            if settle_g is None or settle_g(tau, y) >= 0.0:
                settled = True
                break
        if tau >= horizon:
            break
        # ---- this segment ----------------------------------------------------------------------
        nxt = [b for b in bps if b > tau]
        t_end = min(nxt[0] if nxt else horizon, horizon)
        t_clip = math.nextafter(t_end, -math.inf)
        t0 = tau
        hmax = hmax_pulse if t0 < tau_end else hmax_free
        mb_, mi_ = sb, si

        def p_of(t, t0=t0, t_clip=t_clip):
            return accel_at(code, params, min(max(t, t0), t_clip))

        def rhs(t, yy, mb_=mb_, mi_=mi_):
            p = p_of(t)
            xdd, xsdd, udd, fhd, _, _, R, fh = _dynamics(B, p, yy, mb_, mi_)
            d = [yy[XD], xdd, yy[XSD], xsdd, yy[UD], udd, fhd]
            if nl:
                v_blk = yy[XD] + (yy[XSD] if B.roof else 0.0) + yy[UD]
                mom = B.mb * yy[XD] + B.mst * (yy[XD] + yy[XSD]) + B.m * v_blk
                visc = B.cb * yy[XD] ** 2 + B.cs * yy[XSD] ** 2
                iso = fh * yy[XD] - (fh * fhd / B.ke if B.kind == "bilinear" else 0.0)
                d += [-p * mom, visc, iso, R * yy[UD]]
            return np.array(d)

        specs = []          # (event function, what it marks, direction of the zero crossing)
        xdd0, _, udd0 = _dynamics(B, p0, y, sb, si)[:3]

        def add(fn, kind, direction=-1.0, specs=specs):
            specs.append((fn, kind, direction))

        if sb == 0:
            def ev_b(t, yy, sgn, mb_=mb_, mi_=mi_):
                return lim_b - sgn * _dynamics(B, p_of(t), yy, mb_, mi_)[4]
            add(lambda t, yy: ev_b(t, yy, 1.0), "block_break")
            add(lambda t, yy: ev_b(t, yy, -1.0), "block_break")
        else:
            add(_stop_event(sb, UD, t0, y, udd0), "block_stop")
        if B.kind == "sliding":
            if si == 0:
                def ev_i(t, yy, sgn, mb_=mb_):
                    return lim_q - sgn * _dynamics(B, p_of(t), yy, mb_, 0)[5]
                add(lambda t, yy: ev_i(t, yy, 1.0), "iso_break")
                add(lambda t, yy: ev_i(t, yy, -1.0), "iso_break")
            else:
                add(_stop_event(si, XD, t0, y, xdd0), "iso_stop")
        elif B.kind == "bilinear":
            if si == 0:
                add(lambda t, yy: B.q - yy[FH], "yield")
                add(lambda t, yy: B.q + yy[FH], "yield")
            else:
                add(_stop_event(si, XD, t0, y, xdd0), "unload")
        if settle_g is not None:
            add(settle_g, "settle", 1.0)
        for fn, _, direction in specs:
            fn.terminal, fn.direction = True, direction
        events, kinds = [s[0] for s in specs], [s[1] for s in specs]

        sol = solve_ivp(counted(rhs, max_work, "reference", used), (t0, t_end), y, method="DOP853",
                        rtol=rtol, atol=atol, events=events, max_step=hmax)
        nfev += sol.nfev
        if sol.status < 0:
            raise RuntimeError(f"solve_ivp failed: {sol.message}")
        if hist is not None:
            n = sol.t.size
            hist.append((sol.t, sol.y.copy(), np.full(n, sb, dtype=np.int8), np.full(n, si, dtype=np.int8)))
        if sol.status != 1:
            tau = float(sol.t[-1])
            y = np.array(sol.y[:, -1], dtype=float)
            if tau >= t_end:
                tau = t_end
            continue
        hits = [(te[0], ye[0], k) for te, ye, k in zip(sol.t_events, sol.y_events, kinds, strict=True)
                if len(te)]
        te, ye, kind = min(hits, key=lambda h: h[0])
        zero_len = zero_len + 1 if te <= t0 else 0
        if zero_len > 4:
            raise RuntimeError(f"zero-length stick/slip chatter at tau={te!r}; scene={scene!r}")
        tau = float(te)
        y = np.array(ye, dtype=float)
        if kind == "settle":
            settled = True
            break
        n_events += 1
        event_transition = True
        p = p_at(tau)
        if kind == "block_break":
            forced_b = -_sign(_dynamics(B, p, y, sb, si)[4])
        elif kind == "block_stop":
            y[UD] = 0.0
            if abs(y[U]) > peak:
                peak, tau_peak = abs(y[U]), tau
        elif kind == "iso_break":
            forced_i = _sign(_dynamics(B, p, y, sb, si)[5])
        elif kind == "iso_stop":
            y[XD] = 0.0
        elif kind == "yield":
            si = _sign(y[FH])
            y[FH] = si * B.q
        elif kind == "unload":
            si = 0
            y[FH] = math.copysign(B.q, y[FH])

    if abs(y[U]) > peak:
        peak, tau_peak = abs(y[U]), tau
    h = led = None
    if hist is not None:
        if hist:
            tt = np.concatenate([a for a, _, _, _ in hist])
            yy = np.concatenate([b for _, b, _, _ in hist], axis=1)
            ph_b = np.concatenate([c for _, _, c, _ in hist])
            ph_i = np.concatenate([d for _, _, _, d in hist])
        else:
            tt, yy = np.array([tau]), y[:, None]
            ph_b = ph_i = np.zeros(1, dtype=np.int8)
        fh = yy[FH].copy()
        if B.kind == "sliding":
            fh = np.array([_dynamics(B, p_at(t), col, b, i)[7] for t, col, b, i in
                           zip(tt, yy.T, ph_b, ph_i, strict=True)])
        iso = B.kind in ("bilinear", "sliding")
        h = History(tau=tt, x=yy[X].copy(), xd=yy[XD].copy(), u=yy[U].copy(), ud=yy[UD].copy(), phase=ph_b,
                    xs=yy[XS].copy() if B.flexible else None, xsd=yy[XSD].copy() if B.flexible else None,
                    fh=fh if iso else None, iso_phase=ph_i if iso else None)
        if ledger:
            led = {name: yy[N_STATE + k].copy() for k, name in enumerate(LEDGER_NAMES)}
            led["kinetic"], led["potential"] = energies(scene, h)
    res = PeerResult(method="reference", pi1=float(peak), pi1_residual=float(y[U]), tau_peak=float(tau_peak),
                     settled=settled, n_events=n_events, tau_end=float(tau), nfev=int(nfev), integrator="DOP853",
                     history=h)
    return BuildingRun(result=res, ledger=led)
