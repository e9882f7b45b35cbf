# Every figure of the paper, from the datasets only (isoslide.reports.figures).


rule figure:
    input:
        unpack(figure_datasets),
    output:
        expand("reports/figures/{{fig}}.{ext}", ext=FORMATS),
    params:
        code=CODE["figures"],
        settings=FIGURE_SETTINGS,
    log:
        "logs/figure/{fig}.log",
    benchmark:
        "results/benchmarks/figure/{fig}.tsv"
    threads: 1
    resources:
        mem_mb=600,  # measured: max_rss 276 MB over 8 jobs
        runtime=2,  # minutes; measured: 7.9 s at most
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/figure.py"
