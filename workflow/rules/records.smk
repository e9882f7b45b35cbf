# Real records against their fitted pulses (isoslide.record_study): Fig. 4 from a real record, and
# peak sliding under each record and under its fitted pulse over a Pi2 x Pi3 grid (one job per
# record, then one dataset), its figure and reports/records.html.


rule fig4_record:
    output:
        "results/datasets/fig4_record.nc",
    params:
        code=RECORDS_CODE,
        settings=FIG4_SETTINGS,
    conda:
        "../envs/isoslide.yaml"
    log:
        "logs/records/fig4_record.log",
    script:
        "../scripts/records.py"


rule record_compare:
    output:
        "results/records/{record}.nc",
    params:
        code=RECORDS_CODE,
        settings=RECORDS_SETTINGS,
    conda:
        "../envs/isoslide.yaml"
    log:
        "logs/records/{record}.log",
    threads: 1
    script:
        "../scripts/records.py"


rule records_dataset:
    input:
        expand("results/records/{record}.nc", record=RECORDS),
    output:
        "results/datasets/records.nc",
    params:
        code=RECORDS_CODE,
        settings=RECORDS_SETTINGS,
    conda:
        "../envs/isoslide.yaml"
    log:
        "logs/records/records.log",
    script:
        "../scripts/records.py"


rule figure_records:
    input:
        records="results/datasets/records.nc",
    output:
        expand("reports/figures/records.{ext}", ext=FORMATS),
    params:
        code=FIGURE_CODE,
        settings=FIGURE_SETTINGS,
    conda:
        "../envs/isoslide.yaml"
    log:
        "logs/figure/records.log",
    script:
        "../scripts/figure.py"


rule report_records:
    input:
        notebook="workflow/notebooks/records.ipynb",
        data="results/datasets/records.nc",
        figure="reports/figures/records.png",
        fig4="reports/figures/fig4.png",
    output:
        notebook="reports/records.ipynb",
        html="reports/records.html",
    conda:
        "../envs/isoslide.yaml"
    log:
        "logs/report/records.log",
    shell:
        """
        papermill {input.notebook} reports/.records.tmp.ipynb -k python3 \
            -p records_path {input.data} -p figure_dir reports/figures --no-progress-bar > {log} 2>&1
        mv -f reports/.records.tmp.ipynb {output.notebook}
        jupyter nbconvert --to html --no-input --embed-images --output-dir reports \
            --output .records.tmp {output.notebook} >> {log} 2>&1
        mv -f reports/.records.tmp.html {output.html}
        """
