"""Rule fragility_dataset: chunks -> results/datasets/{frag}.nc with the fitted curves
(isoslide.studies.fragility_study); a study of one chunk is solved here."""

from isoslide.budget import phase
from isoslide.datasets import write_netcdf
from isoslide.studies import fragility_study
from isoslide.store.provenance import log_to

with log_to(snakemake.log[0]) as log:
    ds = fragility_study.dataset_job(fragility_study, fragility_study.fragility_dataset, snakemake.input.chunks,
                                     snakemake.wildcards.frag, snakemake.params.settings, log)
    with phase("writing", log):
        write_netcdf(ds, snakemake.output[0])
