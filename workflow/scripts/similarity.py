"""Rule similarity: tables, complete-similarity spreads and conclusions (isoslide.studies.similarity)."""

from isoslide.budget import phase
from isoslide.datasets import write_netcdf
from isoslide.store.provenance import log_to
from isoslide.studies.similarity import similarity_dataset

with log_to(snakemake.log[0]) as log:
    with phase("solving", log):
        ds = similarity_dataset(snakemake.input.checks, snakemake.input.datasets, snakemake.params.settings)
    with phase("writing", log):
        write_netcdf(ds, snakemake.output[0])
