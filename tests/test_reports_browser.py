"""Every HTML report of the pipeline, and reports/index.html, opened in headless Chromium.

The reports are built from config/test.yaml in a temporary copy of the workflow (as in
tests/test_workflow.py), then each page is loaded from its file:// address in Debian's Chromium
(driven by Debian's chromedriver through selenium; nothing is downloaded at run time) with every
request to an http(s) address blocked and logged.  Each page must show no raw TeX, make no request
other than file: and data:, load every image and log no JavaScript error.

Without Chromium and chromedriver on the machine (``apt-get install chromium chromium-driver``)
these tests are skipped, saying so; .ci/run installs both.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import time
from dataclasses import dataclass
from html import escape
from pathlib import Path

import pytest
import xarray as xr
from selenium import webdriver
from selenium.webdriver.chrome.service import Service

from test_workflow import TEST_CONFIG, copy_workflow, snakemake

REPORT_PAGES = ["accuracy", "figures", "records", "similarity", "fragility", "isolation", "planar", "rocking", "index"]

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
CHROMEDRIVER = shutil.which("chromedriver")
NO_CHROMIUM = "headless Chromium not installed (apt-get install chromium chromium-driver)"


def require_chromium():
    """Skip without Chromium and chromedriver; in CI (CI=true, where .ci/run installs them) fail."""
    if CHROMIUM is None or CHROMEDRIVER is None:
        if os.environ.get("CI") == "true":
            pytest.fail(f"CI=true but {NO_CHROMIUM}: .ci/run installs them as root on Debian")
        pytest.skip(NO_CHROMIUM)

RAW_TEX = re.compile(r"\$[^$\n]{1,200}\$|\\[A-Za-z]{2,}|\\[{}_^]|\^\{|_\{")
"""Raw TeX in visible text: $...$, a command (\\Pi, \\mu, \\frac), or a braced sub/superscript."""


@dataclass(frozen=True)
class PageCheck:
    """What headless Chromium saw on one page.

    Attributes
    ----------
    text : str
        The page's visible text (``document.body.innerText``).
    requests : tuple of str
        Every URL the page requested (from the DevTools ``Network.requestWillBeSent`` events).
    images : tuple of (str, int, bool)
        Per ``<img>``: the start of its ``src``, its ``naturalWidth`` (px), whether it completed.
    console_errors : tuple of str
        Console messages of level SEVERE (JavaScript errors, failed loads).
    seconds : float
        Wall-clock time of loading and inspecting the page, s.
    """

    text: str
    requests: tuple
    images: tuple
    console_errors: tuple
    seconds: float

    def raw_tex(self) -> list[str]:
        """Pieces of visible text that look like unrendered TeX."""
        return RAW_TEX.findall(self.text)

    def network_requests(self) -> list[str]:
        """Requests to anything but file: and data: addresses."""
        return [u for u in self.requests if not u.startswith(("file:", "data:"))]

    def broken_images(self) -> list:
        """Images that did not load (not complete or naturalWidth 0)."""
        return [i for i in self.images if not (i[2] and i[1] > 0)]


def start_browser():
    """Headless Debian Chromium under selenium, its network to http(s) blocked, logs enabled."""
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for arg in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
                "--no-first-run", "--disable-background-networking", "--disable-component-update",
                "--disable-sync", "--disable-extensions", "--allow-file-access-from-files"):
        options.add_argument(arg)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL", "performance": "ALL"})
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    driver.execute_cdp_cmd("Network.enable", {})
    driver.execute_cdp_cmd("Network.setBlockedURLs", {"urls": ["http://*", "https://*", "ws://*", "wss://*"]})
    return driver


def check_page(driver, path: Path) -> PageCheck:
    """Load ``path`` (file://) in ``driver`` and collect what :class:`PageCheck` holds."""
    t0 = time.monotonic()
    driver.get_log("performance")          # drop earlier pages' events
    driver.get_log("browser")
    driver.get(path.resolve().as_uri())
    driver.execute_async_script(           # every image settled (loaded or failed)
        "const done = arguments[arguments.length - 1];"
        "Promise.all([...document.images].map(i => i.complete ? null :"
        " new Promise(r => { i.onload = r; i.onerror = r; }))).then(() => done(null));")
    text = driver.execute_script("return document.body.innerText;")
    images = tuple((s[:60], int(w), bool(c)) for s, w, c in driver.execute_script(
        "return [...document.images].map(i => [i.getAttribute('src') || '', i.naturalWidth, i.complete]);"))
    time.sleep(0.2)                        # late console messages
    requests = []
    for entry in driver.get_log("performance"):
        msg = json.loads(entry["message"])["message"]
        if msg["method"] == "Network.requestWillBeSent":
            requests.append(msg["params"]["request"]["url"])
    errors = tuple(e["message"] for e in driver.get_log("browser") if e["level"] == "SEVERE")
    return PageCheck(text, tuple(requests), images, errors, time.monotonic() - t0)


@pytest.fixture(scope="module")
def browser():
    require_chromium()
    driver = start_browser()
    yield driver
    driver.quit()


@pytest.fixture(scope="module")
def built_reports(tmp_path_factory):
    """reports/ of a run of config/test.yaml in a temporary copy of the workflow, and its seconds."""
    require_chromium()
    wf = copy_workflow(tmp_path_factory.mktemp("wf_reports"))
    t0 = time.monotonic()
    snakemake(wf, "--cores", "2", *TEST_CONFIG, timeout=1800)
    seconds = time.monotonic() - t0
    print(f"test-config run with every report: {seconds:.0f} s")
    return wf / "reports", seconds


# ----------------------------------------------------------------------------------------------
# the checks themselves, on small pages made here (they must catch what they look for)
# ----------------------------------------------------------------------------------------------

def test_the_page_check_catches_raw_tex_network_requests_broken_images_and_script_errors(browser, tmp_path):
    png = "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8z8BQDwAEhQGAhKmMIQAAAABJRU5ErkJggg=="
    good = tmp_path / "good.html"
    good.write_text(f'<html><body><p>Π₁ = u_max/(a_p T_p²) costs $5</p><img src="data:image/png;base64,{png}">'
                    "</body></html>")
    bad = tmp_path / "bad.html"
    bad.write_text(r'<html><head><script src="https://cdn.example.org/x.js"></script></head><body>'
                   r"<p>$\Pi_1 = u_{max}$ and \mu_k</p><img src='missing.png'>"
                   "<script>undefined_function();</script></body></html>")
    ok = check_page(browser, good)
    assert not ok.raw_tex() and not ok.network_requests() and not ok.broken_images() and not ok.console_errors, ok
    assert ok.images and ok.images[0][1] == 1
    ko = check_page(browser, bad)
    assert ko.raw_tex() and "\\mu" in "".join(ko.raw_tex())
    assert ko.network_requests() == ["https://cdn.example.org/x.js"]
    assert ko.broken_images() and ko.broken_images()[0][0] == "missing.png"
    assert any("undefined_function" in e for e in ko.console_errors), ko.console_errors


# ----------------------------------------------------------------------------------------------
# the pipeline's reports
# ----------------------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def checked(browser, built_reports):
    reports, _ = built_reports
    t0 = time.monotonic()
    out = {name: check_page(browser, reports / f"{name}.html") for name in REPORT_PAGES}
    print(f"browser checks of {len(out)} pages: {time.monotonic() - t0:.1f} s")
    return out


@pytest.mark.slow
@pytest.mark.parametrize("page", REPORT_PAGES)
def test_report_renders_offline_in_chromium(checked, page):
    """No raw TeX in the visible text, no request but file:/data:, every image loaded, no console error."""
    c = checked[page]
    assert len(c.text) > 200, c.text
    assert "Traceback" not in c.text
    assert not c.raw_tex(), c.raw_tex()[:10]
    assert not c.network_requests(), c.network_requests()
    assert c.images and not c.broken_images(), c.broken_images()
    assert not c.console_errors, c.console_errors
    assert any(u.startswith("file:") for u in c.requests)


@pytest.mark.slow
def test_reports_load_no_script_from_anywhere(built_reports):
    """The offline template: no <script src=...> at all (no CDN, no MathJax, no require.js)."""
    reports, _ = built_reports
    for page in REPORT_PAGES:
        html = (reports / f"{page}.html").read_text()
        assert not re.search(r"<script[^>]+src=", html), page
        assert "mathjax" not in html.lower(), page


@pytest.mark.slow
def test_similarity_report_draws_the_curves_of_every_verdict(checked, built_reports):
    """Each complete-similarity case and each conclusion comes with its figure; provenance is a table."""
    reports, _ = built_reports
    with xr.open_dataset(reports.parent / "results" / "datasets" / "similarity.nc") as ds:
        n_groups = len(set(ds.complete_group.values))
        n_conclusions = ds.sizes["conclusion"]
        claims = [str(v) for v in ds.conclusion_claim.values]
    page = (reports / "similarity.html").read_text()
    images = len(checked["similarity"].images)
    assert images >= n_groups + n_conclusions, (images, n_groups, n_conclusions)
    text = checked["similarity"].text
    starts = [page.index(escape(claim.split(" (")[0][:40], quote=False)) for claim in claims]
    assert starts == sorted(starts)
    for claim, a, b in zip(claims, starts, [*starts[1:], len(page)], strict=True):
        assert "<img" in page[a:b], f"no figure between this conclusion and the next: {claim}"
    assert "spread band" in page and "Π₁" in text
    provenance = text[text.index("Provenance"):]
    assert "isoslide_config" not in provenance and '{"' not in provenance
    assert "similarity settings: spread_tolerance" in provenance and "similarity settings: complete.pi5.range" in provenance


@pytest.mark.slow
def test_index_page_lists_every_dataset_figure_and_report(checked, built_reports):
    reports, _ = built_reports
    text = checked["index"].text
    for nc in sorted((reports.parent / "results" / "datasets").glob("*.nc")):
        assert f'xr.open_dataset("results/datasets/{nc.name}")' in text, nc.name
    assert 'xr.open_dataset("results/timings/accuracy_timings.nc")' in text
    srcs = [i[0] for i in checked["index"].images]
    for png in sorted((reports / "figures").glob("*.png")):
        assert f"figures/{png.name}" in srcs, png.name
    html = (reports / "index.html").read_text()
    for page in REPORT_PAGES[:-1]:
        assert f'href="{page}.html"' in html, page
    assert "git commit" in text and "all jobs" in text and "chunk_size" in text


@pytest.mark.slow
def test_time_to_build_and_check_the_reports(built_reports, checked):
    """Prints the measured times (the README quotes them); every page checked in under 30 s."""
    _, seconds = built_reports
    total = sum(c.seconds for c in checked.values())
    print(f"test-config run: {seconds:.0f} s; browser checks: {total:.1f} s for {len(checked)} pages")
    assert all(c.seconds < 30 for c in checked.values()), {k: c.seconds for k, c in checked.items()}
