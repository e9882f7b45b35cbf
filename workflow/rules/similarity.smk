# Similarity checks behind reports/similarity.html (isoslide.similarity): one job per study for
# the Buckingham realisations, then one job for the tables, spreads and conclusions.


rule similarity_study:
    input:
        "results/datasets/{study}.nc",
    output:
        "results/similarity/{study}.nc",
    params:
        code=CODE["similarity"],
        settings=SIMILARITY_SETTINGS,
        spec=lambda wildcards: SPECS[wildcards.study],
    log:
        "logs/similarity_study/{study}.log",
    benchmark:
        "results/benchmarks/similarity_study/{study}.tsv"
    threads: 1
    resources:
        mem_mb=500,  # measured: max_rss 242 MB over 7 jobs
        runtime=2,  # minutes; measured: 5.8 s at most
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/similarity_study.py"


rule similarity:
    input:
        checks=expand("results/similarity/{study}.nc", study=STUDIES),
        datasets=DATASETS,
    output:
        "results/datasets/similarity.nc",
    params:
        code=CODE["similarity"],
        settings=SIMILARITY_SETTINGS,
    log:
        "logs/similarity/similarity.log",
    benchmark:
        "results/benchmarks/similarity/similarity.tsv"
    threads: 1
    resources:
        mem_mb=500,  # measured: max_rss 200 MB
        runtime=2,  # minutes; measured: 2.9 s
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/similarity.py"
