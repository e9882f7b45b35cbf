"""Rule accuracy_dataset: the measured parts combined into results/datasets/accuracy.nc (isoslide.accuracy)."""

from pathlib import Path

from isoslide.accuracy import combine, trade_table
from isoslide.datasets import open_dataset, write_netcdf
from isoslide.provenance import log_to

with log_to(snakemake.log[0]) as log:
    parts = {Path(path).stem: open_dataset(path) for path in snakemake.input}
    ds = combine(parts, snakemake.params.config)
    for row in trade_table(ds):
        log.info("%s", row)
    write_netcdf(ds, snakemake.output[0])
