"""Rule merge_study: chunks -> results/datasets/{study}.nc (isoslide.sweep.merge_chunk_files)."""

from isoslide.budget import phase
from isoslide.datasets import write_netcdf
from isoslide.provenance import log_to
from isoslide.sweep import merge_chunk_files

with log_to(snakemake.log[0]) as log:
    log.info("merging %d chunk files of study %s", len(snakemake.input), snakemake.wildcards.study)
    with phase("writing", log):
        write_netcdf(merge_chunk_files(snakemake.input, snakemake.params.spec), snakemake.output[0])
