"""Rule fig4_record: the real record of Fig. 4 with its fitted pulses (isoslide.studies.record_study)."""

from isoslide.datasets import solve_and_write
from isoslide.store.provenance import log_to
from isoslide.solver import warm_up
from isoslide.studies.record_study import fig4_dataset

with log_to(snakemake.log[0]) as log:
    solve_and_write(snakemake.output[0], log, lambda: warm_up(records=True),
                    lambda: fig4_dataset(snakemake.params.settings))
