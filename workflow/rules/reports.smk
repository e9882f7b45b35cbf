# HTML reports, one rule for all of them: papermill runs workflow/notebooks/<report>.ipynb (kernel
# python3, parameters from REPORTS in common.smk injected after its `parameters` cell), nbconvert
# renders the executed notebook without code cells and with its images embedded, through
# workflow/notebooks/offline.html.j2 (JupyterLab's template without its CDN scripts: MathJax,
# require.js, mermaid), so a report makes no network request and reads the same offline; math in
# the notebooks is written in Unicode (Π₁, μ_k) for that reason.  MPLBACKEND=Agg keeps the job
# headless; a notebook that draws selects `%matplotlib inline` so its figures are embedded.  Both run under
# the interpreter that runs Snakemake, so no activated environment is needed.  The executed
# notebook is kept as a log (logs/report/<report>.ipynb), next to the commands' output.


rule report:
    input:
        unpack(report_input),
        template="workflow/notebooks/offline.html.j2",
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
        mem_mb=800,  # measured: max_rss 359 MB (accuracy; papermill + kernel)
        runtime=3,  # minutes; measured: 12.8 s at most (similarity, with its master curves)
    conda:
        "../envs/isoslide.yaml"
    shell:
        """
        export MPLBACKEND=Agg
        {params.python:q} -m papermill {input.notebook:q} {log.notebook:q} -k python3 \
            {params.parameters} --no-progress-bar > {log.log:q} 2>&1
        {params.python:q} -m nbconvert --to html --no-input --embed-images \
            --template-file {input.template:q} --output-dir {params.html_dir:q} --output {wildcards.report} {log.notebook:q} >> {log.log:q} 2>&1
        """


# reports/index.html: the run at a glance (datasets with the line that opens each, figure
# thumbnails, links to every report, provenance and run time), built by isoslide.reports.index_page from
# the files listed in INDEX (common.smk).  It comes last, so the benchmark files of every other
# job of the run are there to be summed.
rule index_page:
    input:
        datasets=list(INDEX["datasets"].values()),
        figures=INDEX["figures"],
        reports=INDEX["reports"],
        needs=INDEX["needs"],
    output:
        "reports/index.html",
    params:
        code=CODE["index"],
        names=list(INDEX["datasets"]),
        config=INDEX["config"],
        benchmark_dir="results/benchmarks",
    log:
        "logs/index_page/index.log",
    benchmark:
        "results/benchmarks/index_page/index.tsv"
    threads: 1
    resources:
        mem_mb=300,  # measured: max_rss 103 MB (test config)
        runtime=2,  # minutes; measured: 0.7 s (test config)
    conda:
        "../envs/isoslide.yaml"
    script:
        "../scripts/index_page.py"
