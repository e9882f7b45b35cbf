# The fragility study (isoslide.studies.fragility_study, `fragility:` in the config): records x stripes x
# friction draws cut into chunks of `fragility.chunk_size` analyses, solved one job per chunk,
# merged and fitted into results/datasets/fragility.nc (isolated slab) and, with
# `building.fixed_base`, results/datasets/fragility_fixed_base.nc (the same contents on a fixed
# base); a dataset of one chunk is solved by its fragility_dataset job (one job instead of two).
# Then the pelicun damage-model CSV, the figure and reports/fragility.html (rule report).
# In the plane (`fragility.planar`, isoslide.studies.fragility_planar): the same fan-out for
# results/datasets/fragility_planar.nc (and fragility_planar_fixed_base.nc), each analysis one
# planar and two 1-D solves, read by reports/fragility.html.


rule fragility_chunk:
    input:
        FRAGILITY_RECORD_FILES,
    output:
        "results/chunks/{frag}/{chunk}.nc",
    params:
        code=CODE["fragility"],
        settings=FRAGILITY_SETTINGS,
    log:
        "logs/fragility_chunk/{frag}/{chunk}.log",
    benchmark:
        "results/benchmarks/fragility_chunk/{frag}/{chunk}.tsv"
    threads: 1
    resources:
        mem_mb=600,  # measured: max_rss 287 MB (a 2,500-analysis chunk of config/fragility_large.yaml)
        runtime=5,  # minutes; measured: 6.1 s for 2,500 analyses (fragility_large.yaml), 9.6 s at most (test config)
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/fragility_chunk.py"


rule fragility_dataset:
    input:
        records=FRAGILITY_RECORD_FILES,
        chunks=fragility_chunk_files,
    output:
        "results/datasets/{frag}.nc",
    params:
        code=CODE["fragility"],
        settings=FRAGILITY_SETTINGS,
    log:
        "logs/fragility_dataset/{frag}.log",
    benchmark:
        "results/benchmarks/fragility_dataset/{frag}.tsv"
    threads: 1
    resources:
        mem_mb=800,  # measured: max_rss 323 MB (fragility_large.yaml, 112,500 analyses), 287 MB (default)
        runtime=30,  # minutes; measured: 281 s at most (fragility_large.yaml, one base), 6.8 s (default)
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/fragility_dataset.py"


rule fragility_pelicun:
    input:
        "results/datasets/fragility.nc",
    output:
        csv="results/fragility/pelicun_damage_db.csv",
        json="results/fragility/pelicun_damage_db.json",
    params:
        code=CODE["pelicun"],
    log:
        "logs/fragility_pelicun/pelicun.log",
    benchmark:
        "results/benchmarks/fragility_pelicun/pelicun.tsv"
    threads: 1
    resources:
        mem_mb=400,  # measured: max_rss 198 MB
        runtime=2,  # minutes; measured: 2.6 s
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/fragility_pelicun.py"


rule fragility_figure:
    input:
        **FRAGILITY_FIGURE_INPUT,
    output:
        FRAGILITY_FIGURE_FILES,
    params:
        code=CODE["fragility_plot"],
        dpi=config["figures"]["dpi"],
    log:
        "logs/fragility_figure/fragility.log",
    benchmark:
        "results/benchmarks/fragility_figure/fragility.tsv"
    threads: 1
    resources:
        mem_mb=600,  # measured: max_rss 208 MB at most
        runtime=2,  # minutes; measured: 4.5 s at most
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/fragility_figure.py"


rule fragility_planar_chunk:
    input:
        PLANAR_FRAGILITY_SUITE_FILES,
    output:
        "results/chunks/{pfrag}/{chunk}.nc",
    params:
        code=CODE["fragility_planar"],
        settings=PLANAR_FRAGILITY_SETTINGS,
    wildcard_constraints:
        pfrag="|".join(PLANAR_FRAGILITY_DATASETS) or "no_planar_dataset",
    log:
        "logs/fragility_planar_chunk/{pfrag}/{chunk}.log",
    benchmark:
        "results/benchmarks/fragility_planar_chunk/{pfrag}/{chunk}.tsv"
    threads: 1
    resources:
        mem_mb=800,  # measured: max_rss 332 MB (a 500-analysis chunk of config/fragility_p695.yaml)
        runtime=30,  # minutes; measured: 28.8 s / 32.4 s for chunk 0 of fragility_p695.yaml (isolated / fixed base); 95 / 233 ms per analysis over its table, 2 min for 500
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/fragility_planar_chunk.py"


rule fragility_planar_dataset:
    input:
        suites=PLANAR_FRAGILITY_SUITE_FILES,
        chunks=planar_fragility_chunk_files,
    output:
        "results/datasets/{pfrag}.nc",
    params:
        code=CODE["fragility_planar"],
        settings=PLANAR_FRAGILITY_SETTINGS,
    wildcard_constraints:
        pfrag="|".join(PLANAR_FRAGILITY_DATASETS) or "no_planar_dataset",
    log:
        "logs/fragility_planar_dataset/{pfrag}.log",
    benchmark:
        "results/benchmarks/fragility_planar_dataset/{pfrag}.tsv"
    threads: 1
    resources:
        mem_mb=1000,  # measured: max_rss 426 MB (default config: 96 analyses solved and fitted in this job)
        runtime=30,  # minutes; measured: 29.7 s at most (default config, 2 busy cores); fragility_p695.yaml: see docs/guide/fragility.rst
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/fragility_planar_dataset.py"
