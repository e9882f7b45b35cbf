# Speed versus accuracy (isoslide.accuracy): results/datasets/accuracy.nc and reports/accuracy.html.
#
#   snakemake --cores 2 accuracy
#
# Self-contained: the settings come from the config's `accuracy:` section when it has one, else
# from isoslide.accuracy.DEFAULTS; the scene set is drawn from the config's studies.  Four
# independent measurement jobs (one per part, so two cores run them side by side) are combined
# into the dataset; the report notebook only reads it.  Every output is written to a temporary
# name and moved into place.

import isoslide.accuracy as _accuracy
import isoslide.sweep as _sweep

try:  # hash of the package code the measurement runs, so that editing it reruns the jobs
    from isoslide.datasets import code_hash as _code_hash

    ACCURACY_CODE = _code_hash(include=("accuracy", "solver", "kernel", "pulses", "scene", "reference",
                                        "regularized", "sweep", "datasets"))
except ImportError:  # pragma: no cover - older package without code_hash
    ACCURACY_CODE = ""

ACCURACY_PARTS = list(_accuracy.PARTS)
# what the measurement depends on: the accuracy settings and the studies with the keys they inherit
ACCURACY_CONFIG = _sweep.jsonable(
    {
        "accuracy": _accuracy.settings_from(config.get("accuracy", {})),
        **{k: config[k] for k in ("studies", "defaults", "pi2", "reference", "chunk_size") if k in config},
    }
)


rule accuracy_part:
    output:
        "results/accuracy/{part}.nc",
    params:
        config=ACCURACY_CONFIG,
        code=ACCURACY_CODE,
    wildcard_constraints:
        part="|".join(ACCURACY_PARTS),
    conda:
        "../envs/isoslide.yaml"
    log:
        "logs/accuracy/{part}.log",
    script:
        "../scripts/accuracy_dataset.py"


rule accuracy_dataset:
    input:
        expand("results/accuracy/{part}.nc", part=ACCURACY_PARTS),
    output:
        "results/datasets/accuracy.nc",
    params:
        config=ACCURACY_CONFIG,
        code=ACCURACY_CODE,
    conda:
        "../envs/isoslide.yaml"
    log:
        "logs/accuracy/combine.log",
    script:
        "../scripts/accuracy_dataset.py"


rule report_accuracy:
    input:
        notebook="workflow/notebooks/accuracy.ipynb",
        data="results/datasets/accuracy.nc",
    output:
        notebook="reports/accuracy.ipynb",
        html="reports/accuracy.html",
    conda:
        "../envs/isoslide.yaml"
    log:
        "logs/report/accuracy.log",
    shell:
        """
        mkdir -p reports
        papermill {input.notebook} reports/.accuracy.tmp.ipynb -k python3 \
            -p accuracy_path {input.data} --no-progress-bar > {log} 2>&1
        mv -f reports/.accuracy.tmp.ipynb {output.notebook}
        jupyter nbconvert --to html --no-input --embed-images --output-dir reports \
            --output .accuracy.tmp {output.notebook} >> {log} 2>&1
        mv -f reports/.accuracy.tmp.html {output.html}
        """


rule accuracy:
    input:
        "results/datasets/accuracy.nc",
        "reports/accuracy.html",
