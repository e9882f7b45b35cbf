"""Rule similarity_study: Buckingham realisations of one study (isoslide.similarity)."""

from isoslide.datasets import logging_to, open_dataset, write_netcdf
from isoslide.similarity import buckingham_study

with logging_to(snakemake.log[0]):  # noqa: F821 - injected by Snakemake
    ds = buckingham_study(open_dataset(snakemake.input[0]), snakemake.params.settings)
    write_netcdf(ds, snakemake.output[0])
