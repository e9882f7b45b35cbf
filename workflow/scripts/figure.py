"""Rule figure: draw figure {fig} of the paper from its datasets (isoslide.reports.figures.draw)."""

import matplotlib

matplotlib.use("Agg")

from isoslide.budget import phase  # noqa: E402
from isoslide.reports.figures import draw  # noqa: E402
from isoslide.store.provenance import log_to  # noqa: E402

with log_to(snakemake.log[0]) as log, phase("reporting", log):
    draw(snakemake.wildcards.fig, dict(snakemake.input.items()), snakemake.output, snakemake.params.settings)
