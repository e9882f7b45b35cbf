# Similarity checks behind reports/similarity.html (isoslide.studies.similarity): each paper study's merge
# job writes its Buckingham realisations (workflow/rules/sweep.smk), then one job makes the
# tables, spreads and conclusions.


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
