# Speed versus accuracy (isoslide.accuracy): results/datasets/accuracy.nc (deterministic: same config,
# same bytes) and its wall-clock costs apart in results/timings/accuracy_timings.nc;
# reports/accuracy.html is the `report` rule's.
#
#   snakemake --cores 2 accuracy
#
# Self-contained: the settings come from the config's `accuracy:` section (completed by the
# schema); the scene set is drawn from the paper's studies as the package ships them (plus the hard
# scenes), so editing a study of the config reruns that study's jobs only.  Independent
# measurement jobs (one per part, so two cores run them side by side) are combined into the
# dataset; the report notebook only reads it.

import isoslide.accuracy as _accuracy

ACCURACY_PARTS = list(_accuracy.PARTS)
# what the measurement depends on: the accuracy settings only (the scenes come from the package)
ACCURACY_CONFIG = sweep.jsonable({"accuracy": _accuracy.settings_from(config.get("accuracy", {}))})


rule accuracy_part:
    output:
        "results/accuracy/{part}.nc",
    params:
        config=ACCURACY_CONFIG,
        code=CODE["accuracy"],
    wildcard_constraints:
        part="|".join(ACCURACY_PARTS),
    log:
        "logs/accuracy_part/{part}.log",
    benchmark:
        "results/benchmarks/accuracy_part/{part}.tsv"
    priority: 10  # the longest jobs of a run, and they need no other job: start them first
    threads: 1
    resources:
        mem_mb=600,  # measured: max_rss 250 MB over 4 jobs
        runtime=5,  # minutes; measured: 49.4 s at most (regularized; 30.9 s alone)
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/accuracy_part.py"


rule accuracy_dataset:
    input:
        expand("results/accuracy/{part}.nc", part=ACCURACY_PARTS),
    output:
        results="results/datasets/accuracy.nc",
        timings="results/timings/accuracy_timings.nc",
    params:
        config=ACCURACY_CONFIG,
        code=CODE["accuracy"],
    log:
        "logs/accuracy_dataset/accuracy.log",
    benchmark:
        "results/benchmarks/accuracy_dataset/accuracy.tsv"
    threads: 1
    resources:
        mem_mb=500,  # measured: max_rss 204 MB
        runtime=2,  # minutes; measured: 3.3 s
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/accuracy_dataset.py"


rule accuracy:
    input:
        "results/datasets/accuracy.nc",
        "results/timings/accuracy_timings.nc",
        "reports/accuracy.html",
    threads: 1
    resources:
        mem_mb=100,  # a target: its job runs nothing
        runtime=1,
