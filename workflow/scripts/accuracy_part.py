"""Rule accuracy_part: one part of the speed-versus-accuracy measurement (isoslide.accuracy)."""

from isoslide.accuracy import measure_part
from isoslide.datasets import write_netcdf
from isoslide.provenance import log_to

with log_to(snakemake.log[0]) as log:
    cfg = snakemake.params.config
    log.info("measuring part %r with settings %s", snakemake.wildcards.part, cfg["accuracy"])
    write_netcdf(measure_part(snakemake.wildcards.part, cfg), snakemake.output[0])
