"""Rule similarity: tables, complete-similarity spreads and conclusions (isoslide.similarity)."""

from isoslide.datasets import write_netcdf
from isoslide.provenance import log_to
from isoslide.similarity import similarity_dataset

with log_to(snakemake.log[0]):
    ds = similarity_dataset(snakemake.input.checks, snakemake.input.datasets, snakemake.params.settings)
    write_netcdf(ds, snakemake.output[0])
