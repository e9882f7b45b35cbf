"""Rule fragility_planar_dataset: chunks -> results/datasets/{pfrag}.nc with the fitted curves and the
comparisons (isoslide.studies.fragility_planar); a dataset of one chunk is solved here."""

from isoslide.budget import phase
from isoslide.datasets import open_dataset, write_netcdf
from isoslide.studies.fragility_planar import base_of, check_settings, merge_chunks, planar_dataset, solve_all
from isoslide.store.provenance import log_to
from isoslide.solver import warm_up

with log_to(snakemake.log[0]) as log:
    settings = snakemake.params.settings
    base = base_of(snakemake.wildcards.pfrag)
    study = check_settings(settings)
    if snakemake.input.chunks:
        log.info("merging %d chunk files of %s", len(snakemake.input.chunks), snakemake.wildcards.pfrag)
        with phase("writing", log):
            analyses = merge_chunks([open_dataset(p) for p in snakemake.input.chunks])
    else:
        log.info("%s is one chunk (%d analyses): solved in this job", snakemake.wildcards.pfrag, study.size)
        with phase("compilation", log):
            warm_up(records=True)
        with phase("solving", log):
            analyses = solve_all(study, base)
    with phase("solving", log):  # maximum-likelihood fits and the bootstrap
        ds = planar_dataset(analyses, study, settings, base)
    with phase("writing", log):
        write_netcdf(ds, snakemake.output[0])
