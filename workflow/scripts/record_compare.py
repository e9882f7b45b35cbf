"""Rule record_compare: one record against its fitted pulse on the Pi2 x Pi3 grid (isoslide.studies.record_study)."""

from isoslide.budget import compile_solve_write
from isoslide.datasets import write_netcdf
from isoslide.store.provenance import log_to
from isoslide.solver import warm_up
from isoslide.studies.record_study import record_dataset

with log_to(snakemake.log[0]) as log:
    compile_solve_write(log, lambda: warm_up(records=True),
                        lambda: record_dataset(snakemake.wildcards.record, snakemake.params.settings),
                        lambda ds: write_netcdf(ds, snakemake.output[0]))
