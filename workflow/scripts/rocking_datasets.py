"""Rule rocking_datasets: the overturning spectra, the sliding-or-rocking map and the overturning fragility
of a rocking block, and the fragility's pelicun damage-model CSV and JSON
(isoslide.studies.rocking.study_datasets, write_outputs)."""

from isoslide.budget import compile_solve_write
from isoslide.solver import warm_up
from isoslide.store.provenance import log_to
from isoslide.studies.rocking import study_datasets, write_outputs

with log_to(snakemake.log[0]) as log:
    compile_solve_write(log, lambda: warm_up(records=True, building=True),
                        lambda: study_datasets(snakemake.params.settings),
                        lambda datasets: write_outputs(datasets, **dict(snakemake.output.items())))
