"""Rule merge_study: chunks -> results/datasets/{study}.nc (isoslide.sweep.merge_chunk_files)."""

from isoslide.datasets import logging_to, write_netcdf
from isoslide.sweep import merge_chunk_files

with logging_to(snakemake.log[0]):  # noqa: F821 - injected by Snakemake
    ds = merge_chunk_files(snakemake.input, snakemake.params.spec)
    write_netcdf(ds, snakemake.output[0])
