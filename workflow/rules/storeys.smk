# Contents on every floor of isolated buildings of N storeys (isoslide.studies.storeys, `storeys:` in
# the config): one job solves every scene into results/datasets/storeys.nc, one draws its figure; the
# findings are a section of reports/isolation.html (the `report` rule's).

import isoslide.studies.storeys as _storeys

STOREYS_SETTINGS = sweep.jsonable(_storeys.storeys_settings(config))
try:
    _storeys.check_settings(STOREYS_SETTINGS)
except ValueError as err:
    raise WorkflowError(f"Invalid configuration: {err}")


rule storeys_dataset:
    output:
        "results/datasets/storeys.nc",
    params:
        code=CODE["storeys"],
        settings=STOREYS_SETTINGS,
    log:
        "logs/storeys_dataset/storeys.log",
    benchmark:
        "results/benchmarks/storeys_dataset/storeys.tsv"
    threads: 1
    resources:
        mem_mb=600,  # measured: max_rss 257 MB
        runtime=2,  # minutes; measured: 5.3 s (default config, 528 scenes: 3.0 s solving), 8.6 s (test config, loaded)
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/storeys_dataset.py"


rule storeys_figure:
    input:
        "results/datasets/storeys.nc",
    output:
        expand("reports/figures/storeys.{ext}", ext=FORMATS),
    params:
        code=CODE["storeys_plot"],
        settings=FIGURE_SETTINGS,
    log:
        "logs/storeys_figure/storeys.log",
    benchmark:
        "results/benchmarks/storeys_figure/storeys.tsv"
    threads: 1
    resources:
        mem_mb=600,  # measured: max_rss 269 MB
        runtime=2,  # minutes; measured: 6.6 s (default config), 16.9 s (test config, 2 cores under load)
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/storeys_figure.py"
