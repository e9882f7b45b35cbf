"""Rule merge_study: chunks -> results/datasets/{study}.nc (isoslide.sweep.merge_chunk_files); a study
of one chunk is solved here (isoslide.sweep.solve_study)."""

from isoslide.budget import phase
from isoslide.datasets import write_netcdf
from isoslide.provenance import log_to
from isoslide.solver import warm_up
from isoslide.sweep import merge_chunk_files, solve_study

with log_to(snakemake.log[0]) as log:
    spec = snakemake.params.spec
    if snakemake.input:
        log.info("merging %d chunk files of study %s", len(snakemake.input), snakemake.wildcards.study)
        with phase("writing", log):
            ds = merge_chunk_files(snakemake.input, spec)
    else:
        log.info("study %s is one chunk: solved in this job", snakemake.wildcards.study)
        with phase("compilation", log):
            warm_up()
        with phase("solving", log):
            ds = solve_study(spec)
    with phase("writing", log):
        write_netcdf(ds, snakemake.output[0])
