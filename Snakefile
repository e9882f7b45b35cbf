# isoslide: Pi-grid fan-out -> labelled netCDF -> every paper figure -> HTML reports.
#
#   snakemake --cores 2                                   # everything (config/config.yaml)
#   snakemake --cores 2 --configfile config/test.yaml     # tiny end-to-end run
#
# The science lives in the isoslide package; rules only wire files together
# (see workflow/rules/*.smk).  Default options come from profiles/default/config.yaml.

import re

from snakemake.utils import min_version, validate

min_version("9.0")


configfile: "config/config.yaml"


validate(config, "config/schema.yaml")


include: "workflow/rules/common.smk"


wildcard_constraints:
    study="|".join(STUDIES),
    chunk=r"\d+",
    fig=r"fig[1-8]",
    record="|".join(re.escape(r) for r in RECORDS),


include: "workflow/rules/sweep.smk"
include: "workflow/rules/similarity.smk"
include: "workflow/rules/figures.smk"
include: "workflow/rules/reports.smk"
include: "workflow/rules/records.smk"
include: "workflow/rules/accuracy.smk"


rule all:
    input:
        DATASETS,
        "results/datasets/similarity.nc",
        FIGURE_FILES,
        "reports/similarity.html",
        "results/datasets/fig4_record.nc",
        "results/datasets/records.nc",
        RECORD_FIGURE_FILES,
        "reports/records.html",
        "reports/figures.html",
        "results/datasets/accuracy.nc",
        "reports/accuracy.html",
    default_target: True
