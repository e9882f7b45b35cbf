"""Rules figure and figure_records: draw one figure from its datasets (isoslide.figures.draw)."""

import matplotlib

matplotlib.use("Agg")

from isoslide.datasets import logging_to  # noqa: E402
from isoslide.figures import draw  # noqa: E402

with logging_to(snakemake.log[0]):  # noqa: F821 - injected by Snakemake
    name = getattr(snakemake.wildcards, "fig", "records")  # noqa: F821 - rule figure_records has no wildcard
    draw(name, dict(snakemake.input.items()), snakemake.output, snakemake.params.settings)  # noqa: F821
