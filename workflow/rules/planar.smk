# Contents sliding in the plane (isoslide.studies.planar, `planar:` in the config): one job solves
# every scene into results/datasets/planar.nc and planar_pi5.nc, one draws the figures; the findings
# are reports/planar.html (the `report` rule's).

import isoslide.studies.planar as _planar

PLANAR_SETTINGS = sweep.jsonable(_planar.planar_settings(config))
try:
    _planar.check_settings(PLANAR_SETTINGS)
except ValueError as err:
    raise WorkflowError(f"Invalid configuration: {err}")
PLANAR_FIGURE_FILES = expand("reports/figures/{fig}.{ext}", fig=list(registry.PLANAR_FIGURES), ext=FORMATS)


rule planar_dataset:
    output:
        planar="results/datasets/planar.nc",
        planar_pi5="results/datasets/planar_pi5.nc",
    params:
        code=CODE["planar"],
        settings=PLANAR_SETTINGS,
    log:
        "logs/planar_dataset/planar.log",
    benchmark:
        "results/benchmarks/planar_dataset/planar.tsv"
    threads: 1
    resources:
        mem_mb=600,  # measured: max_rss 264 MB
        runtime=2,  # minutes; measured: 2.8 s (default config: 576 + 216 scenes, 288 1-D ones, 1.1 s solving), 5.3 s under load
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/planar_dataset.py"


rule planar_figure:
    input:
        planar="results/datasets/planar.nc",
        planar_pi5="results/datasets/planar_pi5.nc",
    output:
        PLANAR_FIGURE_FILES,
    params:
        code=CODE["planar_plot"],
        settings=FIGURE_SETTINGS,
    log:
        "logs/planar_figure/planar.log",
    benchmark:
        "results/benchmarks/planar_figure/planar.tsv"
    threads: 1
    resources:
        mem_mb=600,  # measured: max_rss 273 MB
        runtime=2,  # minutes; measured: 5.6 s (default config, four figures in two formats), 10.4 s under load
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/planar_figure.py"
