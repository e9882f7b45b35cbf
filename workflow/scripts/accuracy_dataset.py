"""Rules accuracy_part (one measurement part) and accuracy_dataset (combine the parts).

The science is in isoslide.accuracy; this script only wires files together.
"""

from isoslide import accuracy
from isoslide.datasets import logging_to, open_dataset, write_netcdf

smk = snakemake  # noqa: F821 - injected by Snakemake

with logging_to(smk.log[0]):
    cfg = smk.params.config
    if smk.rule == "accuracy_part":
        part = smk.wildcards.part
        print(f"measuring part {part!r} with settings {cfg['accuracy']}", flush=True)
        ds = accuracy.measure_part(part, cfg)
    else:
        parts = {}
        for path in smk.input:
            name = path.rsplit("/", 1)[-1].removesuffix(".nc")
            parts[name] = open_dataset(path)
        ds = accuracy.combine(parts, cfg)
        for row in accuracy.trade_table(ds):
            print(row, flush=True)
    write_netcdf(ds, smk.output[0])
