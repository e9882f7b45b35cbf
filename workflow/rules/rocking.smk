# Contents that rock (isoslide.studies.rocking, `rocking:` in the config): one job solves the overturning
# spectra and the sliding-or-rocking map (pulses) and the overturning fragility (recorded ground
# motions), and writes the fragility's pelicun damage-model CSV; one job, because the three together
# cost less than a second job's start-up.  reports/rocking.html is the `report` rule's (its notebook
# draws the figures).

import isoslide.studies.rocking as _rocking

ROCKING_SETTINGS = sweep.jsonable(_rocking.rocking_settings(config))
try:
    _rocking.check_settings(ROCKING_SETTINGS)
except ValueError as err:
    raise WorkflowError(f"Invalid configuration: {err}")


rule rocking_datasets:
    output:
        spectra="results/datasets/rocking_spectra.nc",
        map="results/datasets/rocking_map.nc",
        fragility="results/datasets/rocking_fragility.nc",
        csv="results/rocking/pelicun_damage_db.csv",
        json="results/rocking/pelicun_damage_db.json",
    params:
        code=CODE["rocking"],
        settings=ROCKING_SETTINGS,
    log:
        "logs/rocking_datasets/rocking_datasets.log",
    benchmark:
        "results/benchmarks/rocking_datasets/rocking_datasets.tsv"
    threads: 1
    resources:
        mem_mb=800,  # measured: max_rss 352 MB
        runtime=2,  # minutes; measured: 7.7 s (default config, 2 cores; 7.3 s CPU: 2.0 s start-up, 1.1 s loading the
        #             kernels, 3.7 s solving), 9.8 s under a load of 2.8
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/rocking_datasets.py"
