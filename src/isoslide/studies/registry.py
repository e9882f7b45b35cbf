"""The studies of the pipeline, declared once; the workflow's lists are derived from them.

Each :class:`Study` says what the pipeline makes for it and what it depends on: the configuration
sections it reads, its datasets (``results/datasets/<name>.nc``), its figures
(``reports/figures/<name>.<format>``), further files, its share of the HTML reports (notebook
``workflow/notebooks/<report>.ipynb``), its rule file, the SLURM group of its batched rules and its
code families: for each family, the package modules its scripts (or notebooks) import.  From
:data:`STUDIES` the workflow derives

* the targets of ``rule all`` (:func:`all_targets`),
* the reports and their inputs (:func:`reports`; several studies may add to one report),
* the lists of the index page (:func:`index_lists`),
* the SLURM groups of the cluster profile (:func:`slurm_groups`, written into
  ``profiles/slurm/config.yaml`` by ``python -m isoslide.studies``),
* the modules behind each code family (:func:`code_modules`): the import closure of its entry
  modules, computed from the sources (:mod:`isoslide.studies.imports`), so that editing a module
  reruns exactly the jobs that run it.

Adding a study is then: its module, its rule file (``workflow/rules/<name>.smk``), its scripts, its
notebook (or a section of an existing one) and its configuration section (``config/schema.yaml``
with defaults), plus one :class:`Study` here.

Plain Python, no Snakemake.  Lists that depend on the configuration (the paper's studies, the
fragility study's bases) are callables of the complete configuration, answered by the study's own
module (the workflow imports those modules anyway to check their settings).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field

from . import fragility_planar, fragility_study, isolation_study, rocking
from .imports import closure, module_names

DATASET_DIR = "results/datasets"
"""Directory of the datasets: ``<DATASET_DIR>/<name>.nc``."""

FIGURE_DIR = "reports/figures"
"""Directory of the figures: ``<FIGURE_DIR>/<name>.<format>``."""

REPORT_DIR = "reports"
"""Directory of the HTML reports: ``<REPORT_DIR>/<report>.html``, and of the index page."""

INDEX_PAGE = f"{REPORT_DIR}/index.html"
"""The run at a glance (:mod:`isoslide.reports.index_page`)."""

Names = Sequence[str] | Callable[[Mapping], Sequence[str]]
"""A list of names, or a callable of the complete configuration returning one."""


def _resolve(value, config: Mapping):
    return value(config) if callable(value) else value


def dataset_path(name: str) -> str:
    """File of the dataset ``name``."""
    return f"{DATASET_DIR}/{name}.nc"


def figure_path(name: str, ext: str = "png") -> str:
    """File of the figure ``name`` in format ``ext``."""
    return f"{FIGURE_DIR}/{name}.{ext}"


@dataclass(frozen=True)
class Report:
    """A study's share of one HTML report.

    Attributes
    ----------
    name : str
        The report: notebook ``workflow/notebooks/<name>.ipynb``, page ``reports/<name>.html``.
    data : mapping or callable
        ``{notebook parameter: input file}``: files handed to the notebook, each as the parameter
        of that name (a callable of the configuration may return the mapping).
    parameters : mapping or callable
        Further notebook parameters (values).
    needs : sequence or callable
        Further input files the notebook reads (the figures it shows).
    code : str or None
        The code family of the package modules the notebook imports (None: it imports none).
    """

    name: str
    data: Mapping[str, str] | Callable[[Mapping], Mapping[str, str]] = field(default_factory=dict)
    parameters: Mapping[str, object] | Callable[[Mapping], Mapping[str, object]] = field(default_factory=dict)
    needs: Names = ()
    code: str | None = None


@dataclass(frozen=True)
class Study:
    """One study of the pipeline: its configuration, outputs, reports, rules and code.

    Attributes
    ----------
    name : str
        Name of the study (used in messages and as a key).
    sections : tuple of str
        Top-level configuration sections the study reads.
    datasets : sequence or callable
        Dataset names (``results/datasets/<name>.nc``), or a callable of the complete
        configuration returning them.
    other_datasets : mapping
        ``{name: file}`` of datasets kept elsewhere (wall-clock timings), listed on the index
        page and asked for by ``rule all``.
    figures : sequence of str
        Figure names (``reports/figures/<name>.<format>`` in every configured format).
    outputs : sequence or callable
        Further files ``rule all`` asks for.
    reports : tuple of Report
        The study's shares of the HTML reports.
    code : mapping of str to tuple of str
        ``{family: entry modules}``: per code family, the package modules its scripts or
        notebook import (names relative to the package); the family is their import closure.
        Studies that name the same family add their entry modules to it.
    rule_files : tuple of str
        The study's rule files under ``workflow/rules/``, in include order.
    groups : mapping of str to str
        ``{rule: SLURM group}`` of the study's rules that run batched on a cluster.
    """

    name: str
    sections: tuple[str, ...]
    datasets: Names = ()
    other_datasets: Mapping[str, str] = field(default_factory=dict)
    figures: tuple[str, ...] = ()
    outputs: Names = ()
    reports: tuple[Report, ...] = ()
    code: Mapping[str, tuple[str, ...]] = field(default_factory=dict)
    rule_files: tuple[str, ...] = ()
    groups: Mapping[str, str] = field(default_factory=dict)

    def dataset_names(self, config: Mapping) -> list[str]:
        """Names of the study's datasets under ``config`` (the other datasets last)."""
        return list(_resolve(self.datasets, config)) + list(self.other_datasets)

    def dataset_files(self, config: Mapping) -> dict[str, str]:
        """``{dataset name: file}`` of the study under ``config``."""
        return {n: dataset_path(n) for n in _resolve(self.datasets, config)} | dict(self.other_datasets)


# ----------------------------------------------------------------------------------------------
# the configuration-dependent lists
# ----------------------------------------------------------------------------------------------

def _paper_studies(config: Mapping) -> list[str]:
    return sorted(config["studies"])


def _paper_datasets(config: Mapping) -> list[str]:
    return _paper_studies(config) + ["similarity"]


def _fragility_1d_datasets(config: Mapping) -> list[str]:
    return fragility_study.dataset_names(fragility_study.fragility_settings(config))


def _fragility_planar_datasets(config: Mapping) -> list[str]:
    return fragility_planar.dataset_names(fragility_planar.planar_settings(config))


def _fragility_datasets(config: Mapping) -> list[str]:
    return _fragility_1d_datasets(config) + _fragility_planar_datasets(config)


def _fragility_parameters(config: Mapping) -> dict:
    # the fixed-base comparison and the planar datasets when the configuration asks for them ("" otherwise)
    names, planar = _fragility_1d_datasets(config), _fragility_planar_datasets(config)
    return {"fixed_base_path": dataset_path(names[1]) if len(names) > 1 else "",
            "planar_path": dataset_path(planar[0]) if planar else "",
            "planar_fixed_base_path": dataset_path(planar[1]) if len(planar) > 1 else ""}


def _fragility_needs(config: Mapping) -> list[str]:
    return [dataset_path(n) for n in _fragility_datasets(config)] + ["results/fragility/pelicun_damage_db.csv"]


def _isolation_datasets(config: Mapping) -> list[str]:
    return isolation_study.dataset_names()


PAPER_FIGURES = tuple(f"fig{n}" for n in range(1, 9))
"""The paper's figures."""

ISOLATION_FIGURES = ("isolation_bearings", "isolation_flexible", "isolation_rigid", "isolation_design",
                     "isolation_intensity")
"""The isolation studies' figures (:data:`isoslide.reports.isolation_plot.FIGURES`)."""

PLANAR_FIGURES = ("planar", "planar_ratio", "planar_vertical", "planar_pi5")
"""The planar study's figures (:data:`isoslide.reports.planar_plot.FIGURES`)."""

ROCKING_PELICUN = "results/rocking/pelicun_damage_db.csv"
"""The rocking block's overturning curves as a pelicun damage-model CSV (its ``.json`` beside it)."""


def _rocking_data(config: Mapping) -> dict:
    # spectra_path, map_path, fragility_path and the pelicun CSV the notebook shows
    names = rocking.dataset_names()
    return {f"{n.removeprefix('rocking_')}_path": dataset_path(n) for n in names} | {"pelicun_path": ROCKING_PELICUN}


PIPELINE = Study(
    name="pipeline",
    sections=(),
    code={"index": ("budget", "reports.index_page", "store.provenance")},
    rule_files=("reports.smk",),
    groups={"report": "reports"},
)
"""Not a study: the report rule and the index page, which every study feeds (its rule file comes last)."""

STUDIES: tuple[Study, ...] = (
    Study(
        name="paper",
        sections=("studies", "pi2", "defaults", "reference", "solver", "chunk_size", "similarity", "figures"),
        datasets=_paper_datasets,
        figures=PAPER_FIGURES,
        reports=(
            Report("similarity", data={"similarity_path": dataset_path("similarity")},
                   parameters={"dataset_dir": DATASET_DIR},
                   # the master curves each complete-similarity verdict and conclusion judges
                   needs=lambda config: [dataset_path(n) for n in _paper_studies(config)],
                   code="similarity_report"),
            Report("figures", parameters={"figure_dir": FIGURE_DIR},
                   needs=tuple(figure_path(f) for f in PAPER_FIGURES + ("records",))),
        ),
        code={
            "solve": ("budget", "datasets", "store.provenance", "solver", "studies.sweep"),      # solve_chunk
            "study": ("budget", "datasets", "store.provenance", "studies.similarity", "studies.sweep"),  # merge_study
            "similarity": ("budget", "datasets", "store.provenance", "studies.similarity"),
            "similarity_report": ("studies.claims", "groups"),
            "figures": ("budget", "reports.figures", "store.provenance"),                        # figure, figure_records
        },
        # sweep.smk also solves the isolation studies (merge_isolation_study)
        rule_files=("sweep.smk", "similarity.smk", "figures.smk"),
        groups={"solve_chunk": "solve", "merge_study": "merge", "figure": "figures"},
    ),
    Study(
        name="records",
        sections=("records", "defaults", "solver"),
        datasets=("fig4_record", "records", "record_pairs"),
        figures=("records", "record_pairs"),
        reports=(Report("records", data={"records_path": dataset_path("records"),
                                         "pairs_path": dataset_path("record_pairs")},
                        parameters={"figure_dir": FIGURE_DIR},
                        needs=(figure_path("records"), figure_path("fig4"), figure_path("record_pairs")),
                        code="records"),),
        code={
            # record_compare, records_dataset, record_pairs; the notebook imports studies.record_study
            "records": ("budget", "datasets", "store.provenance", "studies.record_study", "solver"),
            "record_pairs_plot": ("budget", "datasets", "reports.record_pairs_plot", "store.provenance"),
        },
        rule_files=("records.smk",),
        groups={"figure_records": "figures", "record_pairs": "merge", "record_pairs_figure": "figures"},
    ),
    Study(
        name="accuracy",
        sections=("accuracy",),
        datasets=("accuracy",),
        other_datasets={"accuracy_timings": "results/timings/accuracy_timings.nc"},
        reports=(Report("accuracy", data={"accuracy_path": dataset_path("accuracy"),
                                          "timings_path": "results/timings/accuracy_timings.nc"},
                        code="accuracy"),),
        code={"accuracy": ("accuracy", "budget", "datasets", "store.provenance", "solver")},
        rule_files=("accuracy.smk",),
    ),
    Study(
        name="fragility",
        sections=("fragility", "solver"),
        datasets=_fragility_datasets,
        figures=("fragility",),
        outputs=("results/fragility/pelicun_damage_db.csv",),
        reports=(Report("fragility", data={"fragility_path": dataset_path("fragility")}, parameters=_fragility_parameters,
                        needs=_fragility_needs, code="fragility_plot"),),
        code={
            "fragility": ("budget", "datasets", "studies.fragility_study", "store.provenance", "solver"),
            "fragility_plot": ("budget", "datasets", "reports.fragility_plot", "store.provenance"),
            "pelicun": ("budget", "datasets", "studies.pelicun_export", "store.provenance"),
            # fragility_planar_chunk, fragility_planar_dataset
            "fragility_planar": ("budget", "datasets", "store.provenance", "solver", "studies.fragility_planar"),
        },
        rule_files=("fragility.smk",),
        groups={"fragility_chunk": "solve", "fragility_dataset": "merge", "fragility_figure": "figures",
                "fragility_pelicun": "figures", "fragility_planar_chunk": "solve",
                "fragility_planar_dataset": "merge"},
    ),
    Study(
        name="isolation",
        sections=("isolation", "defaults", "solver"),
        datasets=_isolation_datasets,
        figures=ISOLATION_FIGURES,
        reports=(Report("isolation",
                        data={"fp_path": dataset_path("iso_fp"), "lrb_path": dataset_path("iso_lrb"),
                              "flex_base_path": dataset_path("iso_flex_base"),
                              "flex_roof_path": dataset_path("iso_flex_roof"),
                              "rigid_path": dataset_path("isolation_rigid"),
                              "design_path": dataset_path("isolation_design"),
                              "bearings_path": dataset_path("isolation_bearings")},
                        parameters={"figure_dir": FIGURE_DIR},
                        needs=tuple(figure_path(f) for f in ISOLATION_FIGURES), code="isolation_report"),),
        code={
            "isolation": ("budget", "datasets", "studies.isolation_study", "store.provenance", "solver"),
            "isolation_plot": ("budget", "reports.isolation_plot", "store.provenance"),
            "isolation_report": ("datasets", "studies.isolation_study"),
        },
        rule_files=("isolation.smk",),
        groups={"merge_isolation_study": "merge", "isolation_rigid": "merge", "isolation_design": "merge",
                "isolation_bearings": "merge", "isolation_figure": "figures"},
    ),
    Study(
        name="storeys",
        sections=("storeys", "defaults", "solver"),
        datasets=("storeys",),
        figures=("storeys",),
        reports=(Report("isolation", data={"storeys_path": dataset_path("storeys")},
                        needs=(figure_path("storeys"),), code="isolation_report"),),
        code={
            "storeys": ("budget", "datasets", "store.provenance", "solver", "studies.storeys"),
            "storeys_plot": ("budget", "datasets", "store.provenance", "reports.storeys_plot"),
            "isolation_report": ("studies.storeys",),
        },
        rule_files=("storeys.smk",),
        groups={"storeys_dataset": "merge", "storeys_figure": "figures"},
    ),
    Study(
        name="planar",
        sections=("planar", "defaults", "solver"),
        datasets=("planar", "planar_pi5"),
        figures=PLANAR_FIGURES,
        reports=(Report("planar", data={"planar_path": dataset_path("planar"),
                                        "pi5_path": dataset_path("planar_pi5")},
                        parameters={"figure_dir": FIGURE_DIR},
                        needs=tuple(figure_path(f) for f in PLANAR_FIGURES), code="planar"),),
        code={
            # planar_dataset; the notebook's imports (datasets, studies.planar) have the same closure
            "planar": ("budget", "datasets", "store.provenance", "solver", "studies.planar"),
            "planar_plot": ("budget", "datasets", "store.provenance", "reports.planar_plot"),
        },
        rule_files=("planar.smk",),
        groups={"planar_dataset": "merge", "planar_figure": "figures"},
    ),
    Study(
        name="rocking",
        sections=("rocking", "solver"),
        datasets=tuple(rocking.dataset_names()),
        outputs=(ROCKING_PELICUN,),
        # the notebook draws the figures itself
        reports=(Report("rocking", data=_rocking_data, code="rocking_report"),),
        code={
            # rocking_datasets
            "rocking": ("budget", "solver", "store.provenance", "studies.rocking"),
            "rocking_report": ("datasets", "reports.rocking_plot", "studies.rocking"),
        },
        rule_files=("rocking.smk",),
        groups={"rocking_datasets": "merge"},
    ),
)
"""Every study of the pipeline, in the order of ``rule all``, the reports and the index page."""


# ----------------------------------------------------------------------------------------------
# what the workflow derives
# ----------------------------------------------------------------------------------------------

def _studies(studies: Sequence[Study] | None) -> tuple[Study, ...]:
    """``studies``, by default :data:`STUDIES` (read when called), checked for unique names."""
    studies = STUDIES if studies is None else tuple(studies)
    names = [s.name for s in studies]
    dup = sorted({n for n in names if names.count(n) > 1})
    if dup:
        raise ValueError(f"studies = {names!r} name {dup!r} more than once; allowed: unique names")
    return studies


def rule_files(studies: Sequence[Study] | None = None) -> list[str]:
    """Rule files under ``workflow/rules/`` in include order.

    Study by study, then the reports' (``reports.smk``, last: the index page sums the benchmarks of
    every other job).
    """
    studies = _studies(studies)
    out: list[str] = []
    for s in (*studies, PIPELINE):
        out += [f for f in s.rule_files if f not in out]
    return out


def figure_files(figures: Sequence[str], formats: Sequence[str]) -> list[str]:
    """Files of ``figures`` in every format of ``formats`` (figure by figure)."""
    return [figure_path(f, ext) for f in figures for ext in formats]


def reports(config: Mapping, studies: Sequence[Study] | None = None) -> dict[str, dict]:
    """The HTML reports: ``{report: {"data", "parameters", "needs", "code"}}`` (see :class:`Report`).

    The shares of several studies in one report are joined: their data and parameters (a name
    given twice with different values raises ``ValueError``), their needs in order, and one code
    family (they must name the same one).
    """
    studies = _studies(studies)
    out: dict[str, dict] = {}
    for study in studies:
        for r in study.reports:
            entry = out.setdefault(r.name, {"data": {}, "parameters": {}, "needs": [], "code": r.code})
            for key in ("data", "parameters"):
                for k, v in dict(_resolve(getattr(r, key), config)).items():
                    if entry[key].get(k, v) != v:
                        raise ValueError(f"report {r.name!r}: {key} {k!r} = {v!r} of study {study.name!r} differs "
                                         f"from {entry[key][k]!r} given before; allowed: one value per name")
                    entry[key][k] = v
            entry["needs"] += [n for n in _resolve(r.needs, config) if n not in entry["needs"]]
            if r.code != entry["code"]:
                raise ValueError(f"report {r.name!r}: code = {r.code!r} of study {study.name!r} differs from "
                                 f"{entry['code']!r}; allowed: the one code family of the notebook")
    return out


def all_targets(config: Mapping, studies: Sequence[Study] | None = None) -> list[str]:
    """Every file ``rule all`` asks for.

    Each study's datasets, figures (every format of ``figures.formats``) and further outputs, every
    report, then the index page.
    """
    studies = _studies(studies)
    formats = config["figures"]["formats"]
    out: list[str] = []
    for s in studies:
        out += list(s.dataset_files(config).values())
        out += figure_files(s.figures, formats)
        out += list(_resolve(s.outputs, config))
    out += [f"{REPORT_DIR}/{r}.html" for r in reports(config, studies)]
    return out + [INDEX_PAGE]


def index_lists(config: Mapping, studies: Sequence[Study] | None = None) -> dict:
    """What the index page shows, study by study.

    Returns
    -------
    dict
        ``datasets`` (``{name: file}``), ``figures`` (PNG files) and ``reports`` (HTML files).
    """
    studies = _studies(studies)
    datasets: dict[str, str] = {}
    for s in studies:
        for name, path in s.dataset_files(config).items():
            if name in datasets:
                raise ValueError(f"dataset {name!r} of study {s.name!r} is another study's too; "
                                 f"allowed: one study per dataset")
            datasets[name] = path
    return {"datasets": datasets,
            "figures": [figure_path(f) for s in studies for f in s.figures],
            "reports": [f"{REPORT_DIR}/{r}.html" for r in reports(config, studies)]}


def slurm_groups(studies: Sequence[Study] | None = None) -> dict[str, str]:
    """``{rule: SLURM group}`` of every batched rule (the studies', then the reports')."""
    studies = _studies(studies)
    out: dict[str, str] = {}
    for s in (*studies, PIPELINE):
        for rule, group in s.groups.items():
            if out.get(rule, group) != group:
                raise ValueError(f"rule {rule!r}: group {group!r} of study {s.name!r} differs from "
                                 f"{out[rule]!r}; allowed: one group per rule")
            out[rule] = group
    return out


def code_families(studies: Sequence[Study] | None = None) -> dict[str, tuple[str, ...]]:
    """``{family: entry modules}``, the declarations of every study joined (sorted, unique)."""
    studies = _studies(studies)
    out: dict[str, set] = {}
    for s in (*studies, PIPELINE):
        for family, entries in s.code.items():
            if isinstance(entries, str):
                raise ValueError(f"study {s.name!r}: code[{family!r}] = {entries!r} is a string; "
                                 f"allowed: a tuple of module names")
            out.setdefault(family, set()).update(entries)
    return {family: tuple(sorted(entries)) for family, entries in out.items()}


def code_modules(studies: Sequence[Study] | None = None, package_dir=None) -> dict[str, list[str]]:
    """``{family: module names}``: the import closure of each family's entry modules.

    Named as :func:`isoslide.store.provenance.code_hash` takes them (see
    :func:`isoslide.studies.imports.module_names`).
    """
    return {family: module_names(closure(entries, package_dir=package_dir), package_dir)
            for family, entries in code_families(studies).items()}
