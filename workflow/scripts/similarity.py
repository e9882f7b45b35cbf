"""Rule similarity: tables, complete-similarity spreads and conclusions (isoslide.similarity)."""

from isoslide.datasets import logging_to, write_netcdf
from isoslide.similarity import similarity_dataset

with logging_to(snakemake.log[0]):  # noqa: F821 - injected by Snakemake
    ds = similarity_dataset(snakemake.input.checks, snakemake.input.datasets, snakemake.params.settings)
    write_netcdf(ds, snakemake.output[0])
