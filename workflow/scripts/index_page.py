"""Rule index_page: reports/index.html, the run at a glance (isoslide.reports.index_page)."""

from pathlib import Path

from isoslide.budget import phase
from isoslide.reports.index_page import index_html
from isoslide.store.provenance import log_to

with log_to(snakemake.log[0]) as log:
    with phase("reporting", log):
        page = index_html(datasets=dict(zip(snakemake.params.names, snakemake.input.datasets, strict=True)),
                          figures=snakemake.input.figures, reports=snakemake.input.reports,
                          config=snakemake.params.config, out_dir=Path(snakemake.output[0]).parent,
                          benchmark_dir=snakemake.params.benchmark_dir)
        Path(snakemake.output[0]).write_text(page, encoding="utf-8")
