"""Rule fragility_figure: the fragility curves from the datasets (isoslide.reports.fragility_plot.draw_curves)."""

import matplotlib

matplotlib.use("Agg")

from isoslide.budget import phase  # noqa: E402
from isoslide.datasets import open_dataset  # noqa: E402
from isoslide.reports.fragility_plot import draw_curves  # noqa: E402
from isoslide.store.provenance import log_to  # noqa: E402

with log_to(snakemake.log[0]) as log, phase("reporting", log):
    fixed = open_dataset(snakemake.input.fixed_base) if "fixed_base" in snakemake.input.keys() else None
    draw_curves(open_dataset(snakemake.input.isolated), snakemake.output, fixed=fixed,
                dpi=snakemake.params.dpi)
