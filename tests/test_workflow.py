"""The Snakemake workflow, run as a user would: lint, config errors, a tiny end-to-end run, the
reports, benchmarks and resources, code hashes, no-op reruns, per-study reruns and recovery from
SIGKILL.

Every run happens in a temporary copy of the workflow (Snakefile, config/, workflow/,
profiles/), so the repository's own results/ and reports/ are never touched.  Snakemake runs as
``python -m snakemake`` with a PATH that holds neither the interpreter's directory nor any
Snakemake, papermill or Jupyter launcher: an environment that is installed but not activated.
"""

import ast
import csv
import hashlib
import json
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

import isoslide
import isoslide.config
import isoslide.studies.sweep
from isoslide import datasets
from isoslide.store import provenance
from isoslide.studies import imports, registry
from import_walk import import_targets  # tests/ is on sys.path

ROOT = Path(__file__).resolve().parents[1]
TEST_CONFIG = ["--configfile", "config/test.yaml"]
STUDIES = sorted(yaml.safe_load((ROOT / "config" / "config.yaml").read_text())["studies"])
ISOLATION_STUDIES = ["iso_fp", "iso_lrb", "iso_flex_base", "iso_flex_roof"]
ISOLATION_RULES = {"isolation_rigid", "isolation_design", "isolation_bearings", "isolation_figure"}
REPORTS = ["accuracy", "figures", "fragility", "isolation", "planar", "records", "rocking", "similarity"]
LAUNCHERS = ("snakemake", "papermill", "jupyter", "jupyter-nbconvert")


def path_without_interpreter() -> str:
    """PATH without the interpreter's directory and without any directory holding a launcher."""
    here = Path(sys.executable).parent
    keep = []
    for entry in os.environ.get("PATH", "").split(os.pathsep):
        d = Path(entry)
        if not entry or d == here or (d.exists() and d.resolve() == here.resolve()):
            continue
        if any((d / name).exists() for name in LAUNCHERS):
            continue
        keep.append(entry)
    return os.pathsep.join(keep)


ENV = {k: v for k, v in os.environ.items() if k not in ("VIRTUAL_ENV", "CONDA_PREFIX")}
ENV.update(PYTHONHASHSEED="0", PATH=path_without_interpreter())


def copy_workflow(dest: Path) -> Path:
    dest.mkdir(parents=True, exist_ok=True)
    shutil.copy2(ROOT / "Snakefile", dest / "Snakefile")
    for d in ("config", "workflow", "profiles"):
        shutil.copytree(ROOT / d, dest / d, ignore=shutil.ignore_patterns("__pycache__", ".ipynb_checkpoints"))
    return dest


def snakemake(cwd, *args, timeout=900, check=True):
    proc = subprocess.run([sys.executable, "-m", "snakemake", *args], cwd=cwd, capture_output=True,
                          text=True, timeout=timeout, env=ENV)
    out = proc.stdout + proc.stderr
    if check and proc.returncode != 0:
        raise AssertionError(f"snakemake {' '.join(args)} failed ({proc.returncode}):\n{out[-6000:]}")
    return proc.returncode, out


def _job_blocks(out: str) -> list:
    return [b for b in re.split(r"\n(?=\[.*\d{4}\]\n)", out) if re.search(r"^(?:local)?rule \w+:", b, re.M)]


def planned_jobs(out: str) -> list:
    """(rule, wildcards) of every job a dry run plans."""
    jobs = []
    for block in _job_blocks(out):
        rule = re.search(r"^(?:local)?rule (\w+):", block, re.M).group(1)
        w = re.search(r"^\s+wildcards: (.*)$", block, re.M)
        jobs.append((rule, w.group(1) if w else ""))
    return jobs


def planned_benchmarks(out: str) -> dict:
    """{(rule, wildcards): benchmark file or None} of every job a dry run plans."""
    found = {}
    for block, job in zip(_job_blocks(out), planned_jobs(out), strict=True):
        b = re.search(r"^\s+benchmark: (.*)$", block, re.M)
        found[job] = b.group(1).strip() if b else None
    return found


# ----------------------------------------------------------------------------------------------
# the workflow as Snakemake reads it
# ----------------------------------------------------------------------------------------------

DESCRIBE = r"""
import json, types
from pathlib import Path
from snakemake.api import SnakemakeApi
from snakemake.settings.types import ConfigSettings, OutputSettings, ResourceSettings

with SnakemakeApi(OutputSettings()) as api:
    wf = api.workflow(ResourceSettings(), ConfigSettings(configfiles=[Path("config/test.yaml")]),
                      snakefile=Path("Snakefile"), workdir=Path.cwd())._workflow
    g = wf.globals
    rules = {}
    for rule in wf.rules:
        code = dict(rule.params.items()).get("code")
        if callable(code):       # the report rule: one value per report
            code = {r: code(types.SimpleNamespace(report=r)) for r in g["REPORTS"]}
        rules[rule.name] = {
            "resources": sorted(k for k in rule.resources.keys() if not k.startswith("_") and k != "tmpdir"),
            "benchmark": None if rule.benchmark is None else str(rule.benchmark),
            "script": rule.script,
            "shell": rule.shellcmd is not None,
            "code": code,
            "log": dict(rule.log.items()) | {str(i): str(f) for i, f in enumerate(rule.log)},
        }
    index = {k: v for k, v in g["INDEX"].items() if k != "config"}
    print("DESCRIPTION " + json.dumps({"rules": rules, "code_modules": g["CODE_MODULES"], "code": g["CODE"],
                                        "reports": g["REPORTS"], "config": g["config"],
                                        "all": [str(f) for f in wf.get_rule("all").input],
                                        "index_input": [str(f) for f in wf.get_rule("index_page").input],
                                        "index": index}))
"""


@pytest.fixture(scope="module")
def wf(tmp_path_factory):
    return copy_workflow(tmp_path_factory.mktemp("wf"))


@pytest.fixture(scope="module")
def described(wf):
    proc = subprocess.run([sys.executable, "-c", DESCRIBE], cwd=wf, capture_output=True, text=True,
                          timeout=300, env=ENV)
    line = [x for x in proc.stdout.splitlines() if x.startswith("DESCRIPTION ")]
    assert proc.returncode == 0 and line, proc.stdout[-3000:] + proc.stderr[-3000:]
    return json.loads(line[-1].removeprefix("DESCRIPTION "))


def _rule_sources() -> dict:
    """{rule name: its text} from the Snakefile and workflow/rules/*.smk."""
    out = {}
    for path in [ROOT / "Snakefile", *sorted((ROOT / "workflow" / "rules").glob("*.smk"))]:
        for block in re.split(r"\n(?=rule \w+:)", path.read_text())[1:]:
            name = re.match(r"rule (\w+):", block).group(1)
            out[name] = block.split("\n\n\n")[0]
    return out


def test_lint_is_clean(wf):
    code, out = snakemake(wf, "--lint", timeout=300)
    assert "Lints for" not in out, out
    assert code == 0


def test_every_rule_declares_threads_and_resources(described):
    rules = described["rules"]
    sources = _rule_sources()
    assert set(sources) == set(rules)
    for name, rule in rules.items():
        assert {"mem_mb", "runtime"} <= set(rule["resources"]), (name, rule["resources"])
        assert re.search(r"^    threads: \d+$", sources[name], re.M), name
        if rule["benchmark"]:          # a compute rule: sized from its measured benchmarks
            assert re.search(r"^        mem_mb=\d+,  # .*max_rss.*\d", sources[name], re.M), \
                f"rule {name}: mem_mb without the measured max_rss it is sized from"
            assert re.search(r"^        runtime=\d+,  # .*\d s\b", sources[name], re.M), \
                f"rule {name}: runtime without the measured seconds it is sized from"


def test_every_compute_rule_writes_a_benchmark_per_job(described):
    for name, rule in described["rules"].items():
        if rule["script"] or rule["shell"]:
            assert rule["benchmark"] and rule["benchmark"].startswith(f"results/benchmarks/{name}/"), name
            assert rule["benchmark"].endswith(".tsv"), name
        else:
            assert rule["benchmark"] is None, name


def test_every_job_logs_next_to_its_benchmark(described):
    """logs/<rule>/<wildcards>.log pairs with results/benchmarks/<rule>/<wildcards>.tsv, so that
    python -m isoslide.budget finds the phases of every job."""
    for name, rule in described["rules"].items():
        if rule["benchmark"]:
            expected = "logs/" + rule["benchmark"].removeprefix("results/benchmarks/").removesuffix(".tsv") + ".log"
            assert expected in {str(v) for v in rule["log"].values()}, (name, rule["log"], expected)


def test_one_script_per_rule_and_one_report_rule(described):
    scripts = [r["script"] for r in described["rules"].values() if r["script"]]
    assert len(scripts) == len(set(scripts)), scripts
    for script in scripts:
        text = (ROOT / "workflow" / "rules" / script).resolve().read_text()
        assert "snakemake.rule" not in text, script
    assert sorted(described["reports"]) == REPORTS
    assert [n for n, r in described["rules"].items() if r["shell"]] == ["report"]
    assert not [n for n in described["rules"] if n.startswith("report_")]


# ----------------------------------------------------------------------------------------------
# code hashes: every rule reruns when, and only when, a module it imports changes
# ----------------------------------------------------------------------------------------------

PKG = provenance.PACKAGE_DIR


def _module_file(name: str) -> Path | None:
    """File Python runs for ``isoslide.<name>`` (``None`` if no such module)."""
    base = PKG.joinpath(*name.split("."))
    if (base / "__init__.py").is_file():
        return base / "__init__.py"
    return base.with_name(base.name + ".py") if base.with_name(base.name + ".py").is_file() else None


def _isoslide_imports(source: str, module: str | None = None) -> set:
    """Dotted names (relative to the package) of the isoslide modules ``source`` imports."""
    package = None
    if module is not None:
        package = f"isoslide.{module}"
        package = package if _module_file(module).name == "__init__.py" else package.rpartition(".")[0]
    found = set()
    for node, targets in import_targets(source, package):
        if isinstance(node, ast.ImportFrom) and targets[0] == "isoslide":   # the lazy package namespace
            targets += [f"isoslide.{isoslide._EXPORTS[a.name]}" for a in node.names if a.name in isoslide._EXPORTS]
        for t in targets:
            parts = t.split(".")
            if parts[0] != "isoslide":
                continue
            for i in range(2, len(parts) + 1):        # importing a.b.c runs a.b first
                name = ".".join(parts[1:i])
                if _module_file(name) is not None:
                    found.add(name)
    return found


def _import_closure(source: str) -> set:
    """Files of every isoslide module ``source`` imports, directly or through other modules."""
    todo, seen = list(_isoslide_imports(source)), set()
    while todo:
        name = todo.pop()
        if name in seen:
            continue
        seen.add(name)
        todo += _isoslide_imports(_module_file(name).read_text(), name) - seen
    return {_module_file(n) for n in seen}


def _notebook_source(path: Path) -> str:
    cells = json.loads(path.read_text())["cells"]
    code = ["".join(c["source"]) for c in cells if c["cell_type"] == "code"]
    return "\n".join(re.sub(r"^\s*[%!].*$", "pass", c, flags=re.M) for c in code)


def _files(modules) -> set:
    return {f for m in modules for f in provenance.module_files(m)}


def test_code_hash_of_every_rule_is_that_of_the_modules_its_script_imports(described):
    code_of = {family: h for family, h in described["code"].items()}
    family_of = {h: family for family, h in code_of.items()}
    assert len(family_of) == len(code_of)
    checked = set()
    for name, rule in described["rules"].items():
        if rule["script"]:
            source = (ROOT / "workflow" / "rules" / rule["script"]).resolve().read_text()
            family = family_of.get(rule["code"])
            assert family, f"rule {name}: its code parameter is not one of the CODE families"
            assert _files(described["code_modules"][family]) == _import_closure(source), (name, family)
            checked.add(family)
    for report, value in described["rules"]["report"]["code"].items():
        closure = _import_closure(_notebook_source(ROOT / "workflow" / "notebooks" / f"{report}.ipynb"))
        if not closure:
            assert value == "", report
        else:
            family = family_of.get(value)
            assert family and _files(described["code_modules"][family]) == closure, report
            checked.add(family)
    assert checked == set(code_of), "a CODE_MODULES family that no rule uses"


def test_solver_jobs_do_not_depend_on_the_records_modules(described):
    solve = _files(described["code_modules"]["solve"])
    records = _files(["records", "studies.record_study"])
    assert solve and not solve & records
    assert described["rules"]["solve_chunk"]["code"] == described["code"]["solve"]
    assert described["rules"]["solve_chunk"]["code"] != described["code"]["records"]


# ----------------------------------------------------------------------------------------------
# the study registry: rule all, reports, index page, SLURM groups and code families derived from it
# ----------------------------------------------------------------------------------------------

def test_rule_all_reports_and_index_are_the_registry_s(described):
    config = described["config"]
    assert described["all"] == registry.all_targets(config)
    assert described["reports"] == registry.reports(config)
    lists = registry.index_lists(config)
    assert described["index"]["datasets"] == lists["datasets"]
    assert described["index"]["figures"] == lists["figures"] and described["index"]["reports"] == lists["reports"]
    # every study's datasets, figures (every format) and reports are targets; nothing else but the index page
    expected = set()
    for study in registry.STUDIES:
        expected |= set(study.dataset_files(config).values())
        expected |= {f"reports/figures/{f}.{ext}" for f in study.figures for ext in config["figures"]["formats"]}
        expected |= set(study.outputs if not callable(study.outputs) else study.outputs(config))
        expected |= {f"reports/{r.name}.html" for r in study.reports}
    assert set(described["all"]) == expected | {"reports/index.html"}
    assert {"results/datasets/storeys.nc", "reports/figures/storeys.pdf"} <= set(described["all"])
    # the index page's job reads every dataset, figure and report it lists
    assert set(lists["datasets"].values()) | set(lists["figures"]) | set(lists["reports"]) <= set(
        described["index_input"])


def test_every_rule_file_is_included_and_every_rule_belongs_to_a_study(described):
    files = registry.rule_files()
    assert sorted(files) == sorted(p.name for p in (ROOT / "workflow" / "rules").glob("*.smk") if p.name != "common.smk")
    assert files[-1] == "reports.smk"
    sources = _rule_sources()
    assert set(registry.slurm_groups()) <= set(sources) == set(described["rules"])


def test_slurm_profile_groups_are_the_registry_s():
    profile = yaml.safe_load((ROOT / "profiles" / "slurm" / "config.yaml").read_text())
    groups = registry.slurm_groups()
    assert profile["groups"] == groups
    assert set(groups.values()) == set(profile["group-components"])
    assert {"storeys_dataset": "merge", "storeys_figure": "figures", "report": "reports"}.items() <= groups.items()
    proc = subprocess.run([sys.executable, "-m", "isoslide.studies", "--check", "profiles/slurm/config.yaml"],
                          cwd=ROOT, capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0, proc.stderr


def test_slurm_groups_block_is_rewritten_from_the_registry(tmp_path):
    from isoslide.studies.__main__ import main

    profile = tmp_path / "config.yaml"
    text = (ROOT / "profiles" / "slurm" / "config.yaml").read_text()
    profile.write_text(text.replace("  storeys_figure: figures\n", "  storeys_figure: solve\n"))
    assert main(["--check", str(profile)]) == 1
    assert main(["--write", str(profile)]) == 0
    assert profile.read_text() == text
    assert main(["--check", str(profile)]) == 0


def test_code_families_are_the_import_closure_of_their_entry_modules(described):
    """Each family's modules, as the workflow hashes them, are the files the family's entry modules
    import (this file's own ast walk, not the registry's): a module missing from a family, or one too
    many, fails here."""
    families = registry.code_families()
    assert set(families) == set(described["code_modules"])
    for family, entries in families.items():
        closure = _import_closure("\n".join(f"import isoslide.{e}" for e in entries))
        assert _files(described["code_modules"][family]) == closure, family
    assert described["code"]["storeys"] != described["code"]["solve"]
    assert "studies.storeys" in described["code_modules"]["storeys"]
    assert "studies.storeys" in described["code_modules"]["isolation_report"]


def test_import_statements_are_read_as_a_full_parse_reads_them():
    """The workflow's quick reading of import statements finds, in every module of the package, the
    imports a full parse finds."""
    for path in sorted(PKG.rglob("*.py")):
        if "__pycache__" in path.parts:
            continue
        name = path.relative_to(PKG).with_suffix("").as_posix().replace("/", ".").removesuffix(".__init__")
        if name == "__init__":
            continue
        source = path.read_text()
        assert imports.imported_modules(source, name) == _isoslide_imports(source, name), name


def test_a_study_added_to_the_registry_is_planned_listed_and_grouped(tmp_path):
    """One more Study (and its rule file) is all it takes: rule all asks for its dataset and figure,
    the index page lists them, and it has its SLURM group."""
    d = copy_workflow(tmp_path / "added")
    (d / "workflow" / "rules" / "extra.smk").write_text(
        'rule extra_dataset:\n    output:\n        "results/datasets/extra.nc",\n'
        '        expand("reports/figures/extra.{ext}", ext=FORMATS),\n'
        '    threads: 1\n    resources:\n        mem_mb=100,\n        runtime=1,\n'
        '    shell:\n        "touch {output}"\n')
    script = (
        "import dataclasses, runpy, sys\n"
        "from isoslide.studies import registry\n"
        "registry.STUDIES = registry.STUDIES + (registry.Study(name='extra', sections=(), datasets=('extra',),"
        " figures=('extra',), rule_files=('extra.smk',), groups={'extra_dataset': 'merge'}),)\n"
        "print('GROUPS', registry.slurm_groups())\n"
        "sys.argv = ['snakemake', '-n', '--configfile', 'config/test.yaml']\n"
        "runpy.run_module('snakemake', run_name='__main__')\n")
    proc = subprocess.run([sys.executable, "-c", script], cwd=d, capture_output=True, text=True, timeout=300, env=ENV)
    out = proc.stdout + proc.stderr
    assert proc.returncode == 0, out[-4000:]
    assert "'extra_dataset': 'merge'" in out
    jobs = planned_jobs(out)
    assert ("extra_dataset", "") in jobs
    block = [b for b in _job_blocks(out) if re.search(r"^\s*rule all:", b, re.M)][0]
    assert "results/datasets/extra.nc" in block and "reports/figures/extra.pdf" in block
    index = [b for b in _job_blocks(out) if re.search(r"^\s*rule index_page:", b, re.M)][0]
    assert "results/datasets/extra.nc" in index and "reports/figures/extra.png" in index


# ----------------------------------------------------------------------------------------------
# dry runs and configuration errors
# ----------------------------------------------------------------------------------------------

def test_dry_run_plans_the_whole_dag(wf):
    _, out = snakemake(wf, "-n", *TEST_CONFIG, timeout=300)
    jobs = planned_jobs(out)
    rules = {r for r, _ in jobs}
    assert {"solve_chunk", "merge_study", "merge_isolation_study", "similarity", "figure", "fig4_record",
            "record_compare", "records_dataset", "figure_records", "accuracy_part", "accuracy_dataset",
            "fragility_chunk", "fragility_dataset", "fragility_pelicun", "fragility_figure", "rocking_datasets",
            "report", "all"} | ISOLATION_RULES <= rules
    assert sorted(w for r, w in jobs if r == "report") == [f"report={r}" for r in REPORTS]
    chunk_wildcards = [w for r, w in jobs if r == "solve_chunk"]
    assert all(re.fullmatch(r"study=\w+, chunk=\d+", w) for w in chunk_wildcards)
    # a study of one chunk (e.g. fig3_newmark: 6 scenes, chunk_size 15) is solved by its merge job
    specs = isoslide.studies.sweep.check_config(isoslide.config.load(
        ROOT / "config" / "config.yaml", yaml.safe_load((ROOT / "config" / "test.yaml").read_text())))
    several = {f"study={name}" for name, spec in specs.items() if len(isoslide.studies.sweep.spec_chunks(spec)) > 1}
    assert "study=fig3_newmark" not in several and len(several) >= 2
    assert {w.split(",")[0] for w in chunk_wildcards} == several
    assert {w for r, w in jobs if r == "merge_study"} == {f"study={s}" for s in STUDIES}
    assert {w for r, w in jobs if r == "merge_isolation_study"} == {f"study={s}" for s in ISOLATION_STUDIES}
    # the isolation studies of config/test.yaml are one chunk each: no solve_chunk job, one job per rule
    assert not [w for w in chunk_wildcards if "study=iso_" in w]
    assert all(sum(r == rule for r, _ in jobs) == 1 for rule in ISOLATION_RULES)
    # the fragility study: 12 analyses per base in chunks of 5 (config/test.yaml) -> 3 chunk jobs each
    assert sorted(w for r, w in jobs if r == "fragility_chunk") == [
        f"frag={f}, chunk={c}" for f in ("fragility", "fragility_fixed_base") for c in range(3)]
    assert {w for r, w in jobs if r == "fragility_dataset"} == {"frag=fragility", "frag=fragility_fixed_base"}
    # the planar fragility analyses: 8 per base in chunks of 5 (config/test.yaml) -> 2 chunk jobs each
    assert sorted(w for r, w in jobs if r == "fragility_planar_chunk") == [
        f"pfrag={f}, chunk={c}" for f in ("fragility_planar", "fragility_planar_fixed_base") for c in range(2)]
    assert {w for r, w in jobs if r == "fragility_planar_dataset"} == {
        "pfrag=fragility_planar", "pfrag=fragility_planar_fixed_base"}


@pytest.mark.parametrize("overlay, key", [
    ({"chunk_size": 0}, "chunk_size"),
    ({"studies": {"fig6_pi5": {"dims": {"pi5": [0.5, 1.5]}}}}, "pi5"),
    ({"studies": {"fig5_pi3": {"pulse": "sine"}}}, "studies.fig5_pi3.pulse"),
    ({"studies": {"fig8_pi8": {"dims": {"pi3": [1.0, 1.0]}}}}, "studies.fig8_pi8.dims.pi3"),
    ({"similarity": {"complete": {"pi5": {"study": "nope", "range": [0.7, 1.0]}}}}, "similarity.complete.pi5.study"),
    ({"fragility": {"stripes": {"levels": [3.0, 2.0]}}}, "fragility.stripes.levels"),
    ({"fragility": {"records": ["Northridge_1994_PAC-175", "no_such_record"]}}, "fragility.records[1]"),
    ({"fragility": {"limit_states": [0.3, 0.2]}}, "fragility.limit_states"),
    ({"isolation": {"flexible": {"pi12": [0.1, 0.5]}}}, "isolation.flexible.pi12"),
    ({"isolation": {"friction_pendulum": {"pi9": [0.1, -0.1]}}}, "['friction_pendulum']['pi9']"),
    ({"isolation": {"bearings": {"a_p": [2.0, 1.0]}}}, "isolation.bearings.a_p = [2.0, 1.0] is not strictly increasing"),
    ({"storeys": {"storeys": [2, 1]}}, "storeys.storeys = [2, 1] is not strictly increasing"),
    ({"rocking": {"spectra": {"pi3": [1.0, 2.0]}}}, "rocking.spectra.pi3 = [1.0, 2.0] does not start at 0.0"),
])
def test_invalid_config_fails_before_any_job_naming_the_key(tmp_path, overlay, key):
    d = copy_workflow(tmp_path / "bad")
    (d / "config" / "bad.yaml").write_text(yaml.safe_dump(overlay))
    code, out = snakemake(d, "--cores", "1", *TEST_CONFIG, "config/bad.yaml", check=False,
                          timeout=300)
    assert code != 0
    assert key in out, out[-3000:]
    assert not (d / "results").exists() and not (d / "logs").exists()


# ----------------------------------------------------------------------------------------------
# the tiny end-to-end run
# ----------------------------------------------------------------------------------------------

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
        log = (wf / "logs" / "merge_study" / f"{s}.log").read_text()
        assert provenance.source_text().split(" (git")[0] in log and log.rstrip().endswith("done")
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
def test_workflow_runs_without_the_interpreter_on_path(full_run):
    """The run above had no activated environment: papermill, nbconvert and the notebook kernel
    were found through the interpreter that runs Snakemake, not through PATH."""
    wf, _ = full_run
    assert str(Path(sys.executable).parent) not in ENV["PATH"].split(os.pathsep)
    for name in LAUNCHERS:
        assert shutil.which(name, path=ENV["PATH"]) is None, name
    python = shutil.which("python", path=ENV["PATH"])
    assert python is None or Path(python).resolve() != Path(sys.executable).resolve()
    for report in REPORTS:
        assert (wf / "reports" / f"{report}.html").stat().st_size > 0, report
        nb = json.loads((wf / "logs" / "report" / f"{report}.ipynb").read_text())
        assert nb["metadata"]["papermill"]["exception"] is not True, report


@pytest.mark.slow
def test_one_report_rule_makes_every_report_the_same_way(full_run, described):
    wf, _ = full_run
    for report in REPORTS:
        entry = described["reports"][report]
        parameters = {**entry.get("data", {}), **entry.get("parameters", {})}
        html = (wf / "reports" / f"{report}.html").read_text()
        assert "Traceback" not in html, report
        assert "data:image/png;base64," in html, report                   # --embed-images
        assert not re.search(r'<img[^>]+src="(?!data:)', html), report
        for name in parameters:                                            # --no-input
            assert f"{name} = " not in html, (report, name)
        # the executed notebook is kept as the job's log, with the parameters papermill injected
        nb = json.loads((wf / "logs" / "report" / f"{report}.ipynb").read_text())
        assert nb["metadata"]["papermill"]["parameters"] == parameters, report
        injected = [c for c in nb["cells"] if "injected-parameters" in c["metadata"].get("tags", [])]
        assert len(injected) == 1 and all(str(v) in "".join(injected[0]["source"]) for v in parameters.values())
        assert "Executing notebook with kernel: python3" in (wf / "logs" / "report" / f"{report}.log").read_text()
        assert not (wf / "reports" / f"{report}.ipynb").exists(), report


@pytest.mark.slow
def test_benchmark_files_of_every_job(full_run):
    wf, _ = full_run
    _, out = snakemake(wf, "-n", "--forceall", *TEST_CONFIG, timeout=300)
    benchmarks = planned_benchmarks(out)
    assert len(benchmarks) > 40
    for (rule, wildcards), path in benchmarks.items():
        if rule == "all":
            assert path is None
            continue
        assert path and path.startswith(f"results/benchmarks/{rule}/"), (rule, wildcards)
        with open(wf / path, newline="") as f:
            rows = list(csv.DictReader(f, delimiter="\t"))
        assert len(rows) == 1, path
        assert float(rows[0]["s"]) > 0 and float(rows[0]["max_rss"]) > 0, path


@pytest.mark.slow
def test_time_budget_by_phase_of_the_run(full_run):
    """python -m isoslide.budget splits the run's job time into its phases."""
    wf, _ = full_run
    proc = subprocess.run([sys.executable, "-m", "isoslide.budget"], cwd=wf, capture_output=True, text=True,
                          timeout=120, env=ENV)
    assert proc.returncode == 0, proc.stderr
    rows = {line.split()[0]: line.split() for line in proc.stdout.splitlines()[1:7]}
    assert list(rows) == ["start-up", "compilation", "solving", "writing", "reporting", "other"]
    for name in ("start-up", "compilation", "solving", "writing", "reporting"):
        assert int(rows[name][1]) > 0 and float(rows[name][2]) > 0, proc.stdout
    assert "wall-clock of the last run:" in proc.stdout and "unknown" not in proc.stdout, proc.stdout


@pytest.mark.slow
def test_records_outputs(full_run):
    from isoslide.reports.figures import read_caption
    from isoslide.studies.record_study import FIG4_RECORD, ratio_summary

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
    # the accuracy scene set comes from the paper's studies (the package's), so it is not measured
    # again; nor are the records
    assert {r for r, _ in jobs} <= {"solve_chunk", "merge_study", "similarity", "figure",
                                     "report", "index_page", "all"}
    assert {w for r, w in jobs if r == "figure"} == {"fig=fig7"}
    assert {w for r, w in jobs if r == "report"} == {"report=similarity", "report=figures"}


@pytest.mark.slow
def test_changing_the_records_reruns_only_record_jobs(full_run):
    wf, _ = full_run
    (wf / "config" / "rec.yaml").write_text(yaml.safe_dump({"records": {"pi4": 0.2}}))
    _, out = snakemake(wf, "-n", *TEST_CONFIG, "config/rec.yaml", timeout=300)
    jobs = planned_jobs(out)
    rules = {r for r, _ in jobs}
    assert {"record_compare", "records_dataset", "figure_records", "report"} <= rules
    assert rules <= {"record_compare", "records_dataset", "figure_records", "report", "index_page", "all"}, rules
    assert {w for r, w in jobs if r == "report"} == {"report=records", "report=figures"}


@pytest.mark.slow
def test_fragility_outputs(full_run):
    """The fragility datasets, the pelicun CSV, the figure and the report of the tiny run."""
    wf, _ = full_run
    cfg = isoslide.config.load(ROOT / "config" / "config.yaml",
                               yaml.safe_load((ROOT / "config" / "test.yaml").read_text()))["fragility"]
    n = len(cfg["records"]) * len(cfg["stripes"]["levels"]) * cfg["friction_samples"]
    for name in ("fragility", "fragility_fixed_base"):
        ds = datasets.open_dataset(wf / "results" / "datasets" / f"{name}.nc")
        assert ds.sizes["analysis"] == n and list(ds.limit_state.values) == cfg["limit_states"]
        assert ds["theta"].dims == ("limit_state", "im") and list(ds.im.values) == ["pga", "pgv", "pfa", "pfv"]
        assert ds.attrs["Conventions"].startswith("CF") and "isoslide_config" in ds.attrs
        log = (wf / "logs" / "fragility_dataset" / f"{name}.log").read_text()
        assert "merging 3 chunk files" in log and log.rstrip().endswith("done")
    assert (wf / "results" / "fragility" / "pelicun_damage_db.csv").stat().st_size > 0
    for ext in ("png", "pdf"):
        assert (wf / "reports" / "figures" / f"fragility.{ext}").stat().st_size > 1000
    p = cfg["planar"]
    n_planar = len(p["suites"]) * p["pairs"] * len(p["angles"]) * len(p["stripes"]["levels"]) * p["friction_samples"]
    for name in ("fragility_planar", "fragility_planar_fixed_base"):
        ds = datasets.open_dataset(wf / "results" / "datasets" / f"{name}.nc")
        assert ds.sizes["analysis"] == n_planar and list(ds.motion.values) == ["planar", "one_component",
                                                                               "max_component"]
        log = (wf / "logs" / "fragility_planar_dataset" / f"{name}.log").read_text()
        assert "merging 2 chunk files" in log and log.rstrip().endswith("done")
    html = (wf / "reports" / "fragility.html").read_text()
    assert "Fragility of sliding contents" in html and "Traceback" not in html
    assert "both components at once against one at a time" in html


@pytest.mark.slow
def test_isolation_outputs(full_run):
    """The isolation datasets, figures and report of the tiny run."""
    wf, _ = full_run
    cfg = isoslide.config.load(ROOT / "config" / "config.yaml",
                               yaml.safe_load((ROOT / "config" / "test.yaml").read_text()))["isolation"]
    for name in ISOLATION_STUDIES:
        ds = datasets.open_dataset(wf / "results" / "datasets" / f"{name}.nc")
        assert ds["pi1"].dims[-1] == "pi2" and ds.attrs["Conventions"].startswith("CF")
        assert ds.attrs["floor"] == ("roof" if name == "iso_flex_roof" else "base")
    rigid = datasets.open_dataset(wf / "results" / "datasets" / "isolation_rigid.nc")
    assert rigid["rel_error"].dims == ("floor", "pi3", "pi12", "pi2")
    assert list(rigid["pi12"].values) == cfg["flexible"]["pi12"]
    design = datasets.open_dataset(wf / "results" / "datasets" / "isolation_design.nc")
    assert design.sizes["excitation"] == len(cfg["design"]["pulses"]) * len(cfg["design"]["T_p"]) + len(
        cfg["design"]["records"])
    assert design.sizes["mu_k"] == cfg["design"]["mu_k"]["num"] and "isoslide_config" in design.attrs
    bearings = datasets.open_dataset(wf / "results" / "datasets" / "isolation_bearings.nc")
    assert bearings["u_max"].dims == ("building", "isolator", "a_p", "mu_k")
    assert bearings["a_p"].values.tolist() == cfg["bearings"]["a_p"] and "isoslide_config" in bearings.attrs
    log = (wf / "logs" / "isolation_bearings" / "isolation_bearings.log").read_text()
    assert provenance.source_text().split(" (git")[0] in log and log.rstrip().endswith("done")
    for fig in ("isolation_bearings", "isolation_flexible", "isolation_rigid", "isolation_design",
                "isolation_intensity"):
        for ext in ("png", "pdf"):
            assert (wf / "reports" / "figures" / f"{fig}.{ext}").stat().st_size > 1000, (fig, ext)
    html = (wf / "reports" / "isolation.html").read_text()
    assert "Buildings as engineers isolate them" in html and "Traceback" not in html
    assert "Where the paper&#39;s rigid-superstructure reduction holds" in html or \
        "Where the paper's rigid-superstructure reduction holds" in html
    assert "What the bearing does to the contents, from service-level shaking to beyond the design" in html
    assert 'href="isolation.html"' in (wf / "reports" / "index.html").read_text()


@pytest.mark.slow
def test_changing_the_isolation_design_reruns_only_its_jobs(full_run):
    wf, _ = full_run
    (wf / "config" / "iso.yaml").write_text(yaml.safe_dump({"isolation": {"design": {"beta_eff": 0.15}}}))
    _, out = snakemake(wf, "-n", *TEST_CONFIG, "config/iso.yaml", timeout=300)
    jobs = planned_jobs(out)
    # the bearing study's isolators are the design's
    assert {r for r, _ in jobs} == {"isolation_design", "isolation_bearings", "isolation_figure", "report",
                                    "index_page", "all"}
    assert {w for r, w in jobs if r == "report"} == {"report=isolation"}
    # the design's excitations are not the bearing study's
    (wf / "config" / "iso.yaml").write_text(yaml.safe_dump({"isolation": {"design": {"a_p_g": 0.4}}}))
    _, out = snakemake(wf, "-n", *TEST_CONFIG, "config/iso.yaml", timeout=300)
    assert {r for r, _ in planned_jobs(out)} == {"isolation_design", "isolation_figure", "report", "index_page", "all"}
    # the bearing study's own settings: only its job, the figures and the report
    (wf / "config" / "iso.yaml").write_text(yaml.safe_dump({"isolation": {"bearings": {"rate": 10.0}}}))
    _, out = snakemake(wf, "-n", *TEST_CONFIG, "config/iso.yaml", timeout=300)
    assert {r for r, _ in planned_jobs(out)} == {"isolation_bearings", "isolation_figure", "report", "index_page",
                                                 "all"}
    # the band of the rigid reduction: only its map, the figures and the report
    (wf / "config" / "iso.yaml").write_text(yaml.safe_dump({"isolation": {"flexible": {"tolerance": 0.2}}}))
    _, out = snakemake(wf, "-n", *TEST_CONFIG, "config/iso.yaml", timeout=300)
    jobs = planned_jobs(out)
    assert {r for r, _ in jobs} == {"isolation_rigid", "isolation_figure", "report", "index_page", "all"}


@pytest.mark.slow
def test_changing_the_fragility_study_reruns_only_fragility_jobs(full_run):
    wf, _ = full_run
    (wf / "config" / "frag.yaml").write_text(yaml.safe_dump({"fragility": {"seed": 7}}))
    _, out = snakemake(wf, "-n", *TEST_CONFIG, "config/frag.yaml", timeout=300)
    rules = {r for r, _ in planned_jobs(out)}
    assert {"fragility_chunk", "fragility_dataset", "fragility_pelicun", "fragility_figure", "report",
            "fragility_planar_chunk", "fragility_planar_dataset"} <= rules
    assert rules <= {"fragility_chunk", "fragility_dataset", "fragility_pelicun", "fragility_figure", "report",
                     "fragility_planar_chunk", "fragility_planar_dataset", "index_page", "all"}, rules
    assert {w for r, w in planned_jobs(out) if r == "report"} == {"report=fragility"}


@pytest.mark.slow
def test_rocking_outputs(full_run):
    """The rocking datasets, the pelicun CSV and the report of the tiny run."""
    wf, _ = full_run
    cfg = isoslide.config.load(ROOT / "config" / "config.yaml",
                               yaml.safe_load((ROOT / "config" / "test.yaml").read_text()))["rocking"]
    spectra = datasets.open_dataset(wf / "results" / "datasets" / "rocking_spectra.nc")
    assert spectra["theta_max_over_alpha"].dims == ("pulse", "pi3", "pi19", "pi21")
    assert spectra["pi3"].values.tolist() == cfg["spectra"]["pi3"] and "isoslide_config" in spectra.attrs
    rock_map = datasets.open_dataset(wf / "results" / "datasets" / "rocking_map.nc")
    assert rock_map["response"].dims == ("pi3", "mu_s", "pi18") and rock_map["mu_s"].values.tolist() == cfg["map"]["mu_s"]
    frag = datasets.open_dataset(wf / "results" / "datasets" / "rocking_fragility.nc")
    assert frag.sizes["record"] == cfg["fragility"]["motions"] and "overturned" in frag
    log = (wf / "logs" / "rocking_datasets" / "rocking_datasets.log").read_text()
    assert provenance.source_text().split(" (git")[0] in log and log.rstrip().endswith("done")
    assert (wf / "results" / "rocking" / "pelicun_damage_db.csv").read_text().startswith("ID,Incomplete,")
    html = (wf / "reports" / "rocking.html").read_text()
    assert "Contents that rock" in html and "Traceback" not in html
    assert "Does isolation protect the block or expose it?" in html and "Overturning fragility" in html
    assert 'href="rocking.html"' in (wf / "reports" / "index.html").read_text()


@pytest.mark.slow
def test_changing_the_rocking_study_reruns_only_its_job_and_report(full_run):
    wf, _ = full_run
    (wf / "config" / "rock.yaml").write_text(yaml.safe_dump({"rocking": {"map": {"a_p_over_g": 0.6}}}))
    _, out = snakemake(wf, "-n", *TEST_CONFIG, "config/rock.yaml", timeout=300)
    jobs = planned_jobs(out)
    assert {r for r, _ in jobs} == {"rocking_datasets", "report", "index_page", "all"}
    assert {w for r, w in jobs if r == "report"} == {"report=rocking"}


def _digests(directory: Path) -> dict:
    return {p.name: hashlib.sha256(p.read_bytes()).hexdigest() for p in sorted(directory.glob("*.nc"))}


@pytest.mark.slow
def test_sigkill_then_unlock_and_restart_gives_the_same_bytes(full_run, tmp_path):
    """A second run of the same config, SIGKILLed mid-way and resumed, writes every file under
    results/datasets/ byte for byte as the first; wall-clock costs live apart in *_timings.nc."""
    wf, _ = full_run
    d = copy_workflow(tmp_path / "killed")
    cmd = [sys.executable, "-m", "snakemake", "--cores", "2", *TEST_CONFIG]
    proc = subprocess.Popen(cmd, cwd=d, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=ENV,
                            start_new_session=True)
    try:
        deadline = time.monotonic() + 600
        while time.monotonic() < deadline and proc.poll() is None:
            if len(list((d / "results" / "chunks").rglob("*.nc"))) >= 2:   # a few chunks done
                break
            time.sleep(0.1)
        alive_at_kill = proc.poll() is None
        missing_at_kill = [s for s in STUDIES if not (d / "results" / "datasets" / f"{s}.nc").exists()]
        if alive_at_kill:
            os.killpg(proc.pid, signal.SIGKILL)        # the run and every job it started
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
    assert alive_at_kill and proc.returncode == -signal.SIGKILL, "the run ended before it was killed"
    assert missing_at_kill, "every dataset was already written when the run was killed"

    # a SIGKILLed Snakemake cannot remove its lock: the next run stops and says what to do
    # (profiles/default/config.yaml documents it)
    assert list((d / ".snakemake" / "locks").iterdir())
    code, out = snakemake(d, "--cores", "2", *TEST_CONFIG, check=False, timeout=300)
    assert code != 0 and "cannot be locked" in out and "--unlock" in out, out[-3000:]
    snakemake(d, "--unlock", *TEST_CONFIG, timeout=300)
    snakemake(d, "--cores", "2", *TEST_CONFIG, timeout=1500)
    first, second = _digests(wf / "results" / "datasets"), _digests(d / "results" / "datasets")
    assert len(first) >= len(STUDIES) + 4 and "accuracy.nc" in first
    differ = sorted(k for k in first if first[k] != second.get(k))
    for name in differ:   # say what differs before failing
        a = datasets.open_dataset(wf / "results" / "datasets" / name)
        b = datasets.open_dataset(d / "results" / "datasets" / name)
        datasets.assert_same_data(a, b)
    assert {"fragility.nc", "fragility_fixed_base.nc"} <= set(first)
    assert first == second, f"not byte-identical: {differ}"
    timings = sorted(p.name for p in (d / "results" / "timings").glob("*.nc"))
    assert timings and all(t.endswith("_timings.nc") for t in timings)
