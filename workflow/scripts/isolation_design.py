"""Rule isolation_design: linear, bilinear and friction-pendulum isolation of equal effective period
and damping, compared on pulses and records (isoslide.studies.isolation_study.design_dataset)."""

from isoslide.budget import compile_solve_write
from isoslide.datasets import write_netcdf
from isoslide.studies.isolation_study import design_dataset
from isoslide.store.provenance import log_to
from isoslide.solver import warm_up

with log_to(snakemake.log[0]) as log:
    compile_solve_write(log, lambda: warm_up(records=True, building=True),
                        lambda: design_dataset(snakemake.params.settings),
                        lambda ds: write_netcdf(ds, snakemake.output[0]))
