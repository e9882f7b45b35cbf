"""Rule planar_figure: the planar study's figures from its datasets (isoslide.reports.planar_plot.draw_all)."""

import matplotlib

matplotlib.use("Agg")

from isoslide.budget import phase  # noqa: E402
from isoslide.reports.planar_plot import draw_all  # noqa: E402
from isoslide.store.provenance import log_to  # noqa: E402

with log_to(snakemake.log[0]) as log, phase("reporting", log):
    draw_all(dict(snakemake.input.items()), snakemake.output, snakemake.params.settings)
