"""Rule fragility_pelicun: fragility.nc -> a pelicun (FEMA P-58) damage-model CSV and its JSON of
descriptions (isoslide.studies.pelicun_export.write_damage_db; a curve the data could not identify is
written with Incomplete = 1)."""

from isoslide.budget import phase
from isoslide.datasets import open_dataset
from isoslide.studies.pelicun_export import write_damage_db
from isoslide.store.provenance import log_to

with log_to(snakemake.log[0]) as log, phase("writing", log):
    ds = open_dataset(snakemake.input[0])
    write_damage_db(snakemake.output.csv, ds["theta"], ds["beta"], json_path=snakemake.output.json,
                    incomplete="flag", description=f"{ds.attrs['title']} ({ds.attrs['source']})")
