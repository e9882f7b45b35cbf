"""Sphinx extension of the isoslide documentation.

Directives
----------
``.. pi-groups::``
    The Pi-group table, rendered from the registry :data:`isoslide.groups.GROUPS` at build time
    (option ``:groups:`` ``result``, ``paper``, ``building``, ``bearing-friction`` or ``all``, the default).
``.. measurements::``
    The rows of ``docs/measurements.csv`` with a given ``:topic:`` as a table: quantity, value,
    unit, the command that measures it, and when and where it was measured.  A row whose topic is
    never rendered, or that lacks a field, is a build warning (so an error under ``-W``).

Docstring fix-ups
-----------------
A few reStructuredText slips in docstrings are repaired before numpydoc reads them, each
reported in the build log (``docstring fix-up``) with its location:

* ``|x|`` (an absolute value) outside inline literals is escaped, not read as a substitution;
* a section underline shorter than its title is lengthened;
* a simple table with text in a column margin is shown as preformatted text.
"""

from __future__ import annotations

import csv
import re
from pathlib import Path

from docutils import nodes
from docutils.parsers.rst import Directive, directives
from docutils.statemachine import StringList
from sphinx.util import logging

from isoslide.accuracy.measurements import FIELDS as MEASUREMENT_FIELDS

logger = logging.getLogger(__name__)

MEASUREMENTS = Path(__file__).resolve().parent.parent / "measurements.csv"
"""The measured figures the documentation quotes."""

FIELDS = MEASUREMENT_FIELDS
"""Columns of ``measurements.csv`` (:data:`isoslide.accuracy.measurements.FIELDS`); every one is required but
``conditions``."""

GROUP_SETS = ("result", "paper", "building", "bearing-friction", "all")


def _cell(text: str) -> list[str]:
    """A list-table cell (``text`` may be reStructuredText), as indented lines."""
    lines = (text or " ").splitlines() or [" "]
    return [lines[0]] + [f"    {ln}" for ln in lines[1:]]


def _plain(text: str) -> str:
    """Plain text (a registry's words) escaped so that reStructuredText shows it as written."""
    return re.sub(r"([\\`*|_\[\]<>])", r"\\\1", text)


def _list_table(header: list[str], rows: list[list[str]], widths: list[int]) -> list[str]:
    """The lines of a reStructuredText ``list-table`` with one header row."""
    out = [".. list-table::", "   :header-rows: 1", f"   :widths: {' '.join(map(str, widths))}", ""]
    for row in [header, *rows]:
        for i, cell in enumerate(row):
            first, *rest = _cell(cell)
            out.append(f"   {'*' if i == 0 else ' '} - {first}")
            out.extend(f"     {ln}" for ln in rest)
    return out


class _RstDirective(Directive):
    """A directive that writes reStructuredText and parses it in place."""

    def _parse(self, lines: list[str]) -> list[nodes.Node]:
        source, _ = self.state_machine.get_source_and_line(self.lineno)
        container = nodes.container()
        self.state.nested_parse(StringList(lines, source=source), self.content_offset, container)
        return container.children


class PiGroups(_RstDirective):
    """Table of the Pi-groups of :data:`isoslide.groups.GROUPS`."""

    option_spec = {"groups": lambda arg: directives.choice(arg, GROUP_SETS)}

    def run(self):
        """The table's nodes."""
        from isoslide import groups as registry

        which = self.options.get("groups", "all")
        names = {
            "result": (registry.RESULT.name,),
            "paper": registry.PAPER_NAMES,
            "building": registry.BUILDING_NAMES,
            "bearing-friction": registry.BEARING_FRICTION_NAMES,
            "all": tuple(registry.GROUPS),
        }[which]
        rows = []
        for name in names:
            g = registry.GROUPS[name]
            definition = f"``{g.definition}``"
            if g.printed != g.definition:
                definition += f" (the paper prints ``{g.printed}``)"
            default = "required" if g.default is None else f"``{g.default:g}``"
            if g is registry.RESULT:
                default = "the result"
            rows.append([f":math:`{g.tex}`", definition, _plain(g.meaning), f"``{g.range_text}``",
                         default, _plain(g.comment)])
        header = ["group", "definition", "meaning", "valid range", "default", "note"]
        return self._parse(_list_table(header, rows, [8, 22, 20, 16, 9, 30]))


def read_measurements(path: Path = MEASUREMENTS) -> list[dict]:
    """Rows of the measurements file, each checked for its required fields."""
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        if tuple(reader.fieldnames or ()) != FIELDS:
            raise ValueError(f"{path}: columns {reader.fieldnames}, expected {list(FIELDS)}")
        rows = list(reader)
    for i, row in enumerate(rows, start=2):
        missing = [k for k in FIELDS[:-1] if not (row.get(k) or "").strip()]
        if missing:
            raise ValueError(f"{path}:{i}: empty field(s) {missing}")
        if not re.fullmatch(r"\d{4}-\d{2}-\d{2}", row["date"]):
            raise ValueError(f"{path}:{i}: date {row['date']!r} is not YYYY-MM-DD")
    return rows


class Measurements(_RstDirective):
    """Table of the measured figures of one topic of ``measurements.csv``."""

    option_spec = {"topic": directives.unchanged_required}

    def run(self):
        """The table's nodes."""
        env = self.state.document.settings.env
        env.note_dependency(str(MEASUREMENTS))
        topic = self.options.get("topic", "")
        rows = [r for r in read_measurements() if r["topic"] == topic]
        if not rows:
            raise self.error(f"measurements: no row with topic {topic!r} in {MEASUREMENTS.name}")
        rendered = env.domaindata.setdefault("isoslide_measurements", {})
        rendered.setdefault(topic, set()).add(env.docname)
        table = []
        for r in rows:
            where = f"{r['date']}, commit ``{r['commit']}``"
            if r["conditions"].strip():
                where += f"; {_plain(r['conditions'].strip())}"
            table.append([_plain(r["quantity"]), f"**{_plain(r['value'])}**", _plain(r["unit"]),
                          f"``{r['command']}``", where])
        header = ["quantity", "value", "unit", "measured by", "when, where"]
        return self._parse(_list_table(header, table, [28, 10, 8, 30, 24]))


def _merge_measurements(app, env, docnames, other):
    mine = env.domaindata.setdefault("isoslide_measurements", {})
    for topic, docs in other.domaindata.get("isoslide_measurements", {}).items():
        mine.setdefault(topic, set()).update(docs)


def _purge_measurements(app, env, docname):
    for docs in env.domaindata.get("isoslide_measurements", {}).values():
        docs.discard(docname)


def _check_every_topic_rendered(app, env):
    rendered = {t for t, docs in env.domaindata.get("isoslide_measurements", {}).items() if docs}
    for topic in sorted({r["topic"] for r in read_measurements()} - rendered):
        logger.warning(f"measurements: topic {topic!r} of {MEASUREMENTS.name} is on no page",
                       location=str(MEASUREMENTS))


# ---- docstring fix-ups ------------------------------------------------------------------------

_LITERAL = re.compile(r"(``.+?``)")
_ABS = re.compile(r"(?<![\\|\w`])\|([A-Za-z_][\w.]*)\|(?![\w|])")
_UNDERLINE = re.compile(r"^(\s*)([-=~^])\2+\s*$")
_BORDER = re.compile(r"^(\s*)(=+)( +=+)+\s*$")


def _escape_abs(line: str) -> str:
    """``|x|`` outside inline literals written as an absolute value, not a substitution."""
    parts = _LITERAL.split(line)
    return "".join(p if i % 2 else _ABS.sub(r"\\|\1\\|", p) for i, p in enumerate(parts))


def _margin_overflow(border: str, rows: list[str]) -> bool:
    """True if a row of a simple table has text in a column margin (docutils rejects it)."""
    spans = [m.span() for m in re.finditer(r"=+", border)]
    margins = [(spans[i][1], spans[i + 1][0]) for i in range(len(spans) - 1)]
    for row in rows:
        for lo, hi in margins:
            if row[lo:hi].strip():
                return True
    return False


def _fix_tables(lines: list[str]) -> tuple[list[str], int]:
    """Malformed simple tables turned into literal blocks; returns the lines and their count."""
    out, i, fixed = [], 0, 0
    while i < len(lines):
        m = _BORDER.match(lines[i])
        if not m:
            out.append(lines[i])
            i += 1
            continue
        j, borders = i + 1, 1
        while j < len(lines) and lines[j].strip() and borders < 3:
            borders += bool(_BORDER.match(lines[j]) and lines[j].strip() == lines[i].strip())
            j += 1
        block = lines[i:j]
        rows = [ln for ln in block if not _BORDER.match(ln)]
        if _margin_overflow(lines[i], rows):
            indent = m.group(1)
            if out and out[-1].strip():
                out.append("")
            out += [f"{indent}::", ""] + [f"{indent}    {ln[len(indent):]}" for ln in block] + [""]
            fixed += 1
        else:
            out += block
        i = j
    return out, fixed


def fix_docstring(lines: list[str]) -> list[str]:
    """Repair ``lines`` (a docstring) in place; returns what was done."""
    done = []
    for k, line in enumerate(lines):
        escaped = _escape_abs(line)
        if escaped != line:
            done.append(f"line {k + 1}: |x| escaped")
            lines[k] = escaped
    for k in range(1, len(lines)):
        m = _UNDERLINE.match(lines[k])
        title = lines[k - 1]
        if (m and title.strip() and not _UNDERLINE.match(title)
                and len(lines[k].rstrip()) < len(title.rstrip())):
            lines[k] = m.group(1) + m.group(2) * (len(title.rstrip()) - len(m.group(1)))
            done.append(f"line {k + 1}: underline lengthened")
    new, n = _fix_tables(lines)
    if n:
        lines[:] = new
        done.append(f"{n} malformed simple table(s) shown as preformatted text")
    return done


def _process_docstring(app, what, name, obj, options, lines):
    for note in fix_docstring(lines):
        logger.info(f"docstring fix-up in {name}: {note}")


def setup(app):
    """Register the directives, the measurement checks and the docstring fix-ups."""
    app.add_directive("pi-groups", PiGroups)
    app.add_directive("measurements", Measurements)
    app.connect("env-merge-info", _merge_measurements)
    app.connect("env-purge-doc", _purge_measurements)
    app.connect("env-check-consistency", _check_every_topic_rendered)
    app.connect("autodoc-process-docstring", _process_docstring, priority=400)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
