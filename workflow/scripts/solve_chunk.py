"""Rule solve_chunk: solve chunk {chunk} of study {study} (isoslide.sweep.solve_chunk)."""

from isoslide.datasets import write_netcdf
from isoslide.provenance import log_to
from isoslide.sweep import solve_chunk

with log_to(snakemake.log[0]) as log:
    chunk = int(snakemake.wildcards.chunk)
    log.info("study %s, chunk %d", snakemake.wildcards.study, chunk)
    write_netcdf(solve_chunk(snakemake.params.spec, chunk), snakemake.output[0])
