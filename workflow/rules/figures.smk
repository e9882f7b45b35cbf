# Every figure of the paper, from the datasets only (isoslide.figures).


rule figure:
    input:
        unpack(figure_datasets),
    output:
        expand("reports/figures/{{fig}}.{ext}", ext=FORMATS),
    params:
        code=FIGURE_CODE,
        settings=FIGURE_SETTINGS,
    conda:
        "../envs/isoslide.yaml"
    log:
        "logs/figure/{fig}.log",
    script:
        "../scripts/figure.py"
