"""The studies of the pipeline: their registry and the modules of the studies declared there.

:mod:`isoslide.studies.registry` declares every study (configuration section, datasets, figures,
reports, rule file, SLURM groups, code families) and derives the workflow's lists from them;
:mod:`isoslide.studies.imports` computes the import closure behind each code family;
:mod:`isoslide.studies.storeys` (with :mod:`isoslide.reports.storeys_plot`) is the storeys study.

``python -m isoslide.studies`` prints the SLURM groups of the registry and, with ``--write PATH``,
writes them into the ``groups:`` block of a Snakemake profile (``profiles/slurm/config.yaml``).

Nothing is imported here, so a job that runs one study's module loads only that module.
"""
