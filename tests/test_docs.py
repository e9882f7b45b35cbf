"""The documentation site: it builds without a warning, and its generated tables hold what they render."""

import csv
import html
import re
import subprocess
import sys
from pathlib import Path

import pytest

from isoslide.groups import GROUPS

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
sys.path.insert(0, str(DOCS / "_ext"))

import isoslide_docs  # noqa: E402


def _text(page: Path) -> str:
    """The text of an HTML page, tags removed."""
    return html.unescape(re.sub(r"<[^>]+>", "", page.read_text()))


def test_measurements_file_has_every_field_on_every_row():
    rows = isoslide_docs.read_measurements()
    assert rows
    for row in rows:
        assert row["value"].strip() and row["command"].strip() and row["unit"].strip(), row
        assert re.fullmatch(r"[0-9a-f]{7,40}", row["commit"]), row


def test_measurements_file_with_an_empty_command_is_rejected(tmp_path):
    bad = tmp_path / "m.csv"
    with open(bad, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(isoslide_docs.FIELDS)
        w.writerow(["solver", "cost", "1.0", "ms", "", "2026-01-01", "abcdef0", ""])
    with pytest.raises(ValueError, match="command"):
        isoslide_docs.read_measurements(bad)


def test_docstring_fixups_escape_absolute_values_outside_literals_only():
    lines = ["friction ``mu(|v|)`` at speed |v| and |tau|; :math:`|x|` as is"]
    notes = isoslide_docs.fix_docstring(lines)
    assert lines == [r"friction ``mu(|v|)`` at speed \|v\| and \|tau\|; :math:`|x|` as is"]
    assert notes


def test_docstring_fixups_lengthen_a_short_underline_and_keep_a_long_one():
    lines = ["Model (dimensionless)", "----------", "", "Notes", "-----------"]
    isoslide_docs.fix_docstring(lines)
    assert lines[1] == "-" * len("Model (dimensionless)")
    assert lines[4] == "-----------"


def test_docstring_fixups_show_a_malformed_table_as_preformatted_text_and_keep_a_good_one():
    good = ["====  ====", "a     b", "====  ====", "1     2", "====  ===="]
    bad = ["====  ====", "a     b", "====  ====", "12345 2", "====  ===="]
    lines = list(good)
    assert isoslide_docs.fix_docstring(lines) == [] and lines == good
    lines = list(bad)
    isoslide_docs.fix_docstring(lines)
    assert lines[0] == "::" and all(ln.startswith("    ") for ln in lines[2:2 + len(bad)])


@pytest.mark.slow
def test_site_builds_without_a_warning_and_renders_the_registry_and_the_measurements(tmp_path):
    out, warnings = tmp_path / "html", tmp_path / "warnings.txt"
    proc = subprocess.run(
        [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html", "-w", str(warnings),
         str(DOCS), str(out)],
        capture_output=True, text=True, cwd=ROOT)
    assert proc.returncode == 0, proc.stdout[-4000:] + proc.stderr[-4000:]
    assert warnings.read_text().strip() == ""

    model = _text(out / "guide" / "model.html")
    for group in GROUPS.values():
        assert group.definition in model, group.name
        assert group.meaning in model, group.name

    pages = {p.stem: _text(p) for p in (out / "guide").glob("*.html")}
    for row in isoslide_docs.read_measurements():
        assert any(row["value"] in text and row["command"] in text for text in pages.values()), row

    modules = {p.stem for p in (out / "api").glob("isoslide*.html")}
    sources = {".".join(p.relative_to(ROOT / "src").with_suffix("").parts).removesuffix(".__init__")
               for p in (ROOT / "src" / "isoslide").rglob("*.py")
               if p.name != "__main__.py"}  # a ``python -m`` entry point runs when imported
    assert sources <= modules, sorted(sources - modules)
