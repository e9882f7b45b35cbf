"""The Snakemake workflow, run as a user would: lint, config errors, a tiny end-to-end run,
no-op reruns, per-study reruns and recovery from SIGKILL.

Every run happens in a temporary copy of the workflow (Snakefile, config/, workflow/,
profiles/), so the repository's own results/ and reports/ are never touched.
"""

import os
import re
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
import xarray as xr
import yaml

from isoslide import datasets

ROOT = Path(__file__).resolve().parents[1]
TEST_CONFIG = ["--configfile", "config/test.yaml"]
STUDIES = sorted(yaml.safe_load((ROOT / "config" / "config.yaml").read_text())["studies"])


def copy_workflow(dest: Path) -> Path:
    dest.mkdir(parents=True, exist_ok=True)
    shutil.copy2(ROOT / "Snakefile", dest / "Snakefile")
    for d in ("config", "workflow", "profiles"):
        shutil.copytree(ROOT / d, dest / d, ignore=shutil.ignore_patterns("__pycache__", ".ipynb_checkpoints"))
    return dest


def snakemake(cwd, *args, timeout=900, check=True):
    env = dict(os.environ, PYTHONHASHSEED="0")
    proc = subprocess.run([sys.executable, "-m", "snakemake", *args], cwd=cwd, capture_output=True,
                          text=True, timeout=timeout, env=env)
    out = proc.stdout + proc.stderr
    if check and proc.returncode != 0:
        raise AssertionError(f"snakemake {' '.join(args)} failed ({proc.returncode}):\n{out[-6000:]}")
    return proc.returncode, out


def planned_jobs(out: str) -> list:
    """(rule, wildcards) of every job a dry run plans."""
    jobs = []
    for block in re.split(r"\n(?=\[.*\d{4}\]\n)", out):
        m = re.search(r"^(?:local)?rule (\w+):", block, re.M)
        if m:
            w = re.search(r"^\s+wildcards: (.*)$", block, re.M)
            jobs.append((m.group(1), w.group(1) if w else ""))
    return jobs


@pytest.fixture(scope="module")
def wf(tmp_path_factory):
    return copy_workflow(tmp_path_factory.mktemp("wf"))


def test_lint_is_clean(wf):
    code, out = snakemake(wf, "--lint", timeout=300)
    assert "Lints for" not in out, out
    assert code == 0


def test_dry_run_plans_the_whole_dag(wf):
    _, out = snakemake(wf, "-n", *TEST_CONFIG, timeout=300)
    rules = {r for r, _ in planned_jobs(out)}
    assert {"solve_chunk", "merge_study", "similarity_study", "similarity", "figure", "report_similarity",
            "report_figures", "fig4_record", "record_compare", "records_dataset", "figure_records",
            "report_records", "accuracy_part", "accuracy_dataset", "report_accuracy", "all"} <= rules
    chunk_wildcards = [w for r, w in planned_jobs(out) if r == "solve_chunk"]
    assert all(re.fullmatch(r"study=\w+, chunk=\d+", w) for w in chunk_wildcards)


@pytest.mark.parametrize("overlay, key", [
    ({"chunk_size": 0}, "chunk_size"),
    ({"studies": {"fig6_pi5": {"dims": {"pi5": [0.5, 1.5]}}}}, "pi5"),
    ({"studies": {"fig5_pi3": {"pulse": "sine"}}}, "studies.fig5_pi3.pulse"),
    ({"studies": {"fig8_pi8": {"dims": {"pi3": [1.0, 1.0]}}}}, "studies.fig8_pi8.dims.pi3"),
    ({"similarity": {"complete": {"pi5": {"study": "nope", "range": [0.7, 1.0]}}}}, "similarity.complete.pi5.study"),
])
def test_invalid_config_fails_before_any_job_naming_the_key(tmp_path, overlay, key):
    d = copy_workflow(tmp_path / "bad")
    (d / "config" / "bad.yaml").write_text(yaml.safe_dump(overlay))
    code, out = snakemake(d, "--cores", "1", *TEST_CONFIG, "config/bad.yaml", check=False,
                          timeout=300)
    assert code != 0
    assert key in out, out[-3000:]
    assert not (d / "results").exists() and not (d / "logs").exists()


@pytest.fixture(scope="module")
def full_run(wf):
    t0 = time.monotonic()
    snakemake(wf, "--cores", "2", *TEST_CONFIG, timeout=1500)
    return wf, time.monotonic() - t0


@pytest.mark.slow
def test_tiny_config_runs_end_to_end(full_run):
    wf, seconds = full_run
    print(f"tiny end-to-end run: {seconds:.0f} s")
    for s in STUDIES:
        ds = xr.open_dataset(wf / "results" / "datasets" / f"{s}.nc")
        assert ds.attrs["Conventions"].startswith("CF") and "pi1" in ds
        assert ds["pi1"].dims[-1] == "pi2"
        ds.close()
        assert (wf / "logs" / "merge_study" / f"{s}.log").exists()
    for n in range(1, 9):
        for ext in ("png", "pdf"):
            assert (wf / "reports" / "figures" / f"fig{n}.{ext}").stat().st_size > 0
    sim = (wf / "reports" / "similarity.html").read_text()
    assert "Buckingham" in sim and "Verdict" in sim and "Traceback" not in sim
    gallery = (wf / "reports" / "figures.html").read_text()
    assert "Figure 8" in gallery and "Fig. 8." in gallery and "Traceback" not in gallery
    assert "Record versus pulse" in gallery and "Records. Peak sliding" in gallery
    assert not list((wf / "results").rglob(".*.tmp")) and not list((wf / "reports").glob(".*tmp*"))


@pytest.mark.slow
def test_records_outputs(full_run):
    from isoslide.figures import read_caption
    from isoslide.record_study import FIG4_RECORD, ratio_summary

    wf, _ = full_run
    cfg = yaml.safe_load((wf / "config" / "test.yaml").read_text())["records"]
    ds = datasets.open_dataset(wf / "results" / "datasets" / "records.nc")
    assert ds["pi1_record"].dims == ("record", "pi2", "pi3")
    assert dict(ds.sizes) == {"record": len(cfg["names"]), "pi2": cfg["pi2"]["num"], "pi3": len(cfg["pi3"])}
    assert list(ds["record"].values) == cfg["names"]
    for v in ("pi1_record", "pi1_pulse", "ratio", "pi2", "pi3", "a_p", "T_p", "r2"):
        assert ds[v].attrs.get("long_name") and "units" in ds[v].attrs, v
    assert ds.attrs["Conventions"].startswith("CF") and "isoslide_config" in ds.attrs
    f4 = datasets.open_dataset(wf / "results" / "datasets" / "fig4_record.nc")
    assert f4.attrs["record"] == FIG4_RECORD and "accel_record" in f4 and "accel_ricker" in f4
    caption = read_caption(wf / "reports" / "figures" / "fig4.png")
    assert FIG4_RECORD in caption and "RRS228" in caption and "R^2" in caption
    for ext in ("png", "pdf"):
        assert (wf / "reports" / "figures" / f"records.{ext}").stat().st_size > 1000
    html = (wf / "reports" / "records.html").read_text()
    a = ratio_summary(ds, ds.attrs["tolerance"]).sel(record="all")
    assert "Record versus pulse" in html and "Traceback" not in html
    assert f"{float(a['median_ratio']):.2f}" in html and f"{int(a['n_both_slide'])}" in html
    assert "accuracy" in (wf / "reports" / "accuracy.html").read_text().lower()


@pytest.mark.slow
def test_second_run_does_nothing(full_run):
    wf, _ = full_run
    _, out = snakemake(wf, "-n", *TEST_CONFIG, timeout=300)
    assert "Nothing to be done" in out, out[-3000:]


@pytest.mark.slow
def test_changing_one_study_reruns_only_that_study(full_run):
    wf, _ = full_run
    (wf / "config" / "change.yaml").write_text(yaml.safe_dump({"studies": {"fig7_pi7": {"dims": {"pi7": [0.0, 1.0]}}}}))
    _, out = snakemake(wf, "-n", *TEST_CONFIG, "config/change.yaml", timeout=300)
    jobs = planned_jobs(out)
    per_study = {(r, w) for r, w in jobs if "study=" in w}
    assert per_study and all("study=fig7_pi7" in w for _, w in per_study), per_study
    # the accuracy scene set is drawn from the studies, so it is measured again; the records are not
    assert {r for r, _ in jobs} <= {"solve_chunk", "merge_study", "similarity_study", "similarity", "figure",
                                     "report_similarity", "report_figures", "accuracy_part", "accuracy_dataset",
                                     "report_accuracy", "all"}
    assert {w for r, w in jobs if r == "figure"} == {"fig=fig7"}


@pytest.mark.slow
def test_changing_the_records_reruns_only_record_jobs(full_run):
    wf, _ = full_run
    (wf / "config" / "rec.yaml").write_text(yaml.safe_dump({"records": {"pi4": 0.2}}))
    _, out = snakemake(wf, "-n", *TEST_CONFIG, "config/rec.yaml", timeout=300)
    rules = {r for r, _ in planned_jobs(out)}
    assert {"record_compare", "records_dataset", "figure_records", "report_records"} <= rules
    assert rules <= {"record_compare", "records_dataset", "figure_records", "report_records", "report_figures",
                     "all"}, rules


@pytest.mark.slow
def test_sigkill_then_restart_gives_the_same_datasets(full_run, tmp_path):
    wf, _ = full_run
    d = copy_workflow(tmp_path / "killed")
    targets = [f"results/datasets/{s}.nc" for s in STUDIES]
    cmd = [sys.executable, "-m", "snakemake", *targets, "--cores", "2", *TEST_CONFIG]
    proc = subprocess.Popen(cmd, cwd=d, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            start_new_session=True)
    try:
        deadline = time.monotonic() + 600
        while time.monotonic() < deadline and proc.poll() is None:
            if len(list((d / "results" / "chunks").rglob("*.nc"))) >= 2:   # killed mid-run
                break
            time.sleep(0.2)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)        # the run and every job it started
        proc.wait()
    snakemake(d, *targets, "--cores", "2", *TEST_CONFIG, timeout=1500)
    for s in STUDIES:
        a = datasets.open_dataset(d / "results" / "datasets" / f"{s}.nc")
        b = datasets.open_dataset(wf / "results" / "datasets" / f"{s}.nc")
        datasets.assert_same_data(a, b)
