# isoslide: Pi-grid fan-out -> labelled netCDF -> every paper figure -> HTML reports.
#
#   snakemake --cores 2                                   # everything (config/config.yaml)
#   snakemake --cores 2 --configfile config/test.yaml     # tiny end-to-end run
#
# The science lives in the isoslide package; rules only wire files together
# (see workflow/rules/*.smk).  Default options come from profiles/default/config.yaml.
# Every compute rule writes a benchmark (results/benchmarks/<rule>/...tsv).  The `resources:` of
# each rule are sized from those of the default run (`snakemake --cores 2` from empty results/, 50
# jobs, 2 min 26 s on 2 shared cores; the numbers are next to each rule): mem_mb about twice the
# largest max_rss, runtime (minutes) at least ten times the longest wall time, since machines differ
# in speed (about twice between two machines of this kind measured) and a job that runs outside this
# Snakefile's start (below) compiles what the shipped kernels lack.

import os
import re
import shlex
import sys

from snakemake.utils import min_version, validate

min_version("9.0")

# Every job is single-threaded; one BLAS/OpenMP thread also keeps sums in a fixed order, so the
# same config gives the same bytes on any machine (jobs inherit this environment, locally and on
# a cluster, where each job reads this file again).
for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"


# The compiled kernels: where the ones shipped with the package do not fit (another numba, a non-x86
# machine, ISOSLIDE_CPU_TARGET=host), compile them once here, saying so in one line, before any job
# starts; the jobs, parallel or on a cluster's nodes, then load them from numba's cache instead of
# each compiling them again (isoslide.jit_cache warm; a quick check when the shipped kernels fit).
onstart:
    shell(f"{shlex.quote(sys.executable)} -m isoslide.jit_cache warm")


configfile: "config/config.yaml"


validate(config, "config/schema.yaml")


include: "workflow/rules/common.smk"


wildcard_constraints:
    study="|".join(STUDY_SPECS),
    chunk=r"\d+",
    fig=r"fig[1-8]",
    record="|".join(re.escape(r) for r in RECORDS),
    report="|".join(REPORTS),
    frag="|".join(FRAGILITY_DATASETS),


# Each study's rules (the study registry, isoslide.studies.registry, lists their files; the
# reports' come last).
for _rule_file in registry.rule_files():

    include: f"workflow/rules/{_rule_file}"


# Every study's datasets, figures and further files, every report and the index page (registry).
rule all:
    input:
        ALL_TARGETS,
    default_target: True
    threads: 1
    resources:
        mem_mb=100,  # a target: its job runs nothing
        runtime=1,
