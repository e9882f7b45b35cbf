# Similarity checks behind reports/similarity.html (isoslide.similarity): one job per study for
# the Buckingham realisations, then one job for the tables, spreads and conclusions.


rule similarity_study:
    input:
        "results/datasets/{study}.nc",
    output:
        "results/similarity/{study}.nc",
    params:
        code=SIMILARITY_CODE,
        settings=SIMILARITY_SETTINGS,
        spec=lambda wildcards: SPECS[wildcards.study],
    conda:
        "../envs/isoslide.yaml"
    log:
        "logs/similarity_study/{study}.log",
    script:
        "../scripts/similarity_study.py"


rule similarity:
    input:
        checks=expand("results/similarity/{study}.nc", study=STUDIES),
        datasets=DATASETS,
    output:
        "results/datasets/similarity.nc",
    params:
        code=SIMILARITY_CODE,
        settings=SIMILARITY_SETTINGS,
    conda:
        "../envs/isoslide.yaml"
    log:
        "logs/similarity/similarity.log",
    script:
        "../scripts/similarity.py"
