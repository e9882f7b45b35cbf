"""Rule fig4_record: the real record of Fig. 4 with its fitted pulses (isoslide.studies.record_study)."""

from isoslide.budget import compile_solve_write
from isoslide.datasets import write_netcdf
from isoslide.store.provenance import log_to
from isoslide.solver import warm_up
from isoslide.studies.record_study import fig4_dataset

with log_to(snakemake.log[0]) as log:
    compile_solve_write(log, lambda: warm_up(records=True),
                        lambda: fig4_dataset(snakemake.params.settings),
                        lambda ds: write_netcdf(ds, snakemake.output[0]))
