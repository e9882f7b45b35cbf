"""Rule similarity_study: Buckingham realisations of one study (isoslide.similarity)."""

from isoslide.datasets import open_dataset, write_netcdf
from isoslide.provenance import log_to
from isoslide.similarity import buckingham_study

with log_to(snakemake.log[0]):
    ds = buckingham_study(open_dataset(snakemake.input[0]), snakemake.params.settings)
    write_netcdf(ds, snakemake.output[0])
