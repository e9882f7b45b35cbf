# Helpers shared by the rules: the checked study specifications and the file lists.
# Everything here is computed from the config; nothing runs the solver.

import sys

from snakemake.exceptions import WorkflowError

import isoslide.sweep as sweep
from isoslide.datasets import code_hash

# Semantic checks beyond the JSON schema (Pi ranges, pulse names, key consistency); a bad value
# stops the workflow here, before any job runs, with its key path in the message.
try:
    SPECS = sweep.check_config(config)
except sweep.ConfigError as err:
    raise WorkflowError(f"Invalid configuration: {err}")

STUDIES = sorted(SPECS)
DATASETS = expand("results/datasets/{study}.nc", study=STUDIES)
FIGURES = [f"fig{n}" for n in range(1, 9)]
FORMATS = config["figures"]["formats"]
FIGURE_FILES = expand("reports/figures/{fig}.{ext}", fig=FIGURES, ext=FORMATS)
SIMILARITY_SETTINGS = sweep.jsonable(config["similarity"])
FIGURE_SETTINGS = sweep.jsonable(config["figures"])

# Hashes of the package code behind each step, passed as parameters so that editing isoslide reruns the
# jobs that depend on the edited modules (Snakemake's `code` trigger only sees the script itself).
# The solver's modules: those the package loads on import, plus the peer solvers of `method:`.
_LOADED = {m.split(".")[1] for m in sys.modules if m.startswith("isoslide.")}
SOLVER_CODE = code_hash(include=_LOADED | {"regularized", "reference"}, exclude=("figures", "similarity"))
SIMILARITY_CODE = code_hash(include=("similarity", "pulses", "scene", "datasets"))
FIGURE_CODE = code_hash(include=("figures", "pulses", "scene", "datasets", "record_study"))
RECORDS_CODE = code_hash(include=_LOADED | {"records", "record_study", "pulses", "datasets"},
                         exclude=("figures", "similarity", "accuracy"))

# Real records against their fitted pulses (workflow/rules/records.smk).
RECORDS_SETTINGS = sweep.jsonable(
    {"records": config["records"], "defaults": config["defaults"], "solver": config["solver"]}
)
RECORDS = list(config["records"]["names"])
FIG4_SETTINGS = {"records": {"fig4": config["records"]["fig4"]}}  # Fig. 4 depends on its record only
RECORD_FIGURE_FILES = expand("reports/figures/records.{ext}", ext=FORMATS)

for _name, _c in SIMILARITY_SETTINGS.get("complete", {}).items():
    if _c["study"] not in SPECS:
        raise WorkflowError(
            f"Invalid configuration: similarity.complete.{_name}.study = {_c['study']!r} "
            f"is not a study; known: {STUDIES}"
        )


def chunk_files(wildcards):
    """Chunk files of one study."""
    spec = SPECS[wildcards.study]
    return expand(
        "results/chunks/{study}/{chunk}.nc",
        study=wildcards.study,
        chunk=sweep.spec_chunks(spec),
    )


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
