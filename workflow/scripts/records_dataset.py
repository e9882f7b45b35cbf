"""Rule records_dataset: every record's comparison in one dataset (isoslide.studies.record_study)."""

from isoslide.budget import phase
from isoslide.datasets import open_dataset, write_netcdf
from isoslide.store.provenance import log_to
from isoslide.studies.record_study import records_dataset

with log_to(snakemake.log[0]) as log:
    ds = records_dataset([open_dataset(p) for p in snakemake.input], snakemake.params.settings)
    log.info("%s", ds)
    with phase("writing", log):
        write_netcdf(ds, snakemake.output[0])
