"""Rule fragility_planar_dataset: chunks -> results/datasets/{pfrag}.nc with the fitted curves and the
comparisons (isoslide.studies.fragility_planar); a dataset of one chunk is solved here."""

from isoslide.budget import phase
from isoslide.datasets import write_netcdf
from isoslide.studies import fragility_planar
from isoslide.studies.fragility_study import dataset_job
from isoslide.store.provenance import log_to

with log_to(snakemake.log[0]) as log:
    ds = dataset_job(fragility_planar, fragility_planar.planar_dataset, snakemake.input.chunks,
                     snakemake.wildcards.pfrag, snakemake.params.settings, log)
    with phase("writing", log):
        write_netcdf(ds, snakemake.output[0])
