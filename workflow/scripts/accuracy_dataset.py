"""Rule accuracy_dataset: the measured parts combined into results/datasets/accuracy.nc and its
wall-clock costs into results/timings/accuracy_timings.nc (isoslide.accuracy)."""

from pathlib import Path

from isoslide.accuracy import combine, split_timings, trade_table
from isoslide.budget import phase
from isoslide.datasets import open_dataset, write_netcdf
from isoslide.store.provenance import log_to

with log_to(snakemake.log[0]) as log:
    parts = {Path(path).stem: open_dataset(path) for path in snakemake.input}
    ds = combine(parts, snakemake.params.config)
    for row in trade_table(ds):
        log.info("%s", row)
    results, timings = split_timings(ds)
    with phase("writing", log):
        write_netcdf(timings, snakemake.output.timings)
        write_netcdf(results, snakemake.output.results)
