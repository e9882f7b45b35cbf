"""Similarity checks: the independent SI-units solver, spreads, tables and conclusions."""


import numpy as np
import pytest
import xarray as xr

import isoslide
from isoslide.studies import claims
from isoslide.studies import similarity as S
from isoslide.peers.si import simulate_si

G = isoslide.G_STANDARD
BASE = dict(pi2=0.2, pi3=1.0, pi4=0.1, pi5=1.0, pi6=0.0, pi7=0.0, pi8=1e-5)


def pi1_si(pis, a_p, T_p, M_b, convention="isoslide", pulse="ricker", t_end=None):
    p = S.physical_parameters(pis, a_p, T_p, M_b, convention)
    return simulate_si(p, pulse, t_end=None if t_end is None else t_end * T_p).pi1


@pytest.mark.parametrize("pi2", [0.1, 0.4, 0.9])
def test_si_solver_reproduces_newmark(pi2):
    pis = dict(BASE, pi2=pi2, pi3=0.0, pi4=0.0)
    assert pi1_si(pis, 3.0, 0.7, 1e5, pulse="rectangular") == pytest.approx(0.5 * (1 / pi2 - 1), rel=1e-8)


def test_physical_parameters_realise_the_groups():
    pis = dict(BASE, pi5=0.7, pi6=500.0, pi7=2.0, pi8=0.3)
    p = S.physical_parameters(pis, 4.0, 2.5, 3e5, "isoslide")
    sc = isoslide.Scene.from_physical(p["a_p"], p["T_p"], p["M_b"], p["T_b"], p["xi_b"], p["m_ec"],
                                      p["mu_s"], p["mu_k"], p["beta"], p["gamma"])
    for k, v in pis.items():
        assert getattr(sc, k) == pytest.approx(v, rel=1e-12)
    paper = S.physical_parameters(pis, 4.0, 2.5, 3e5, "paper")
    assert isoslide.paper_groups(**{k: paper[k] for k in ("a_p", "T_p", "M_b", "T_b", "xi_b", "m_ec", "mu_s",
                                                          "mu_k", "beta", "gamma")})["pi7"] == pytest.approx(2.0)
    assert paper["gamma"] == pytest.approx(p["gamma"] * G / 4.0)
    with pytest.raises(ValueError, match="convention"):
        S.physical_parameters(pis, 1, 1, 1, "other")


@pytest.mark.parametrize("pis", [
    BASE,
    dict(BASE, pi5=0.6, pi6=3000.0),
    dict(BASE, pi3=0.5, pi8=1.0, pi2=0.3),
])
def test_si_solver_agrees_with_isoslide_and_is_self_similar(pis):
    sol = isoslide.solve(isoslide.Scene(**pis))
    vals = [pi1_si(pis, a, T, M, t_end=sol.tau_end + 1) for a, T, M in ((G, 1.0, 1e5), (0.3 * G, 3.1, 4e6))]
    assert vals[0] == pytest.approx(vals[1], rel=1e-6)
    assert vals[0] == pytest.approx(sol.pi1, rel=1e-5)


def test_the_printed_pi7_is_not_a_similarity_group():
    pis = dict(BASE, pi7=2.0)
    ours = [pi1_si(pis, a, 1.0, 1e5, "isoslide") for a in (0.5 * G, 2.0 * G)]
    paper = [pi1_si(pis, a, 1.0, 1e5, "paper") for a in (0.5 * G, 2.0 * G)]
    assert ours[0] == pytest.approx(ours[1], rel=1e-7)
    assert abs(paper[0] - paper[1]) / paper[0] > 0.05


def _study(values, family="pi5", other=("pi3", [1.0])):
    pi2 = np.linspace(0.1, 1.0, 10)
    fam = np.array(values, dtype=float)
    base = np.maximum(0.0, 1.0 - pi2)
    pi1 = np.stack([[base * (1 + 0.02 * k) for k in range(fam.size)] for _ in other[1]])
    return xr.Dataset({"pi1": ((other[0], family, "pi2"), pi1)},
                      coords={other[0]: other[1], family: fam, "pi2": pi2})


def test_curve_spread():
    ds = _study([0.5, 0.7, 0.85, 1.0])
    s = S.curve_spread(ds, "pi5", 0.7, 1.0)
    assert int(s["n_curves"]) == 3
    assert float(s["spread"].sel(pi3=1.0)) == pytest.approx(0.04 * 0.9)     # (1.06 - 1.02) * max(base)
    assert float(s["relative"].sel(pi3=1.0)) == pytest.approx(0.04 * 0.9 / (1.06 * 0.9))
    assert float(s["pi2_at"].sel(pi3=1.0)) == pytest.approx(0.1)


def _check(study, between=0.0, n=2, pi7=0.0, swept="pi3 pi2"):
    pi1 = np.array([0.1, 0.2])[:n]
    si = np.repeat(pi1[:, None, None], 2, axis=1).repeat(2, axis=2).copy()
    si[:, 1, 1] *= 1 + between
    ds = xr.Dataset({"pi1_grid": ("sample", pi1), "pi1_si": (("sample", "realisation", "convention"), si)},
                    coords={"convention": list(S.CONVENTIONS),
                            **{g: ("sample", np.full(n, pi7 if g == "pi7" else 0.1)) for g in S.GROUPS}})
    ds.attrs.update(study=study, swept=swept)
    return ds


def test_buckingham_tables_flag_the_failing_group():
    checks = [_check("a"), _check("b", between=0.3, pi7=2.0, swept="pi7 pi2")]
    t = S.buckingham_tables(checks, 1e-4)
    assert t["buckingham_verdict"].sel(study="a").values.tolist() == [1, 1]
    assert t["buckingham_verdict"].sel(study="b").values.tolist() == [1, 0]
    g = t["group_verdict"]
    assert int(g.sel(group="pi7", convention="paper")) == 0
    assert int(g.sel(group="pi7", convention="isoslide")) == 1
    assert int(g.sel(group="pi3", convention="paper")) == 1          # same definition, same verdict
    assert str(t["group_definition"].sel(group="pi7", convention="paper").values) == "gamma a_p T_p"


def test_claims_on_synthetic_curves_and_missing_studies_reported():
    d5 = _study([0.5, 0.7, 1.0], other=("pi3", [0.5, 1.0, 2.0]))
    spreads = {"pi5": S.curve_spread(d5, "pi5", 0.7, 1.0)}
    out = {c["key"]: c for c in claims.evaluate({"fig6_pi5": d5}, spreads, 0.1)}
    assert list(out) == [c.key for c in claims.CLAIMS]          # every claim reported, in order
    assert out["pi5_similarity"]["verdict"] == claims.HOLDS
    # synthetic Pi5 < 1 curves are lower everywhere: only the reduction holds
    assert out["static_friction"]["verdict"] == claims.HOLDS_PARTLY
    missing = out["isolation_amplifies"]
    assert missing["verdict"] == claims.NOT_EVALUATED and "study fig5_pi3" in missing["finding"]
    assert "similarity.complete.pi6" in out["pi6_complete_similarity"]["finding"]
    for c in out.values():
        assert c["claim"] and c["finding"] and c["criterion"]


def test_a_renamed_study_is_reported_not_dropped():
    d5 = _study([0.5, 0.7, 1.0], other=("pi3", [0.5, 1.0, 2.0]))
    out = claims.evaluate({"static_friction_study": d5}, {}, 0.1)
    assert len(out) == len(claims.CLAIMS)
    assert all(c["verdict"] == claims.NOT_EVALUATED for c in out)
