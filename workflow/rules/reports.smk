# HTML reports: papermill runs a notebook (kernel python3, parameters injected after its
# `parameters` cell), then nbconvert renders it.  Both write to a temporary name first and the
# result is moved into place, so an interrupted job never leaves a partial report.


rule report_similarity:
    input:
        notebook="workflow/notebooks/similarity.ipynb",
        data="results/datasets/similarity.nc",
    output:
        notebook="reports/similarity.ipynb",
        html="reports/similarity.html",
    conda:
        "../envs/isoslide.yaml"
    log:
        "logs/report/similarity.log",
    shell:
        """
        papermill {input.notebook} reports/.similarity.tmp.ipynb -k python3 \
            -p similarity_path {input.data} --no-progress-bar > {log} 2>&1
        mv -f reports/.similarity.tmp.ipynb {output.notebook}
        jupyter nbconvert --to html --no-input --output-dir reports \
            --output .similarity.tmp {output.notebook} >> {log} 2>&1
        mv -f reports/.similarity.tmp.html {output.html}
        """


rule report_figures:
    input:
        notebook="workflow/notebooks/figures.ipynb",
        figures=expand("reports/figures/{fig}.png", fig=FIGURES + ["records"]),
    output:
        notebook="reports/figures.ipynb",
        html="reports/figures.html",
    conda:
        "../envs/isoslide.yaml"
    log:
        "logs/report/figures.log",
    shell:
        """
        papermill {input.notebook} reports/.figures.tmp.ipynb -k python3 \
            -p figure_dir reports/figures --no-progress-bar > {log} 2>&1
        mv -f reports/.figures.tmp.ipynb {output.notebook}
        jupyter nbconvert --to html --no-input --output-dir reports \
            --output .figures.tmp {output.notebook} >> {log} 2>&1
        mv -f reports/.figures.tmp.html {output.html}
        """
