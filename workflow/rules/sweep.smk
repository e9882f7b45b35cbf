# Fan-out and merge: each study is cut into chunks of `chunk_size` scenes, solved one job per
# chunk, and merged with an exact coordinate join into results/datasets/<study>.nc.


rule solve_chunk:
    output:
        "results/chunks/{study}/{chunk}.nc",
    params:
        code=SOLVER_CODE,
        # the study's full specification: editing one study reruns only its chunks
        spec=lambda wildcards: SPECS[wildcards.study],
    conda:
        "../envs/isoslide.yaml"
    log:
        "logs/solve_chunk/{study}/{chunk}.log",
    threads: 1
    script:
        "../scripts/solve_chunk.py"


rule merge_study:
    input:
        chunk_files,
    output:
        "results/datasets/{study}.nc",
    params:
        code=SOLVER_CODE,
        spec=lambda wildcards: SPECS[wildcards.study],
    conda:
        "../envs/isoslide.yaml"
    log:
        "logs/merge_study/{study}.log",
    script:
        "../scripts/merge_study.py"
