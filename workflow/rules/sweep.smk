# Fan-out and merge: each study is cut into chunks of `chunk_size` scenes, solved one job per
# chunk, and merged with an exact coordinate join into results/datasets/<study>.nc.  A study of
# one chunk is solved by its merge job directly (same bytes, one job instead of two).  The merge
# job of a paper study also realises sampled points in SI units (the Buckingham check of
# reports/similarity.html), reading the dataset it has just written from memory.


rule solve_chunk:
    output:
        "results/chunks/{study}/{chunk}.nc",
    params:
        code=CODE["solve"],
        # the study's full specification: editing one study reruns only its chunks
        spec=lambda wildcards: STUDY_SPECS[wildcards.study],
    log:
        "logs/solve_chunk/{study}/{chunk}.log",
    benchmark:
        "results/benchmarks/solve_chunk/{study}/{chunk}.tsv"
    threads: 1
    resources:
        mem_mb=500,  # measured: max_rss 246 MB over 10 jobs
        runtime=2,  # minutes; measured: 5.3 s at most (median 3.6 s)
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/solve_chunk.py"


rule merge_study:
    input:
        chunk_files,
    output:
        dataset="results/datasets/{study}.nc",
        similarity="results/similarity/{study}.nc",
    params:
        code=CODE["study"],
        spec=lambda wildcards: SPECS[wildcards.study],
        # only the settings the Buckingham check reads: editing the similarity tables' settings
        # reruns the similarity job, not the studies
        buckingham=BUCKINGHAM_SETTINGS,
    wildcard_constraints:
        study="|".join(STUDIES),
    log:
        "logs/merge_study/{study}.log",
    benchmark:
        "results/benchmarks/merge_study/{study}.tsv"
    threads: 1
    resources:
        mem_mb=500,  # measured: max_rss 248 MB over 7 jobs
        runtime=2,  # minutes; measured: 5.0 s at most (fig5_pi4: solving and its check)
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/merge_study.py"


# The isolation studies (workflow/rules/isolation.smk): merged or solved the same way; their
# similarity is checked by the tests (the SI-unit peer of the general building).
rule merge_isolation_study:
    input:
        chunk_files,
    output:
        "results/datasets/{study}.nc",
    params:
        code=CODE["solve"],
        spec=lambda wildcards: ISOLATION_SPECS[wildcards.study],
    wildcard_constraints:
        study="|".join(ISOLATION_STUDIES),
    log:
        "logs/merge_isolation_study/{study}.log",
    benchmark:
        "results/benchmarks/merge_isolation_study/{study}.tsv"
    threads: 1
    resources:
        mem_mb=500,  # measured: max_rss 248 MB over 4 jobs
        runtime=2,  # minutes; measured: 2.7 s at most
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/merge_isolation_study.py"
