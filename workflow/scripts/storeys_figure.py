"""Rule storeys_figure: the storeys study's figure from its dataset (isoslide.reports.storeys_plot.draw)."""

import matplotlib

matplotlib.use("Agg")

from isoslide.budget import phase  # noqa: E402
from isoslide.store.provenance import log_to  # noqa: E402
from isoslide.reports.storeys_plot import draw  # noqa: E402

with log_to(snakemake.log[0]) as log, phase("reporting", log):
    draw(snakemake.input[0], snakemake.output, snakemake.params.settings)
