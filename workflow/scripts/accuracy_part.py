"""Rule accuracy_part: one part of the speed-versus-accuracy measurement (isoslide.accuracy)."""

from isoslide.accuracy import measure_part
from isoslide.budget import phase
from isoslide.datasets import write_netcdf
from isoslide.store.provenance import log_to
from isoslide.solver import warm_up

with log_to(snakemake.log[0]) as log:
    cfg = snakemake.params.config
    log.info("measuring part %r with settings %s", snakemake.wildcards.part, cfg["accuracy"])
    with phase("compilation", log):
        warm_up()
    with phase("solving", log):
        ds = measure_part(snakemake.wildcards.part, cfg)
    with phase("writing", log):
        write_netcdf(ds, snakemake.output[0])
