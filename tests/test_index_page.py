"""isoslide.reports.index_page without Snakemake: the page of a small fake run, its tables and links."""

import html
import re

import numpy as np
import pytest
import xarray as xr
from PIL import Image, PngImagePlugin

from isoslide import __version__
from isoslide.reports.index_page import flatten, human_size, index_html, job_times


@pytest.fixture
def run(tmp_path):
    """A fake run: two datasets, a figure (PNG with caption + PDF), a report, benchmark files."""
    (tmp_path / "results" / "datasets").mkdir(parents=True)
    (tmp_path / "reports" / "figures").mkdir(parents=True)
    for name, n in (("fig5_pi3", 3), ("similarity", 2)):
        xr.Dataset({"pi1": (("pi2",), np.arange(n, dtype=float))}, attrs={"title": f"title of {name}"}) \
            .to_netcdf(tmp_path / "results" / "datasets" / f"{name}.nc")
    info = PngImagePlugin.PngInfo()
    info.add_text("Description", "Fig. 5. Master curves of Pi1. " + "More text. " * 30 + "END")
    Image.new("RGB", (40, 30), "white").save(tmp_path / "reports" / "figures" / "fig5.png", pnginfo=info)
    (tmp_path / "reports" / "figures" / "fig5.pdf").write_bytes(b"%PDF-1.4\n")
    (tmp_path / "reports" / "similarity.html").write_text("<html></html>")
    for rule, rows in (("solve_chunk", [(1.5, 100.0), (2.5, 120.0)]), ("report", [(4.0, 300.0)])):
        d = tmp_path / "results" / "benchmarks" / rule
        d.mkdir(parents=True)
        for k, (s, rss) in enumerate(rows):
            (d / f"{k}.tsv").write_text(f"s\th:m:s\tmax_rss\n{s}\t0:00:0{s:.0f}\t{rss}\n")
    return tmp_path


def page(run, **kw):
    args = dict(datasets={"fig5_pi3": "results/datasets/fig5_pi3.nc", "similarity": "results/datasets/similarity.nc"},
                figures=["reports/figures/fig5.png"], reports=["reports/similarity.html"],
                config={"chunk_size": 15, "studies": {"fig5_pi3": {"dims": {"pi3": [0.01, 1.0]}}}},
                out_dir="reports", benchmark_dir="results/benchmarks", commit="abc123")
    args.update(kw)
    return index_html(**args)


def test_index_lists_datasets_with_size_and_the_line_that_opens_them(run, monkeypatch):
    monkeypatch.chdir(run)
    text = html.unescape(page(run))
    size = human_size((run / "results/datasets/fig5_pi3.nc").stat().st_size)
    assert 'xr.open_dataset("results/datasets/fig5_pi3.nc")' in text
    assert "title of fig5_pi3" in text and "pi2 = 3" in text and size in text
    assert 'href="../results/datasets/similarity.nc"' in text


def test_index_links_figures_pdfs_and_reports_relative_to_the_page(run, monkeypatch):
    monkeypatch.chdir(run)
    text = page(run)
    assert '<a href="figures/fig5.png"><img src="figures/fig5.png"' in text
    assert '<a href="figures/fig5.pdf">PDF</a>' in text
    assert "Fig. 5. Master curves of Pi1. More text." in text and "END" not in text   # caption, cut
    assert '<a href="similarity.html">similarity</a>' in text


def test_index_provenance_and_run_time_tables(run, monkeypatch):
    monkeypatch.chdir(run)
    text = page(run)
    assert f"<td>{__version__}</td>" in text and "<code>abc123</code>" in text
    assert re.search(r"<td>solve_chunk</td><td class=\"num\">2</td><td class=\"num\">4.0</td>"
                     r"<td class=\"num\">2.5</td><td class=\"num\">120</td>", text)
    assert "<b>8.0</b>" in text                                     # all jobs: 1.5 + 2.5 + 4.0 s
    assert "<code>studies.fig5_pi3.dims.pi3</code></td><td><code>[0.01, 1.0]</code>" in text
    assert "<script" not in text and "http" not in text.replace("http-equiv", "")


def test_index_without_benchmarks_says_the_run_time_is_not_available(run, monkeypatch):
    monkeypatch.chdir(run)
    assert "Run time: not available" in page(run, benchmark_dir=None)
    assert "Run time: not available" in page(run, benchmark_dir="results/nowhere")


def test_index_names_missing_input_files(run, monkeypatch):
    monkeypatch.chdir(run)
    with pytest.raises(FileNotFoundError, match="reports/missing.html"):
        page(run, reports=["reports/missing.html"])


def test_job_times_reads_every_benchmark_file_per_rule(run):
    times = {t.rule: t for t in job_times(run / "results" / "benchmarks")}
    assert set(times) == {"report", "solve_chunk"}
    assert times["solve_chunk"].jobs == 2 and times["solve_chunk"].total_s == 4.0
    assert times["report"].max_rss_mb == 300.0


def test_human_size_and_flatten():
    assert [human_size(n) for n in (0, 999, 1000, 1_234_567, 5_000_000_000)] == \
        ["0 B", "999 B", "1.0 kB", "1.2 MB", "5.0 GB"]
    with pytest.raises(ValueError, match="n_bytes = -1"):
        human_size(-1)
    assert flatten({"b": {"c": [1, 2], "a": "x"}, "a": 1, "e": {}}) == \
        [("a", "1"), ("b.a", '"x"'), ("b.c", "[1, 2]"), ("e", "{}")]


def test_a_study_added_to_the_registry_is_on_the_index_page(run, monkeypatch):
    """The page's lists come from the study registry: one more Study puts its dataset, figure and
    report on the page."""
    import isoslide.config
    from isoslide.studies import registry

    config = isoslide.config.load()
    extra = registry.Study(name="extra", sections=(), datasets=("fig5_pi3",), figures=("fig5",),
                           reports=(registry.Report("similarity"),))
    before = registry.index_lists(config)
    assert "fig5_pi3" in before["datasets"]          # a paper study: it is the paper's, not a new one
    lists = registry.index_lists(config, [extra])
    assert lists == {"datasets": {"fig5_pi3": "results/datasets/fig5_pi3.nc"},
                     "figures": ["reports/figures/fig5.png"], "reports": ["reports/similarity.html"]}
    with pytest.raises(ValueError, match="dataset 'fig5_pi3' of study 'extra'"):
        registry.index_lists(config, [*registry.STUDIES, extra])
    monkeypatch.setattr(registry, "STUDIES", registry.STUDIES + (
        registry.Study(name="more", sections=(), datasets=("more",), figures=("more",)),))
    lists = registry.index_lists(config)
    assert lists["datasets"]["more"] == "results/datasets/more.nc" and lists["figures"][-1] == "reports/figures/more.png"
    assert list(lists["datasets"])[:len(before["datasets"])] == list(before["datasets"])
    monkeypatch.chdir(run)
    lists = registry.index_lists(config, [extra])
    text = html.unescape(page(run, datasets=lists["datasets"], figures=lists["figures"], reports=lists["reports"]))
    assert 'xr.open_dataset("results/datasets/fig5_pi3.nc")' in text
    assert '<img src="figures/fig5.png"' in text and '<a href="similarity.html">similarity</a>' in text


def test_index_lists_every_study_of_the_registry():
    import isoslide.config
    from isoslide.studies import registry

    config = isoslide.config.load()
    lists = registry.index_lists(config)
    for study in registry.STUDIES:
        assert set(study.dataset_files(config).items()) <= set(lists["datasets"].items()), study.name
        assert {f"reports/figures/{f}.png" for f in study.figures} <= set(lists["figures"]), study.name
        assert {f"reports/{r.name}.html" for r in study.reports} <= set(lists["reports"]), study.name
    assert lists["datasets"]["storeys"] == "results/datasets/storeys.nc"
    assert "reports/figures/storeys.png" in lists["figures"]
    assert lists["datasets"]["accuracy_timings"] == "results/timings/accuracy_timings.nc"
