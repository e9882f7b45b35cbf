"""Rule merge_isolation_study: chunks -> results/datasets/{study}.nc for an isolation study
(isoslide.studies.sweep.merge_chunk_files); a study of one chunk is solved here (isoslide.studies.sweep.solve_study)."""

from isoslide.budget import phase
from isoslide.datasets import write_netcdf
from isoslide.store.provenance import log_to
from isoslide.studies.sweep import study_dataset

with log_to(snakemake.log[0]) as log:
    ds = study_dataset(snakemake.input, snakemake.params.spec, log)
    with phase("writing", log):
        write_netcdf(ds, snakemake.output[0])
