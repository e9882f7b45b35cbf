"""Rule similarity_study: Buckingham realisations of one study (isoslide.similarity)."""

from isoslide.budget import phase
from isoslide.datasets import open_dataset, write_netcdf
from isoslide.provenance import log_to
from isoslide.similarity import buckingham_study

with log_to(snakemake.log[0]) as log:
    with phase("solving", log):
        ds = buckingham_study(open_dataset(snakemake.input[0]), snakemake.params.settings)
    with phase("writing", log):
        write_netcdf(ds, snakemake.output[0])
