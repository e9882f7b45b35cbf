"""Rule figure_records: the record-versus-pulse figure from records.nc (isoslide.reports.figures.draw)."""

import matplotlib

matplotlib.use("Agg")

from isoslide.budget import phase  # noqa: E402
from isoslide.reports.figures import draw  # noqa: E402
from isoslide.store.provenance import log_to  # noqa: E402

with log_to(snakemake.log[0]) as log, phase("reporting", log):
    draw("records", dict(snakemake.input.items()), snakemake.output, snakemake.params.settings)
