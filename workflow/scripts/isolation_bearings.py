"""Rule isolation_bearings: a lead-rubber bearing, friction pendulums of constant and speed-dependent
friction and a triple friction pendulum, designed alike, over a pulse's intensity
(isoslide.studies.isolation_study.bearings_dataset)."""

from isoslide.budget import compile_solve_write
from isoslide.datasets import write_netcdf
from isoslide.studies.isolation_study import bearings_dataset
from isoslide.store.provenance import log_to
from isoslide.solver import warm_up

with log_to(snakemake.log[0]) as log:
    compile_solve_write(log, lambda: warm_up(building=True),
                        lambda: bearings_dataset(snakemake.params.settings),
                        lambda ds: write_netcdf(ds, snakemake.output[0]))
