"""Rule solve_chunk: solve chunk {chunk} of study {study} (isoslide.sweep.solve_chunk)."""

from isoslide.datasets import logging_to, write_netcdf
from isoslide.sweep import solve_chunk

with logging_to(snakemake.log[0]):  # noqa: F821 - injected by Snakemake
    write_netcdf(solve_chunk(snakemake.params.spec, int(snakemake.wildcards.chunk)), snakemake.output[0])
