"""Rule storeys_dataset: contents on every floor of isolated buildings of N storeys
(isoslide.studies.storeys.storeys_dataset)."""

from isoslide.budget import compile_and_solve, phase
from isoslide.datasets import write_netcdf
from isoslide.store.provenance import log_to
from isoslide.solver import warm_up
from isoslide.studies.storeys import storeys_dataset

with log_to(snakemake.log[0]) as log:
    ds = compile_and_solve(log, lambda: warm_up(building=True),
                           lambda: storeys_dataset(snakemake.params.settings))
    log.info("%s", ds)
    with phase("writing", log):
        write_netcdf(ds, snakemake.output[0])
