"""Rule solve_chunk: solve chunk {chunk} of study {study} (isoslide.studies.sweep.solve_chunk)."""

from isoslide.budget import compile_and_solve, phase
from isoslide.datasets import write_netcdf
from isoslide.store.provenance import log_to
from isoslide.solver import warm_up
from isoslide.studies.sweep import solve_chunk

with log_to(snakemake.log[0]) as log:
    chunk = int(snakemake.wildcards.chunk)
    log.info("study %s, chunk %d", snakemake.wildcards.study, chunk)
    ds = compile_and_solve(log, warm_up, lambda: solve_chunk(snakemake.params.spec, chunk))
    with phase("writing", log):
        write_netcdf(ds, snakemake.output[0])
