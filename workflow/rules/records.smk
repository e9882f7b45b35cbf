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
