"""Rule accuracy_part: one part of the speed-versus-accuracy measurement (isoslide.accuracy)."""

from isoslide.accuracy import measure_part
from isoslide.budget import compile_and_solve, phase
from isoslide.datasets import write_netcdf
from isoslide.store.provenance import log_to
from isoslide.solver import warm_up

with log_to(snakemake.log[0]) as log:
    cfg = snakemake.params.config
    log.info("measuring part %r with settings %s", snakemake.wildcards.part, cfg["accuracy"])
    ds = compile_and_solve(log, warm_up, lambda: measure_part(snakemake.wildcards.part, cfg))
    with phase("writing", log):
        write_netcdf(ds, snakemake.output[0])
