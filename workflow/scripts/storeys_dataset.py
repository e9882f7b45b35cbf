"""Rule storeys_dataset: contents on every floor of isolated buildings of N storeys
(isoslide.studies.storeys.storeys_dataset)."""

from isoslide.budget import compile_solve_write
from isoslide.datasets import write_netcdf
from isoslide.store.provenance import log_to
from isoslide.solver import warm_up
from isoslide.studies.storeys import storeys_dataset

with log_to(snakemake.log[0]) as log:
    compile_solve_write(log, lambda: warm_up(building=True),
                        lambda: storeys_dataset(snakemake.params.settings),
                        lambda ds: write_netcdf(ds, snakemake.output[0]))
