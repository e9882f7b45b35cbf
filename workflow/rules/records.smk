# Real records against their fitted pulses (isoslide.studies.record_study): Fig. 4 from a real record, and
# peak sliding under each record and under its fitted pulse over a Pi2 x Pi3 grid (one job per
# record, then one dataset) and its figure; reports/records.html is the `report` rule's.


rule fig4_record:
    output:
        "results/datasets/fig4_record.nc",
    params:
        code=CODE["records"],
        settings=FIG4_SETTINGS,
    log:
        "logs/fig4_record/fig4_record.log",
    benchmark:
        "results/benchmarks/fig4_record/fig4_record.tsv"
    threads: 1
    resources:
        mem_mb=500,  # measured: max_rss 223 MB
        runtime=2,  # minutes; measured: 3.9 s
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/fig4_record.py"


rule record_compare:
    output:
        "results/records/{record}.nc",
    params:
        code=CODE["records"],
        settings=RECORDS_SETTINGS,
    log:
        "logs/record_compare/{record}.log",
    benchmark:
        "results/benchmarks/record_compare/{record}.tsv"
    threads: 1
    resources:
        mem_mb=600,  # measured: max_rss 273 MB over 4 jobs
        runtime=2,  # minutes; measured: 5.7 s at most
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/record_compare.py"


rule records_dataset:
    input:
        expand("results/records/{record}.nc", record=RECORDS),
    output:
        "results/datasets/records.nc",
    params:
        code=CODE["records"],
        settings=RECORDS_SETTINGS,
    log:
        "logs/records_dataset/records.log",
    benchmark:
        "results/benchmarks/records_dataset/records.tsv"
    threads: 1
    resources:
        mem_mb=500,  # measured: max_rss 223 MB
        runtime=2,  # minutes; measured: 3.4 s
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/records_dataset.py"


rule figure_records:
    input:
        records="results/datasets/records.nc",
    output:
        expand("reports/figures/records.{ext}", ext=FORMATS),
    params:
        code=CODE["figures"],
        settings=FIGURE_SETTINGS,
    log:
        "logs/figure_records/records.log",
    benchmark:
        "results/benchmarks/figure_records/records.tsv"
    threads: 1
    resources:
        mem_mb=600,  # measured: max_rss 285 MB
        runtime=2,  # minutes; measured: 8.5 s
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/figure_records.py"


# The recorded pairs (`records.pairs`): each horizontal component of a suite's pairs as recorded and as its
# fitted pulse on a line, and the pair as recorded and as the pair of fitted pulses in the plane; one job
# (the rule's settings are the `pairs` part only, so the rest of the record study leaves it alone).

import isoslide.studies.record_study as _record_study

RECORD_PAIRS_SETTINGS = sweep.jsonable(_record_study.pairs_settings(config))
try:
    _record_study.check_pairs_settings(RECORD_PAIRS_SETTINGS)
except ValueError as err:
    raise WorkflowError(f"Invalid configuration: {err}")


rule record_pairs:
    output:
        "results/datasets/record_pairs.nc",
    params:
        code=CODE["records"],
        settings=RECORD_PAIRS_SETTINGS,
    log:
        "logs/record_pairs/record_pairs.log",
    benchmark:
        "results/benchmarks/record_pairs/record_pairs.tsv"
    threads: 1
    resources:
        mem_mb=800,  # measured: max_rss 343 MB
        runtime=5,  # minutes; measured: 11.2-16.2 s under load (default slice: 4 pairs x 4 Pi2 x 2 Pi3, 7.0 s solving); the whole set (14 x 6 x 3) 28 s solving
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/record_pairs.py"


rule record_pairs_figure:
    input:
        record_pairs="results/datasets/record_pairs.nc",
    output:
        expand("reports/figures/record_pairs.{ext}", ext=FORMATS),
    params:
        code=CODE["record_pairs_plot"],
        settings=FIGURE_SETTINGS,
    log:
        "logs/record_pairs_figure/record_pairs.log",
    benchmark:
        "results/benchmarks/record_pairs_figure/record_pairs.tsv"
    threads: 1
    resources:
        mem_mb=600,  # measured: max_rss 268 MB
        runtime=2,  # minutes; measured: 9.5 s (two formats) under load
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/record_pairs_figure.py"
