"""Verification of the exact solver.

Every expected value here is either a closed form, an invariance of the
physics, or the public reference values of an independent solver (copied
into tests/public_cases.py; the product never reads ../shared).
"""

import math

import numpy as np
import pytest

import isoslide
from isoslide import Scene, paper_groups, pulses, solve, solve_many
from isoslide.engine import kernel
from isoslide import solver
from isoslide.solver import peak_stuck_demand

from public_cases import PHYSICAL_CASES as PUBLIC_PHYSICAL_CASES  # noqa: E402
from public_cases import PI_CASES as PUBLIC_PI_CASES  # noqa: E402


def rel(a, b):
    return abs(a - b) / abs(b) if b else abs(a)


@pytest.mark.parametrize("case", PUBLIC_PI_CASES)
def test_public_pi_cases(case):
    *pis, expected, _note = case
    sol = solve(Scene(*pis))
    assert sol.settled
    if expected == 0.0:
        assert sol.pi1 == 0.0 and sol.model == "no-slide"
    else:
        assert rel(sol.pi1, expected) < 1e-6


@pytest.mark.parametrize("kw, expected", PUBLIC_PHYSICAL_CASES)
def test_public_physical_cases(kw, expected):
    sol = solve(Scene.from_physical(**kw))
    assert sol.settled
    assert rel(sol.u_max, expected) < 1e-6


@pytest.mark.parametrize("pi2", [0.05, 0.2, 0.5, 0.9, 0.999])
def test_newmark_closed_form(pi2):
    """Rigid floor, rectangular pulse, Coulomb: Pi1 = (1/Pi2 - 1)/2 (Newmark 1965)."""
    sol = solve(Scene(pi2, 0.0, pulse="rectangular"))
    exact = 0.5 * (1.0 / pi2 - 1.0)
    assert sol.model == "fixed-base+coulomb"
    assert rel(sol.pi1, exact) < 1e-12
    assert sol.pi1_residual == pytest.approx(-exact, rel=1e-12)   # slides against the pulse
    assert sol.tau_peak == pytest.approx(1.0 / pi2, rel=1e-12)    # stops at tau = 1/Pi2


def test_newmark_no_slide_when_pulse_below_friction():
    sol = solve(Scene(1.0, 0.0, pulse="rectangular"))
    assert sol.pi1 == 0.0 and sol.model == "fixed-base+no-slide"


# ---------------------------------------------------------------- Buckingham

PI_POINTS = {
    "pi3": dict(pi2=0.15, pi3=1.3, pi4=0.1),
    "pi4": dict(pi2=0.15, pi3=1.0, pi4=0.27),
    "pi5": dict(pi2=0.2, pi3=0.8, pi4=0.1, pi5=0.6, pi6=300.0),
    "pi6": dict(pi2=0.2, pi3=2.0, pi4=0.05, pi5=0.8, pi6=40.0),
    "pi7": dict(pi2=0.15, pi3=1.5, pi4=0.1, pi7=0.8),
    "pi8": dict(pi2=0.1, pi3=1.2, pi4=0.1, pi8=0.3),
}


def physical_realisation(pis, a_p, T_p, M_b, g, printed_pi7=False):
    """Physical parameters that reproduce the Pi point (isoslide's groups, or
    with the paper's printed Pi7 = gamma a_p T_p when printed_pi7)."""
    mu_k = pis["pi2"] * a_p / g
    pi7 = pis.get("pi7", 0.0)
    gamma = pi7 / (a_p * T_p) if printed_pi7 else pi7 / (g * T_p)
    return dict(a_p=a_p, T_p=T_p, M_b=M_b, T_b=pis["pi3"] * T_p, xi_b=pis["pi4"],
                m_ec=pis.get("pi8", 1e-5) * M_b, mu_s=mu_k / pis.get("pi5", 1.0), mu_k=mu_k,
                beta=pis.get("pi6", 0.0) / (a_p * T_p), gamma=gamma, g=g)


def realisations(seed, n=4):
    rng = np.random.default_rng(seed)
    return [dict(a_p=rng.uniform(0.5, 15.0), T_p=rng.uniform(0.2, 5.0), M_b=10 ** rng.uniform(3, 7),
                 g=rng.uniform(1.6, 25.0)) for _ in range(n)]


@pytest.mark.parametrize("group", sorted(PI_POINTS))
def test_buckingham_invariance(group):
    """Random (a_p, T_p, M_b, g) with the same Pi-groups give the same Pi1."""
    pis = PI_POINTS[group]
    base = solve(Scene(**pis)).pi1
    assert base > 0
    for r in realisations(hash(group) % 2**32):
        sol = solve(Scene.from_physical(**physical_realisation(pis, **r)))
        assert rel(sol.pi1, base) < 1e-7
        assert sol.u_max == pytest.approx(sol.pi1 * r["a_p"] * r["T_p"] ** 2, rel=1e-14)


def test_paper_printed_pi7_is_not_a_similarity_group():
    """The paper prints Pi7 = gamma a_p T_p; for Eq. 1 it does not hold: two
    realisations with equal printed groups give different Pi1 (ratio a_p/g
    differs), while gamma g T_p holds (test above)."""
    pis = PI_POINTS["pi7"]
    values = []
    for r in [dict(a_p=3.0, T_p=1.0, M_b=1e6, g=9.80665), dict(a_p=12.0, T_p=0.7, M_b=2e5, g=9.80665)]:
        phys = physical_realisation(pis, **r, printed_pi7=True)
        printed = paper_groups(**phys)
        assert printed["pi7"] == pytest.approx(pis["pi7"], rel=1e-12)
        values.append(solve(Scene.from_physical(**phys)).pi1)
    assert rel(values[0], values[1]) > 1e-2


# ---------------------------------------------------------------- symmetry, energy

def _sampled_ricker(sign):
    tau = np.linspace(-2.0, 2.0, 801)
    return pulses.sampled(sign * pulses.ricker().accel(tau), tau[1] - tau[0], tau0=-2.0)


@pytest.mark.parametrize("pis", [dict(pi2=0.2, pi3=1.0, pi4=0.1), dict(pi2=0.15, pi3=0.0),
                                 dict(pi2=0.2, pi3=1.5, pi4=0.05, pi5=0.7, pi6=500.0, pi8=0.2)])
def test_mirror_symmetry(pis):
    """Flipping the sign of the ground motion flips u_s: same Pi1, opposite residual."""
    a = solve(Scene(**pis, pulse=_sampled_ricker(+1.0)))
    b = solve(Scene(**pis, pulse=_sampled_ricker(-1.0)))
    assert a.pi1 > 0
    assert rel(b.pi1, a.pi1) < 1e-9
    assert b.pi1_residual == pytest.approx(-a.pi1_residual, rel=1e-8)
    assert b.tau_peak == pytest.approx(a.tau_peak, abs=1e-9)


def _trapz(f, t):
    return float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(t)))


@pytest.mark.parametrize("pis", [dict(pi2=0.1, pi3=1.0, pi4=0.1, pi8=0.3),
                                 dict(pi2=0.15, pi3=2.0, pi4=0.05, pi5=0.7, pi6=200.0, pi7=0.3, pi8=0.5)])
def test_energy_balance(pis):
    """Over the whole history (per unit M_b, dimensionless):
    T + V = W_ground - D_isolator - E_friction, with T = x'^2/2 + Pi8 (x'+u')^2/2,
    V = w^2 x^2/2, dW = -p (x' + Pi8 (x'+u')), dD = 2 z w x'^2, dE = Pi8 phi |u'|."""
    sc = Scene(**pis)
    sol = solve(sc, history=True, max_step=2e-4, rtol=1e-9)
    h = sol.history
    w = 2 * math.pi / sc.pi3
    p = sc.pulse.accel(h.tau)
    e = np.exp(-sc.pi6 * np.abs(h.ud))
    sech = 2 * e / (1 + e * e)
    phi = sc.static_level * sech + sc.pi2 * (1 - sech) + sc.pi7 * np.abs(h.ud)
    kinetic = 0.5 * h.xd ** 2 + 0.5 * sc.pi8 * (h.xd + h.ud) ** 2
    strain = 0.5 * w * w * h.x ** 2
    work = -_trapz(p * (h.xd + sc.pi8 * (h.xd + h.ud)), h.tau)
    damping = _trapz(2 * sc.pi4 * w * h.xd ** 2, h.tau)
    friction = _trapz(sc.pi8 * phi * np.abs(h.ud), h.tau)
    assert friction > 1e-3 * work > 0
    residual = kinetic[-1] + strain[-1] - (work - damping - friction)
    assert abs(residual) < 1e-6 * work


# ---------------------------------------------------------------- accuracy knob

HARD_SCENES = [
    dict(pi2=0.2, pi3=1.0, pi4=0.1, pi5=0.7, pi6=1000.0),
    dict(pi2=0.153, pi3=1.0, pi4=0.05, pi5=0.7, pi6=1000.0),
    dict(pi2=0.0502, pi3=2.0, pi4=0.05, pi5=0.85, pi6=1000.0),
    dict(pi2=0.07, pi3=1.0, pi4=0.02, pi8=0.5),
    dict(pi2=0.3, pi3=0.5, pi4=0.3, pi7=2.0),
    dict(pi2=0.02, pi3=3.0, pi4=0.1),
]


@pytest.mark.parametrize("pis", HARD_SCENES)
def test_default_accuracy_and_convergence(pis):
    """The default rtol=1e-6 meets 1e-6 against a converged answer; looser
    settings stay within their own target and errors shrink as rtol tightens."""
    sc = Scene(**pis)
    converged = solve(sc, rtol=1e-11).pi1
    assert rel(solve(sc, rtol=1e-12).pi1, converged) < 1e-9
    errs = {r: rel(solve(sc, rtol=r).pi1, converged) for r in (1e-2, 1e-4, 1e-6)}
    for r, e in errs.items():
        assert e <= r
    assert errs[1e-6] < 1e-6


def test_exact_zeros_stay_zero():
    for rtol in (1e-2, 1e-6, 1e-10):
        sol = solve(Scene(0.7, 0.0), rtol=rtol)   # Ricker peak 1 < mu_s g / a_p? no: 0.7 < 1 slides
        assert sol.pi1 > 0
        sol = solve(Scene(1.0 + 1e-12, 0.0), rtol=rtol)
        assert sol.pi1 == 0.0 and sol.model == "fixed-base+no-slide"


def test_just_above_threshold_slides_a_little():
    """Fixed base, Ricker peak = 1: Pi2 just under 1 gives a tiny, positive, convergent Pi1."""
    vals = [solve(Scene(1.0 - 1e-4, 0.0), rtol=r).pi1 for r in (1e-6, 1e-10)]
    assert 0 < vals[1] < 1e-8
    assert rel(vals[0], vals[1]) < 1e-6


# ---------------------------------------------------------------- limits and reductions

def test_pi8_to_zero_gives_one_way():
    one_way = solve(Scene(0.1, 1.0, 0.1, pi8=0.0))
    assert one_way.model == "coulomb+one-way"
    prev = None
    for pi8 in (1e-2, 1e-3, 1e-4, 1e-5):
        d = abs(solve(Scene(0.1, 1.0, 0.1, pi8=pi8), model="full").pi1 - one_way.pi1)
        if prev is not None:
            assert d < 0.2 * prev          # first order in Pi8
        prev = d
    assert prev < 1e-4 * one_way.pi1


def test_one_way_reduction_used_only_when_bound_holds():
    tiny = Scene(0.1, 1.0, 0.1, pi8=1e-12)
    sol = solve(tiny)
    assert sol.model == "coulomb+one-way"
    assert rel(sol.pi1, solve(tiny, model="full").pi1) < 1e-7
    assert solve(Scene(0.1, 1.0, 0.1, pi8=1e-5)).model == "coulomb"


@pytest.mark.parametrize("pis", [dict(pi2=0.2, pi3=0.0, pi5=0.7), dict(pi2=0.2, pi3=1.0, pi4=0.1, pi5=0.75)])
def test_pi6_to_infinity_gives_static_kinetic_switch(pis):
    sharp = solve(Scene(**pis), model="static-kinetic").pi1
    errs = [rel(solve(Scene(**pis, pi6=pi6)).pi1, sharp) for pi6 in (1e3, 1e4, 1e5, 1e6)]
    assert all(b < a for a, b in zip(errs, errs[1:], strict=False))
    assert errs[-1] < 1e-3


@pytest.mark.parametrize("pis", [dict(pi2=0.2, pi3=1.0, pi4=0.1), dict(pi2=0.1, pi3=0.0),
                                 dict(pi2=0.05, pi3=2.0, pi4=0.1, pi8=0.5)])
def test_coulomb_path_equals_full_model(pis):
    a = solve(Scene(**pis))
    b = solve(Scene(**pis), model="full")
    assert "coulomb" in a.model and "stribeck" in b.model
    assert rel(a.pi1, b.pi1) < 1e-8


def test_fixed_base_is_the_limit_of_a_stiff_base():
    fixed = solve(Scene(0.2, 0.0)).pi1
    d = [rel(solve(Scene(0.2, pi3, 0.2)).pi1, fixed) for pi3 in (0.04, 0.02, 0.01)]
    assert d[2] < d[1] < d[0] < 0.1


@pytest.mark.parametrize("pis", [dict(pi2=0.2, pi3=1.0, pi4=0.1), dict(pi2=0.15, pi3=2.0, pi4=0.05, pi5=0.7, pi6=100.0)])
def test_settlement_stop_changes_nothing(pis):
    """Following the scene 200 isolation periods past settlement adds no sliding."""
    a = solve(Scene(**pis))
    b = solve(Scene(**pis), settle=False)
    assert a.settled and b.tau_end > a.tau_end + 100
    assert a.pi1 == b.pi1 and a.pi1_residual == b.pi1_residual


def test_undamped_resonant_scene_does_not_settle():
    sol = solve(Scene(0.05, 1.0, 0.0, pi8=0.0), horizon=20)
    assert not sol.settled
    assert sol.tau_end == pytest.approx(2.0 + 20.0, rel=1e-12)


def test_batch_no_slide_shortcut_matches_single_solves():
    pi2 = np.linspace(0.05, 1.5, 40)
    scenes = [Scene(p, 1.5, 0.1) for p in pi2]
    batch = solve_many(scenes)
    single = [solve(s) for s in scenes]
    demand = peak_stuck_demand(scenes[0])
    for b_pi1, b_model, s, p in zip(batch.pi1, batch.model, single, pi2, strict=False):
        assert b_pi1 == pytest.approx(s.pi1, rel=1e-12, abs=0)
        assert (b_model == "no-slide") == (p > demand)
        if p > demand:
            assert s.pi1 == 0.0
    assert (batch.model == "no-slide").sum() > 5
    assert (batch.pi1 > 0).sum() > 5


def test_peak_stuck_demand_is_the_slide_threshold():
    """Just below the stuck system's peak demand it slides, just above it does not."""
    sc = Scene(0.3, 1.0, 0.1)
    d = peak_stuck_demand(sc)
    assert solve(Scene(d * (1 - 1e-6), 1.0, 0.1)).pi1 > 0
    assert solve(Scene(d * (1 + 1e-9), 1.0, 0.1)).pi1 == 0.0


# ---------------------------------------------------------------- bad input

@pytest.mark.parametrize("kwargs, name", [
    (dict(pi2=float("nan"), pi3=1.0), "pi2"), (dict(pi2=0.0, pi3=1.0), "pi2"),
    (dict(pi2=0.2, pi3=-1.0), "pi3"), (dict(pi2=0.2, pi3=float("inf")), "pi3"),
    (dict(pi2=0.2, pi3=1.0, pi4=-0.1), "pi4"), (dict(pi2=0.2, pi3=1.0, pi5=1.2), "pi5"),
    (dict(pi2=0.2, pi3=1.0, pi5=0.0), "pi5"), (dict(pi2=0.2, pi3=1.0, pi6=-1.0), "pi6"),
    (dict(pi2=0.2, pi3=1.0, pi7=float("nan")), "pi7"), (dict(pi2=0.2, pi3=1.0, pi8=-1e-3), "pi8"),
    (dict(pi2=0.2, pi3=1.0, pulse="triangle"), "pulse"),
])
def test_bad_pi_input_names_parameter_value_and_range(kwargs, name):
    with pytest.raises(ValueError, match=rf"^{name} = .*(allowed|one of)"):
        Scene(**kwargs)


@pytest.mark.parametrize("bad, name", [("a_p", "a_p"), ("T_p", "T_p"), ("M_b", "M_b"), ("mu_s", "mu_s"), ("g", "g")])
def test_bad_physical_input(bad, name):
    kw = dict(a_p=3.0, T_p=1.0, M_b=1e6, T_b=2.0, xi_b=0.1, m_ec=10.0, mu_s=0.3, mu_k=0.2)
    kw[bad] = -1.0
    with pytest.raises(ValueError, match=rf"^{name} = -1.0 is out of range; allowed range"):
        Scene.from_physical(**kw)


def test_mu_k_above_mu_s_rejected():
    with pytest.raises(ValueError, match=r"^mu_k = 0.4 .* 0 < value <= 0.3"):
        Scene.from_physical(3.0, 1.0, 1e6, 2.0, 0.1, 10.0, mu_s=0.3, mu_k=0.4)


def test_overdamped_and_massless_valid():
    assert solve(Scene(0.2, 1.0, 2.5)).settled
    s = solve(Scene.from_physical(3.0, 1.0, 1e6, 2.0, 1.5, 0.0, 0.2, 0.2))
    assert s.model.endswith("one-way") and s.u_max > 0


def test_a_run_out_of_steps_raises_instead_of_returning_a_truncated_answer(monkeypatch):
    """A solve that exhausts its step budget raises StepBudgetError naming rtol; no partial Pi1."""
    sc = Scene(pi2=0.1, pi3=1.0, pi4=0.1)
    full = solve(sc)
    assert full.settled and full.n_steps > 60
    monkeypatch.setattr(solver, "step_budget", lambda scene, horizon=solver.DEFAULT_HORIZON: 60)
    with pytest.raises(isoslide.StepBudgetError, match=r"rtol = 1e-06.*allowed range"):
        solve(sc)


BUDGET_SCENES = [Scene(pi2=0.5, pi3=0.0), Scene(pi2=0.5, pi3=1e-3, pi4=0.0), Scene(pi2=0.2, pi3=1.0, pi4=0.1),
                 Scene(pi2=0.5, pi3=100.0, pi4=0.0), Scene(pi2=0.1, pi3=2.0, pi4=0.05, pi9=0.05),
                 Scene(pi2=0.1, pi3=2.0, pi4=0.05, pi9=0.05, pi10=0.005),
                 Scene(pi2=0.1, pi3=2.0, pi4=0.05, pi11=0.6, pi12=0.2, pi13=0.02, floor="roof")]
"""Fixed, stiff, paper, very soft bases and general buildings (sliding and bilinear bearings, a roof)."""


@pytest.mark.parametrize("horizon", [0.0, 1.0, 200.0])
def test_step_budget_is_never_below_the_kernels_minimum(horizon):
    for sc in BUDGET_SCENES:
        assert solver.step_budget(sc, horizon) >= kernel.MAX_STEPS, sc


def test_step_budget_grows_with_the_isolation_periods_followed():
    """A stiffer base (smaller Pi3) or a longer horizon never lowers the budget, and a very stiff
    base followed to the horizon gets more than the kernel's minimum."""
    pi3s = np.geomspace(1e-4, 100.0, 40)
    budgets = [solver.step_budget(Scene(pi2=0.5, pi3=p, pi4=0.0)) for p in pi3s]
    assert (np.diff(budgets) <= 0).all()
    assert budgets[0] > kernel.MAX_STEPS
    for sc in BUDGET_SCENES:
        by_horizon = [solver.step_budget(sc, h) for h in (0.0, 10.0, 200.0, 1e4)]
        assert (np.diff(by_horizon) >= 0).all(), sc
    stiff = Scene(pi2=0.5, pi3=1e-3, pi4=0.0)
    assert solver.step_budget(stiff, 1e4) > solver.step_budget(stiff, 200.0) > kernel.MAX_STEPS


def test_a_general_buildings_step_budget_covers_its_base():
    """The building integrates the isolated base too: never less budget than the paper model of that base."""
    for sc in BUDGET_SCENES:
        base = Scene(pi2=sc.pi2, pi3=sc.pi3, pi4=sc.pi4)
        assert solver.step_budget(sc) >= solver.step_budget(base), sc


@pytest.mark.slow
def test_step_budget_lets_a_long_stiff_undamped_scene_finish():
    """An undamped stiff base rung by a rectangular pulse keeps the block slipping to the horizon:
    over 5 million steps, more than the kernel's minimum budget, and the solve still finishes."""
    sc = Scene(pi2=0.3, pi3=1.37e-3, pi4=0.0, pi8=0.0, pulse="rectangular")
    horizon = 120.0
    s = solve(sc, horizon=horizon)
    assert not s.settled and s.tau_end == pytest.approx(sc.pulse.tau_end + horizon, rel=1e-12)
    assert kernel.MAX_STEPS < s.n_steps <= solver.step_budget(sc, horizon)
    assert s.n_events > 100_000 and math.isfinite(s.pi1) and s.pi1 > 0.0


def test_bad_solver_options():
    sc = Scene(0.2, 1.0, 0.1)
    with pytest.raises(ValueError, match="rtol = 0.5"):
        solve(sc, rtol=0.5)
    with pytest.raises(ValueError, match="method = 'magic'"):
        solve(sc, method="magic")
    with pytest.raises(ValueError, match="model = 'tiny'"):
        solve(sc, model="tiny")


def test_every_pulse_shape_solves():
    for name in pulses.PULSE_NAMES:
        sol = solve(Scene(0.3, 1.0, 0.1, pulse=name))
        assert sol.settled and np.isfinite(sol.pi1) and sol.pi1 >= 0


def test_package_exports():
    assert isoslide.solve is solve and isoslide.Scene is Scene


def test_peer_methods_through_solve():
    """method='reference' and 'regularized' answer the same Newmark scene
    (the regularised one to its stiffness-limited accuracy)."""
    sc = Scene(0.3, 0.0, pulse="rectangular")
    exact = 0.5 * (1 / 0.3 - 1)
    ref = solve(sc, method="reference")
    reg = solve(sc, method="regularized", stiffness=1e6)
    assert ref.model == "reference" and rel(ref.pi1, exact) < 1e-10
    assert reg.model == "regularized" and 1e-5 < rel(reg.pi1, exact) < 1e-2
    with pytest.raises(TypeError):
        solve(sc, stiffness=1e6)          # not an option of the exact method
