"""Rule fragility_planar_chunk: analyses of chunk {chunk} of {pfrag} (isoslide.studies.fragility_planar.solve_chunk)."""

from isoslide.budget import phase
from isoslide.datasets import write_netcdf
from isoslide.studies import fragility_planar
from isoslide.studies.fragility_study import chunk_job
from isoslide.store.provenance import log_to

with log_to(snakemake.log[0]) as log:
    ds = chunk_job(fragility_planar, snakemake.wildcards.pfrag, int(snakemake.wildcards.chunk),
                   snakemake.params.settings, log)
    log.info("%d analyses (each a planar and two 1-D solves)", ds.sizes["analysis"])
    with phase("writing", log):
        write_netcdf(ds, snakemake.output[0])
