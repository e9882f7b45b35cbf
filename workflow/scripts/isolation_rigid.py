"""Rule isolation_rigid: where the rigid-superstructure reduction holds (isoslide.studies.isolation_study)."""

from isoslide.budget import phase
from isoslide.datasets import write_netcdf
from isoslide.studies.isolation_study import rigid_dataset
from isoslide.store.provenance import log_to

with log_to(snakemake.log[0]) as log:
    with phase("reporting", log):
        ds = rigid_dataset({"base": snakemake.input.base, "roof": snakemake.input.roof}, snakemake.params.settings)
    log.info("%s", ds)
    with phase("writing", log):
        write_netcdf(ds, snakemake.output[0])
