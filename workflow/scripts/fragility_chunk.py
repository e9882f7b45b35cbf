"""Rule fragility_chunk: analyses of chunk {chunk} of {frag} (isoslide.studies.fragility_study.solve_chunk)."""

from isoslide.budget import phase
from isoslide.datasets import write_netcdf
from isoslide.studies import fragility_study
from isoslide.store.provenance import log_to

with log_to(snakemake.log[0]) as log:
    ds = fragility_study.chunk_job(fragility_study, snakemake.wildcards.frag, int(snakemake.wildcards.chunk),
                                   snakemake.params.settings, log)
    log.info("%d analyses", ds.sizes["analysis"])
    with phase("writing", log):
        write_netcdf(ds, snakemake.output[0])
