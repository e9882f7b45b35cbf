"""Rule fragility_planar_chunk: analyses of chunk {chunk} of {pfrag} (isoslide.studies.fragility_planar.solve_chunk)."""

from isoslide.budget import phase
from isoslide.datasets import write_netcdf
from isoslide.studies.fragility_planar import base_of, check_settings, solve_chunk
from isoslide.store.provenance import log_to
from isoslide.solver import warm_up

with log_to(snakemake.log[0]) as log:
    chunk = int(snakemake.wildcards.chunk)
    base = base_of(snakemake.wildcards.pfrag)
    study = check_settings(snakemake.params.settings)
    log.info("%s, chunk %d (%s base)", snakemake.wildcards.pfrag, chunk, base)
    with phase("compilation", log):
        warm_up(records=True)
    with phase("solving", log):
        ds = solve_chunk(study, chunk, base)
    log.info("%d analyses (each a planar and two 1-D solves)", ds.sizes["analysis"])
    with phase("writing", log):
        write_netcdf(ds, snakemake.output[0])
