"""Rule storeys_dataset: contents on every floor of isolated buildings of N storeys
(isoslide.studies.storeys.storeys_dataset)."""

from isoslide.datasets import solve_and_write
from isoslide.store.provenance import log_to
from isoslide.solver import warm_up
from isoslide.studies.storeys import storeys_dataset

with log_to(snakemake.log[0]) as log:
    solve_and_write(snakemake.output[0], log, lambda: warm_up(building=True),
                    lambda: storeys_dataset(snakemake.params.settings))
