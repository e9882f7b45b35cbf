# Every figure of the paper, from the datasets only (isoslide.figures).


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
        mem_mb=1000,
        runtime=10,
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/figure.py"
