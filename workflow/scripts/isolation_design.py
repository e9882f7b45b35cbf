"""Rule isolation_design: linear, bilinear and friction-pendulum isolation of equal effective period
and damping, compared on pulses and records (isoslide.studies.isolation_study.design_dataset)."""

from isoslide.datasets import solve_and_write
from isoslide.studies.isolation_study import design_dataset
from isoslide.store.provenance import log_to
from isoslide.solver import warm_up

with log_to(snakemake.log[0]) as log:
    solve_and_write(snakemake.output[0], log, lambda: warm_up(records=True, building=True),
                    lambda: design_dataset(snakemake.params.settings))
