"""Rules fig4_record, record_compare and records_dataset (isoslide.record_study).

The science is in isoslide.record_study; this script only wires files together.
"""

from isoslide.datasets import logging_to, open_dataset, write_netcdf
from isoslide.record_study import fig4_dataset, record_dataset, records_dataset

smk = snakemake  # noqa: F821 - injected by Snakemake

with logging_to(smk.log[0]):
    settings = smk.params.settings
    if smk.rule == "fig4_record":
        ds = fig4_dataset(settings)
    elif smk.rule == "record_compare":
        ds = record_dataset(smk.wildcards.record, settings)
    else:
        ds = records_dataset([open_dataset(p) for p in smk.input], settings)
    print(ds, flush=True)
    write_netcdf(ds, smk.output[0])
