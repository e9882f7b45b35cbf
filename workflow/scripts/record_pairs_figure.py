"""Rule record_pairs_figure: the figure of the recorded pairs (isoslide.reports.record_pairs_plot.draw)."""

import matplotlib

matplotlib.use("Agg")

from isoslide.budget import phase  # noqa: E402
from isoslide.reports.record_pairs_plot import draw  # noqa: E402
from isoslide.store.provenance import log_to  # noqa: E402

with log_to(snakemake.log[0]) as log, phase("reporting", log):
    draw(dict(snakemake.input.items()), snakemake.output, snakemake.params.settings)
