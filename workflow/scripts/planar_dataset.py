"""Rule planar_dataset: contents sliding in the plane, and the Pi5 slice
(isoslide.studies.planar.planar_dataset, pi5_dataset)."""

from isoslide.budget import phase
from isoslide.datasets import write_netcdf
from isoslide.store.provenance import log_to
from isoslide.solver import warm_up
from isoslide.studies.planar import pi5_dataset, planar_dataset

with log_to(snakemake.log[0]) as log:
    with phase("compilation", log):
        warm_up(building=True)
    with phase("solving", log):
        ds = planar_dataset(snakemake.params.settings)
        ds5 = pi5_dataset(snakemake.params.settings)
    log.info("%s", ds)
    log.info("%s", ds5)
    with phase("writing", log):
        write_netcdf(ds, snakemake.output.planar)
        write_netcdf(ds5, snakemake.output.planar_pi5)
