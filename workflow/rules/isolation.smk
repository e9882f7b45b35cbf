# Buildings as engineers isolate them (isoslide.studies.isolation_study, `isolation:` in the config).  The
# master curves of real bearings and of a flexible superstructure (studies iso_fp, iso_lrb,
# iso_flex_base, iso_flex_roof) are ordinary studies: solved and merged by the rules of sweep.smk.
# Here: where the rigid-superstructure reduction holds, the comparison of isolation systems of equal
# effective period and damping, those bearings over the pulse's intensity (a friction pendulum with
# friction rising with speed and a triple friction pendulum among them), their figures;
# reports/isolation.html is the `report` rule's.


rule isolation_rigid:
    input:
        base="results/datasets/iso_flex_base.nc",
        roof="results/datasets/iso_flex_roof.nc",
    output:
        "results/datasets/isolation_rigid.nc",
    params:
        code=CODE["isolation"],
        settings=ISOLATION_RIGID_SETTINGS,
    log:
        "logs/isolation_rigid/isolation_rigid.log",
    benchmark:
        "results/benchmarks/isolation_rigid/isolation_rigid.tsv"
    threads: 1
    resources:
        mem_mb=500,  # measured: max_rss 236 MB
        runtime=2,  # minutes; measured: 4.1 s (default config, 2 cores under load)
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/isolation_rigid.py"


rule isolation_design:
    input:
        ISOLATION_RECORD_FILES,
    output:
        "results/datasets/isolation_design.nc",
    params:
        code=CODE["isolation"],
        settings=ISOLATION_DESIGN_SETTINGS,
    log:
        "logs/isolation_design/isolation_design.log",
    benchmark:
        "results/benchmarks/isolation_design/isolation_design.tsv"
    threads: 1
    resources:
        mem_mb=700,  # measured: max_rss 351 MB
        runtime=4,  # minutes; measured: 21.1 s (default config with 10 mu_k, 2 cores under load), 12.4 s with 7
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/isolation_design.py"


rule isolation_bearings:
    output:
        "results/datasets/isolation_bearings.nc",
    params:
        code=CODE["isolation"],
        settings=ISOLATION_BEARINGS_SETTINGS,
    log:
        "logs/isolation_bearings/isolation_bearings.log",
    benchmark:
        "results/benchmarks/isolation_bearings/isolation_bearings.tsv"
    threads: 1
    resources:
        mem_mb=700,  # measured: max_rss 306 MB (403 MB compiling the kernel)
        runtime=2,  # minutes; measured: 11.7-15.5 s with the triple pendulum (default config, 2 cores, load 4.4;
        #             solving 3.0-4.0 s of it), 8.4-16.3 s without it (solving 2.0-3.8 s); compiling a kernel the
        #             cache lacks adds about 2.5 min
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/isolation_bearings.py"


rule isolation_figure:
    input:
        **ISOLATION_FIGURE_INPUT,
    output:
        ISOLATION_FIGURE_FILES,
    params:
        code=CODE["isolation_plot"],
        settings=FIGURE_SETTINGS,
    log:
        "logs/isolation_figure/isolation_figure.log",
    benchmark:
        "results/benchmarks/isolation_figure/isolation_figure.tsv"
    threads: 1
    resources:
        mem_mb=600,  # measured: max_rss 296 MB
        runtime=6,  # minutes; measured: 31.2 s drawing, 11.0 s of it the bearing study's figure (default config, 2 cores, load 3);
        #             that figure with the triple pendulum 9-14 s, 6-8 s without it (load 3.5)
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/isolation_figure.py"
