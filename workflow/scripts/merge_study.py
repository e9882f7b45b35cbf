"""Rule merge_study: chunks -> results/datasets/{study}.nc (isoslide.studies.sweep.merge_chunk_files; a study
of one chunk is solved here, isoslide.studies.sweep.solve_study), then its Buckingham check ->
results/similarity/{study}.nc (isoslide.studies.similarity.buckingham_study)."""

from isoslide.budget import phase
from isoslide.datasets import write_netcdf
from isoslide.store.provenance import log_to
from isoslide.studies.similarity import buckingham_study
from isoslide.studies.sweep import study_dataset

with log_to(snakemake.log[0]) as log:
    ds = study_dataset(snakemake.input, snakemake.params.spec, log)
    with phase("writing", log):
        write_netcdf(ds, snakemake.output.dataset)
    with phase("solving", log):
        check = buckingham_study(ds, snakemake.params.buckingham)
    with phase("writing", log):
        write_netcdf(check, snakemake.output.similarity)
