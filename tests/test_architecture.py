"""The package's structure: no import cycles, one Pi-group registry, one source of defaults."""

import ast
import dataclasses
import re
import subprocess
import sys
from pathlib import Path

import pytest

import isoslide
import isoslide.config
from isoslide import groups

PKG = Path(isoslide.__file__).resolve().parent
ROOT = PKG.parents[1]


def _module_name(path: Path) -> str:
    rel = path.relative_to(PKG.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _package_imports():
    """{module: [(imported isoslide module, at module level?)]} from the source (no import run)."""
    modules = {_module_name(p): p for p in PKG.rglob("*.py")}
    out = {}
    for name, path in modules.items():
        tree = ast.parse(path.read_text())
        is_pkg = path.name == "__init__.py"
        top_level = {id(n) for n in tree.body}
        found = []
        for node in ast.walk(tree):
            targets = []
            if isinstance(node, ast.ImportFrom):
                if node.level:
                    base = name.split(".") if is_pkg else name.split(".")[:-1]
                    base = base[: len(base) - (node.level - 1)]
                    mod = ".".join(base + ([node.module] if node.module else []))
                else:
                    mod = node.module or ""
                targets = [mod] + [f"{mod}.{a.name}" for a in node.names]
            elif isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            for t in targets:
                if t in modules and t not in (name, "isoslide"):   # the package namespace is always loaded
                    found.append((t, id(node) in top_level))
        out[name] = found
    return out


def test_no_import_cycles_between_package_modules():
    graph = {m: sorted({t for t, _ in deps}) for m, deps in _package_imports().items()}
    # a package's __init__ that re-exports its modules is not a dependency of those modules
    for m in graph:
        graph[m] = [t for t in graph[m] if not m.startswith(t + ".")]
    state, stack, cycles = {}, [], []

    def visit(m):
        state[m] = 1
        stack.append(m)
        for t in graph.get(m, ()):
            if state.get(t) == 1:
                cycles.append(stack[stack.index(t):] + [t])
            elif t not in state:
                visit(t)
        stack.pop()
        state[m] = 2

    for m in sorted(graph):
        if m not in state:
            visit(m)
    assert not cycles, "import cycles: " + "; ".join(" -> ".join(c) for c in cycles)


def test_package_modules_import_each_other_at_module_level():
    """No isoslide import hidden inside a function (the lazy package namespace excepted)."""
    hidden = [(m, t) for m, deps in _package_imports().items() if m != "isoslide"
              for t, top in deps if not top]
    assert not hidden, f"imports inside functions: {hidden}"


def test_the_datasets_module_is_a_leaf():
    deps = {t for t, _ in _package_imports()["isoslide.datasets"]}
    assert deps <= {"isoslide.atomic", "isoslide.groups", "isoslide.models", "isoslide.store.provenance",
                    "isoslide.model.validation"}


def test_the_atomic_write_module_imports_nothing_of_the_package():
    """isoslide.atomic serves the datasets, figures, exports and the kernels' import: standard library only."""
    assert _package_imports()["isoslide.atomic"] == []


def test_scene_fields_are_the_registry_input_groups_with_their_defaults():
    fields = {f.name: f for f in dataclasses.fields(isoslide.Scene)}
    pi_fields = [n for n in fields if n.startswith("pi")]
    assert pi_fields == list(groups.INPUT_NAMES + groups.ROCKING_NAMES + groups.TFP_SPEED_NAMES)
    assert all(fields[n].default is None for n in groups.ROCKING_NAMES + groups.TFP_SPEED_NAMES)
    for g in groups.INPUTS:
        f = fields[g.name]
        if g.default is None:
            assert f.default is dataclasses.MISSING, g.name
        else:
            assert f.default == g.default, g.name


def test_scene_errors_quote_the_registry_range():
    for g in groups.INPUTS:
        bad = g.lo - 1.0 if g.lo_in or g.lo > -1 else float("nan")
        args = {"pi2": 0.2, "pi3": 1.0, g.name: bad}
        with pytest.raises(ValueError, match=rf"{g.name} = .*allowed range: {re.escape(g.range_text)}"):
            isoslide.Scene(**args)


DUMMY = """
import isoslide.groups as g
dummy = g.Group("pi99", "Q / (M_b a_p)", "dummy strength", r"\\Pi_{99}", r"Q/(M_b a_p)", "Π₉₉", default=0.5,
                comment="a group added for the test")
g.INPUTS = g.INPUTS + (dummy,)
g.GROUPS = {x.name: x for x in (g.RESULT, *g.INPUTS)}
g.INPUT_NAMES = tuple(x.name for x in g.INPUTS)
import contextlib, io, json
from isoslide import cli, datasets, figures, scene, similarity, sweep
help_text = io.StringIO()
with contextlib.redirect_stdout(help_text), contextlib.suppress(SystemExit):
    cli.main(["solve", "--help"])
print(json.dumps({
    "attrs": datasets.pi_attrs("pi99"),
    "label": figures.LABELS["pi99"],
    "definition": list(similarity.DEFINITIONS["pi99"]),
    "sweep": "pi99" in sweep.PI_NAMES and "pi99" in sweep.SWEEPABLE,
    "range": list(scene.PI_RANGES["pi99"]),
    "cli": "--pi99" in help_text.getvalue() and "dummy strength" in help_text.getvalue(),
}))
"""


def test_a_group_added_to_the_registry_appears_everywhere():
    """A new group in isoslide.groups reaches dataset attributes, figure labels, the similarity
    definitions, the study dimensions, the validation ranges and the command-line help."""
    import json

    out = subprocess.run([sys.executable, "-c", DUMMY], capture_output=True, text=True, check=True)
    got = json.loads(out.stdout.strip().splitlines()[-1])
    assert got["attrs"]["long_name"] == "Pi99 = Q / (M_b a_p): dummy strength"
    assert got["attrs"]["units"] == "1" and got["attrs"]["comment"] == "a group added for the test"
    assert got["label"] == r"$\Pi_{99} = Q/(M_b a_p)$"
    assert got["definition"] == ["Q / (M_b a_p)", "Q / (M_b a_p)"]
    assert got["sweep"] and got["cli"]
    assert got["range"][:2] == [0.0, float("inf")]


# ----------------------------------------------------------------------------------------------
# one source of defaults
# ----------------------------------------------------------------------------------------------

def _leaves(schema, path=()):
    """(path, subschema) of every configurable leaf of the schema (studies are the user's)."""
    props = schema.get("properties", {})
    for k, sub in props.items():
        if k == "studies" or (path and path[-1] == "similarity" and k == "complete"):
            continue
        if sub.get("type") == "object" and "properties" in sub:
            yield from _leaves(sub, path + (k,))
        else:
            yield path + (k,), sub


def test_every_configuration_key_has_its_default_in_the_schema():
    missing = [".".join(p) for p, sub in _leaves(isoslide.config.schema()) if "default" not in sub]
    assert not missing, f"schema keys without a default: {missing}"


def test_loaded_configuration_equals_snakemakes_validation():
    """isoslide.config.load fills exactly what the workflow's snakemake.utils.validate fills."""
    import yaml
    from snakemake.utils import validate

    raw = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
    validate(raw, str(ROOT / "config" / "schema.yaml"))
    assert raw == isoslide.config.load(ROOT / "config" / "config.yaml")


def test_the_package_ships_the_repository_configuration():
    assert isoslide.config.paper_config_path().read_text() == (ROOT / "config" / "config.yaml").read_text()


def _config_keys(schema, out=None):
    out = set() if out is None else out
    for k, sub in schema.get("properties", {}).items():
        out.add(k)
        _config_keys(sub, out)
    return out


def test_library_holds_no_hidden_configuration_defaults():
    """No ``config.get("<key>", <default>)`` or ``settings.get(...)`` in the package: defaults live
    in the schema."""
    keys = _config_keys(isoslide.config.schema()) - {"pulse"}   # a study's own pulse falls back explicitly
    offenders = []
    for path in PKG.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            if (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "get"
                    and len(node.args) == 2 and isinstance(node.args[0], ast.Constant)
                    and node.args[0].value in keys
                    and re.search(r"config|settings|section|cfg", ast.unparse(node.func.value))
                    and not (isinstance(node.args[1], ast.Constant) and node.args[1].value is None)):
                offenders.append(f"{path.relative_to(PKG)}:{node.lineno} .get({node.args[0].value!r}, ...)")
    assert not offenders, offenders


# ----------------------------------------------------------------------------------------------
# the layout: a few top-level modules, subpackages by what they hold, imports in one direction
# ----------------------------------------------------------------------------------------------

LAYERS = (
    ("base", ("isoslide.atomic", "isoslide.budget", "isoslide.config", "isoslide.groups", "isoslide.jit_cache",
              "isoslide.model", "isoslide.models")),
    ("excitation", ("isoslide.pulses",)),
    ("scene", ("isoslide.scene", "isoslide.records")),
    ("engine", ("isoslide.engine",)),
    ("store", ("isoslide.store",)),
    ("peers", ("isoslide.peers",)),
    ("solver", ("isoslide.solver",)),
    ("datasets", ("isoslide.datasets",)),
    ("studies", ("isoslide.studies", "isoslide.accuracy")),
    ("reports", ("isoslide.reports",)),
    ("interface", ("isoslide.cli", "isoslide.bench")),
)
"""The package's layers, lowest first: a module imports from its own layer and those below only."""


def _layer(module: str) -> int | None:
    for i, (_, prefixes) in enumerate(LAYERS):
        if any(module == p or module.startswith(p + ".") for p in prefixes):
            return i
    return None


def test_every_module_belongs_to_one_layer():
    unplaced = [m for m in _package_imports() if m != "isoslide" and _layer(m) is None]
    assert not unplaced, f"modules in no layer of LAYERS: {unplaced}"


def test_imports_go_down_the_layers_only():
    """model -> excitation -> scene -> engine -> store -> peers -> solver -> datasets -> studies -> reports -> cli."""
    upward = [(m, t) for m, deps in _package_imports().items() if m != "isoslide"
              for t, _ in deps if _layer(t) is not None and _layer(t) > _layer(m)]
    assert not upward, "imports of a higher layer: " + "; ".join(f"{m} -> {t}" for m, t in upward)


def test_the_package_has_at_most_twelve_top_level_modules():
    top = sorted(p.stem for p in PKG.glob("*.py") if p.stem not in ("__init__", "__main__"))
    assert len(top) <= 12, top


def test_modules_of_the_flat_layout_still_import_from_their_old_names():
    """``isoslide.<old>`` is the module at its new place, with a DeprecationWarning naming it."""
    import importlib
    import warnings

    for old, new in isoslide.MOVED.items():
        assert (PKG / Path(*new.split("."))).with_suffix(".py").is_file(), new
        assert not (PKG / Path(*old.split("."))).with_suffix(".py").exists(), old
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        sys.modules.pop("isoslide.sweep", None)
        old = importlib.import_module("isoslide.sweep")
    assert old is importlib.import_module("isoslide.studies.sweep")
    assert any(issubclass(w.category, DeprecationWarning) and "isoslide.studies.sweep" in str(w.message)
               for w in caught)


INNER_LOOPS = {
    "building_kernel": ("deriv", "rk_step", "_event", "_event_at", "_accels", "_block_load", "normal", "friction",
                        "bearing_level", "_hysteretic", "_storey_force", "_base_shear", "_floor_stuck",
                        "_bearing_need", "contact"),
    "planar_kernel": ("deriv", "rk_step", "_event", "_demand", "_bearing_need", "_slaved_dir", "_turning"),
}
"""The functions each Runge-Kutta stage or event evaluation of the general and planar kernels runs."""


@pytest.mark.parametrize("module", sorted(INNER_LOOPS))
def test_the_kernels_inner_loops_are_compiled_without_reference_counting(module):
    """What runs at every stage allocates nothing, so it is compiled without numba's reference counts
    (atomic increments and decrements on every array argument at every call): a function that
    needed them would not compile."""
    import importlib

    mod = importlib.import_module(f"isoslide.engine.{module}")
    counted = [name for name in INNER_LOOPS[module] if getattr(mod, name).targetoptions.get("_nrt", True)]
    assert not counted, f"{module}: {counted} are compiled with reference counting"
