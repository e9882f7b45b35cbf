# Helpers shared by the rules: the checked study specifications, the file lists, the code each
# family of rules runs and the table of reports.  Everything here is computed from the config and
# the study registry (isoslide.studies.registry: rule files, `rule all`, reports, index page, code
# families, SLURM groups); nothing runs the solver.

import os
import shlex
import sys

from snakemake.exceptions import WorkflowError

import isoslide.studies.fragility_planar as fragility_planar
import isoslide.studies.fragility_study as fragility_study
import isoslide.studies.isolation_study as isolation_study
import isoslide.studies.similarity as similarity
import isoslide.studies.sweep as sweep
from isoslide.store.provenance import code_hash
from isoslide.studies import registry

# Semantic checks beyond the JSON schema (Pi ranges, pulse names, key consistency); a bad value
# stops the workflow here, before any job runs, with its key path in the message.
try:
    SPECS = sweep.check_config(config)
    # the isolation studies (friction pendulum, lead-rubber, flexible superstructure on base and roof):
    # ordinary studies of the `isolation:` section, solved and merged by the same rules
    ISOLATION_SPECS = isolation_study.study_specs(config)
    isolation_study.check_bearings(config["isolation"]["bearings"])
except sweep.ConfigError as err:
    raise WorkflowError(f"Invalid configuration: {err}")
STUDY_SPECS = SPECS | ISOLATION_SPECS  # every study the rules of sweep.smk solve

STUDIES = sorted(SPECS)
DATASETS = expand("results/datasets/{study}.nc", study=STUDIES)
FIGURES = [f"fig{n}" for n in range(1, 9)]
FORMATS = config["figures"]["formats"]
FIGURE_FILES = expand("reports/figures/{fig}.{ext}", fig=FIGURES, ext=FORMATS)
SIMILARITY_SETTINGS = sweep.jsonable(config["similarity"])
BUCKINGHAM_SETTINGS = {k: SIMILARITY_SETTINGS[k] for k in similarity.BUCKINGHAM_KEYS}
FIGURE_SETTINGS = sweep.jsonable(config["figures"])

# The isoslide modules behind each family of rules: the import closure of the entry modules each
# study declares for the family (its scripts' or notebook's imports; isoslide.studies.registry),
# computed from the sources.  Their hash is a rule parameter, so editing one of them reruns exactly
# the jobs that run it (Snakemake's `code` trigger only sees the script itself); tests/test_workflow.py
# checks each family against the imports of the scripts and notebooks that use it.
CODE_MODULES = registry.code_modules()
CODE = {family: code_hash(include=modules) for family, modules in CODE_MODULES.items()}

# Real records against their fitted pulses (workflow/rules/records.smk).
RECORDS_SETTINGS = sweep.jsonable(
    {"records": config["records"], "defaults": config["defaults"], "solver": config["solver"]}
)
RECORDS = list(config["records"]["names"])
FIG4_SETTINGS = {"records": {"fig4": config["records"]["fig4"]}}  # Fig. 4 depends on its record only
RECORD_FIGURE_FILES = expand("reports/figures/records.{ext}", ext=FORMATS)

# The fragility study (workflow/rules/fragility.smk): checked here, so a bad value or a record that
# cannot be read stops the workflow before any job runs.
FRAGILITY_SETTINGS = sweep.jsonable(fragility_study.fragility_settings(config))
try:
    FRAGILITY_STUDY = fragility_study.check_settings(FRAGILITY_SETTINGS)
except ValueError as err:
    raise WorkflowError(f"Invalid configuration: {err}")
FRAGILITY_DATASETS = fragility_study.dataset_names(FRAGILITY_SETTINGS)
FRAGILITY_RECORD_FILES = [r for r in FRAGILITY_SETTINGS["fragility"]["records"]
                          if os.path.splitext(r)[1].lower() in (".at2", ".csv") and os.path.isfile(r)]
FRAGILITY_FIGURE_FILES = expand("reports/figures/fragility.{ext}", ext=FORMATS)
FRAGILITY_FIGURE_INPUT = {"isolated": "results/datasets/fragility.nc"} | (
    {"fixed_base": "results/datasets/fragility_fixed_base.nc"} if len(FRAGILITY_DATASETS) > 1 else {})

# The planar fragility analyses (`fragility.planar`, isoslide.studies.fragility_planar): recorded
# pairs of suites, checked here (the suites are read), so a bad value stops the workflow before any job.
PLANAR_FRAGILITY_SETTINGS = sweep.jsonable(fragility_planar.planar_settings(config))
PLANAR_FRAGILITY_DATASETS = fragility_planar.dataset_names(PLANAR_FRAGILITY_SETTINGS)
try:
    PLANAR_FRAGILITY_STUDY = (fragility_planar.check_settings(PLANAR_FRAGILITY_SETTINGS)
                              if PLANAR_FRAGILITY_DATASETS else None)
except ValueError as err:
    raise WorkflowError(f"Invalid configuration: {err}")
# a suite given as a manifest (.csv) is an input file; built-in suites are read from installed packages
PLANAR_FRAGILITY_SUITE_FILES = [s for s in PLANAR_FRAGILITY_SETTINGS["fragility"]["planar"]["suites"]
                                if os.path.splitext(s)[1].lower() == ".csv" and os.path.isfile(s)]

# Buildings as engineers isolate them (workflow/rules/isolation.smk).
ISOLATION_SETTINGS = sweep.jsonable(isolation_study.isolation_settings(config))
# each rule gets only the sections it reads, so editing one part reruns only its jobs
ISOLATION_RIGID_SETTINGS = {"isolation": {"flexible": ISOLATION_SETTINGS["isolation"]["flexible"]}}
ISOLATION_DESIGN_SETTINGS = ISOLATION_SETTINGS | {"isolation": {"design": ISOLATION_SETTINGS["isolation"]["design"]}}
# the bearing study: its subsection and the design keys of its isolators (not the design's excitations)
ISOLATION_BEARINGS_SETTINGS = isolation_study.bearing_settings(ISOLATION_SETTINGS)
ISOLATION_STUDIES = list(ISOLATION_SPECS)
ISOLATION_DATASETS = isolation_study.dataset_names()
ISOLATION_RECORD_FILES = [r for r in ISOLATION_SETTINGS["isolation"]["design"]["records"]
                          if os.path.splitext(r)[1].lower() in (".at2", ".csv") and os.path.isfile(r)]
ISOLATION_FIGURE_INPUT = {name: f"results/datasets/{name}.nc" for name in ISOLATION_DATASETS}
ISOLATION_FIGURE_FILES = expand("reports/figures/{fig}.{ext}", fig=list(registry.ISOLATION_FIGURES), ext=FORMATS)

for _name, _c in SIMILARITY_SETTINGS.get("complete", {}).items():
    if _c["study"] not in SPECS:
        raise WorkflowError(
            f"Invalid configuration: similarity.complete.{_name}.study = {_c['study']!r} "
            f"is not a study; known: {STUDIES}"
        )

# HTML reports, made by the one `report` rule of workflow/rules/reports.smk from
# workflow/notebooks/<report>.ipynb (papermill, then nbconvert), joined from the studies' shares
# (isoslide.studies.registry.Report).  Per report:
#   data        input files handed to the notebook, each as the parameter of the same name;
#   parameters  further notebook parameters (values);
#   needs       further input files the notebook reads (e.g. the figures of a directory);
#   code        the CODE_MODULES family of the isoslide modules the notebook imports (if any).
REPORTS = registry.reports(config)

# The targets of the default rule `all` (every study's datasets, figures and further files, every
# report and the index page).
ALL_TARGETS = registry.all_targets(config)

# reports/index.html, made by index_page in workflow/rules/reports.smk.  It lists the datasets
# (name to file), shows the figures (PNG; the PDF of the same name is linked), links the reports
# and shows the complete configuration; `needs` are the figures' other formats.
INDEX = registry.index_lists(config) | {
    "needs": registry.figure_files([f for s in registry.STUDIES for f in s.figures], FORMATS),
    "config": sweep.jsonable(config),
}


def chunk_files(wildcards):
    """Chunk files of one study; none for a study of one chunk (merge_study solves it itself)."""
    spec = STUDY_SPECS[wildcards.study]
    if len(sweep.spec_chunks(spec)) == 1:
        return []
    return expand(
        "results/chunks/{study}/{chunk}.nc",
        study=wildcards.study,
        chunk=sweep.spec_chunks(spec),
    )


def fragility_chunk_files(wildcards):
    """Chunk files of a fragility dataset; none for one chunk (fragility_dataset solves it itself)."""
    n = fragility_study.n_chunks(FRAGILITY_STUDY)
    if n == 1:
        return []
    return expand("results/chunks/{frag}/{chunk}.nc", frag=wildcards.frag, chunk=range(n))


def planar_fragility_chunk_files(wildcards):
    """Chunk files of a planar fragility dataset; none for one chunk (its dataset job solves it)."""
    n = fragility_planar.n_chunks(PLANAR_FRAGILITY_STUDY)
    if n == 1:
        return []
    return expand("results/chunks/{pfrag}/{chunk}.nc", pfrag=wildcards.pfrag, chunk=range(n))


def figure_datasets(wildcards):
    """Datasets a figure is drawn from (by the studies' `figure:` number)."""
    number = int(wildcards.fig[3:])
    out = {
        name: f"results/datasets/{name}.nc"
        for name in STUDIES
        if SPECS[name]["figure"] == number
    }
    if number == 4:  # the real record that stands in for the paper's Rinaldi record
        out["record"] = "results/datasets/fig4_record.nc"
    return out


def report_input(wildcards):
    """Notebook, data files and further files of one report (see REPORTS)."""
    entry = REPORTS[wildcards.report]
    return {
        "notebook": f"workflow/notebooks/{wildcards.report}.ipynb",
        **entry.get("data", {}),
        "needs": entry.get("needs", []),
    }


def report_parameters(wildcards, input):
    """`papermill -p NAME VALUE` options of one report: its data files, then its parameters."""
    entry = REPORTS[wildcards.report]
    values = {name: input[name] for name in entry.get("data", {})}
    values.update(entry.get("parameters", {}))
    return " ".join(f"-p {name} {shlex.quote(str(value))}" for name, value in values.items())
