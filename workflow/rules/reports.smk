# HTML reports, one rule for all of them: papermill runs workflow/notebooks/<report>.ipynb (kernel
# python3, parameters from REPORTS in common.smk injected after its `parameters` cell), nbconvert
# renders the executed notebook without code cells and with its images embedded.  Both run under
# the interpreter that runs Snakemake, so no activated environment is needed.  The executed
# notebook is kept as a log (logs/report/<report>.ipynb), next to the commands' output.


rule report:
    input:
        unpack(report_input),
    output:
        html="reports/{report}.html",
    params:
        parameters=report_parameters,
        code=lambda wildcards: CODE.get(REPORTS[wildcards.report].get("code"), ""),
        html_dir=lambda wildcards, output: os.path.dirname(output.html),
        python=sys.executable,  # the interpreter running Snakemake: papermill, nbconvert, the kernel
    log:
        notebook="logs/report/{report}.ipynb",
        log="logs/report/{report}.log",
    benchmark:
        "results/benchmarks/report/{report}.tsv"
    threads: 1
    resources:
        mem_mb=800,  # measured: max_rss 347 MB (accuracy; papermill + kernel)
        runtime=3,  # minutes; measured: 8.3 s at most
    conda:
        "../envs/isoslide.yaml"
    shell:
        """
        export MPLBACKEND=Agg
        {params.python:q} -m papermill {input.notebook:q} {log.notebook:q} -k python3 \
            {params.parameters} --no-progress-bar > {log.log:q} 2>&1
        {params.python:q} -m nbconvert --to html --no-input --embed-images \
            --output-dir {params.html_dir:q} --output {wildcards.report} {log.notebook:q} >> {log.log:q} 2>&1
        """
