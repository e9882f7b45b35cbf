"""Rule record_pairs: recorded pairs against their fitted pulses, on a line and in the plane
(isoslide.studies.record_study.record_pairs_dataset)."""

from isoslide.budget import compile_solve_write
from isoslide.datasets import write_netcdf
from isoslide.store.provenance import log_to
from isoslide.solver import warm_up
from isoslide.studies.record_study import record_pairs_dataset

with log_to(snakemake.log[0]) as log:
    compile_solve_write(log, lambda: warm_up(records=True, building=True),
                        lambda: record_pairs_dataset(snakemake.params.settings),
                        lambda ds: write_netcdf(ds, snakemake.output[0]))
