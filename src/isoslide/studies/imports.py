"""Which isoslide modules a piece of code runs: the import closure, read from the sources.

The workflow passes a hash of the modules behind each rule as a rule parameter, so that editing a
module reruns exactly the jobs that run it.  :func:`closure` finds those modules from a few entry
modules without importing anything: it reads the import statements of each module (at any depth,
functions included, so a lazily imported solver counts) and follows those that name a module of
the package, until nothing new is reached.

Conventions (those of :func:`isoslide.store.provenance.code_hash`): module names are relative to the
package, dotted for subpackages (``"solver"``, ``"peers.reference"``); importing ``a.b.c`` runs
``a`` and ``a.b`` first, so a subpackage's ``__init__`` counts; a name imported from the lazy
package namespace (``from isoslide import solve``) counts as the module that defines it; the
package's own ``__init__`` is left out (every job runs it).  :func:`module_names` writes a closure
as the names :func:`~isoslide.store.provenance.code_hash` takes: a subpackage every file of which is
reached by its name (``"peers"``), otherwise each file (``"studies.__init__"``,
``"studies.storeys"``).

Only the import statements are parsed (a regular expression finds them, :mod:`ast` reads each):
the closure of the whole package costs a few milliseconds, which matters because the workflow
computes it on every start, also on a cluster's compute nodes.
"""

from __future__ import annotations

import ast
import functools
import re
from collections.abc import Iterable
from pathlib import Path

PACKAGE = "isoslide"
PACKAGE_DIR = Path(__file__).resolve().parents[1]
"""The directory of the ``isoslide`` package."""

_STATEMENT = re.compile(
    r"^[ \t]*(?:from[ \t]+[\w.]+[ \t]+import[ \t]*(?:\([^)]*\)|[^\n]*(?:\\\n[^\n]*)*)"
    r"|import[ \t]+[^\n]*(?:\\\n[^\n]*)*)",
    re.MULTILINE,
)


def _root(package_dir: Path | str | None) -> Path:
    if package_dir is None or package_dir is PACKAGE_DIR:
        return PACKAGE_DIR
    return Path(package_dir).resolve()


def module_file(name: str, package_dir: Path | str | None = None) -> Path | None:
    """File Python runs for ``isoslide.<name>`` (a subpackage's ``__init__.py``); None if none."""
    return _module_file(name, _root(package_dir))


@functools.lru_cache(maxsize=None)
def _module_file(name: str, root: Path) -> Path | None:
    base = root.joinpath(*name.split("."))
    if (base / "__init__.py").is_file():
        return base / "__init__.py"
    file = base.with_name(base.name + ".py")
    return file if file.is_file() else None


def _statements(source: str) -> list[ast.stmt]:
    """The import statements of ``source`` (found by a pattern, each parsed on its own)."""
    out = []
    for match in _STATEMENT.finditer(source):
        text = match.group(0).strip().rstrip(";")
        try:
            out += ast.parse(text).body
        except SyntaxError:   # a line of text that only looks like an import (in a string)
            continue
    return out


@functools.lru_cache(maxsize=None)
def _exports(package_dir: Path) -> dict:
    """``{name: module}`` of the lazy package namespace (``_EXPORTS`` of ``isoslide/__init__.py``)."""
    init = package_dir / "__init__.py"
    for node in ast.parse(init.read_text(encoding="utf-8")).body:
        if (isinstance(node, ast.Assign) and any(isinstance(t, ast.Name) and t.id == "_EXPORTS" for t in node.targets)
                and isinstance(node.value, ast.Dict)):
            return {ast.literal_eval(k): ast.literal_eval(v) for k, v in zip(node.value.keys, node.value.values,
                                                                              strict=True)}
    return {}


def imported_modules(source: str, module: str | None = None, package_dir: Path | str | None = None) -> set[str]:
    """Names of the isoslide modules that ``source`` imports directly.

    Parameters
    ----------
    source : str
        Python source (a module, a workflow script, the code cells of a notebook).
    module : str, optional
        The module ``source`` is (dotted, relative to the package), to resolve relative imports;
        None for code outside the package.
    package_dir : path, optional
        The package directory; default :data:`PACKAGE_DIR`.
    """
    root = _root(package_dir)
    is_package = module is not None and _module_file(module, root).name == "__init__.py"
    found = set()
    for node in _statements(source):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                if module is None:
                    raise ValueError(f"module = None with a relative import (level {node.level}); "
                                     f"allowed: the dotted name of the importing module")
                base = [PACKAGE, *module.split(".")]
                base = base if is_package else base[:-1]
                base = base[: len(base) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            targets = [target] + [f"{target}.{a.name}" for a in node.names]
            if target == PACKAGE:
                exports = _exports(root)
                targets += [f"{PACKAGE}.{exports[a.name]}" for a in node.names if a.name in exports]
        else:
            targets = [a.name for a in node.names]
        for t in targets:
            parts = t.split(".")
            if parts[0] != PACKAGE:
                continue
            for i in range(2, len(parts) + 1):       # importing a.b.c runs a.b first
                name = ".".join(parts[1:i])
                if _module_file(name, root) is not None:
                    found.add(name)
    return found


@functools.lru_cache(maxsize=None)
def _module_imports(name: str, package_dir: Path) -> frozenset:
    return frozenset(imported_modules(_module_file(name, package_dir).read_text(encoding="utf-8"), name,
                                      package_dir))


def closure(entries: Iterable[str] = (), source: str | None = None,
            package_dir: Path | str | None = None) -> frozenset:
    """Every isoslide module that importing ``entries`` (and running ``source``) runs.

    Parameters
    ----------
    entries : iterable of str
        Module names relative to the package (``"sweep"``, ``"studies.storeys"``).
    source : str, optional
        Further code whose isoslide imports count too (a script, a notebook's code).
    package_dir : path, optional
        The package directory; default :data:`PACKAGE_DIR`.

    Returns
    -------
    frozenset of str
        Module names, the entries included (a subpackage by its ``__init__``'s name, ``"peers"``).

    Raises
    ------
    ValueError
        If an entry is not a module of the package.
    """
    if isinstance(entries, str):
        raise TypeError(f"entries must be a collection of module names, not the string {entries!r}")
    root = _root(package_dir)
    entries = list(entries)
    missing = [e for e in entries if _module_file(e, root) is None]
    if missing:
        raise ValueError(f"entries = {missing!r} are not modules of isoslide under {root}; "
                         f"allowed: dotted names relative to the package, e.g. 'solver' or 'peers.reference'")
    todo = set()
    for e in entries:       # importing a.b runs a first
        parts = e.split(".")
        todo |= {".".join(parts[:i]) for i in range(1, len(parts) + 1)}
    if source is not None:
        todo |= imported_modules(source, None, root)
    seen: set[str] = set()
    while todo:
        name = todo.pop()
        if name in seen:
            continue
        seen.add(name)
        todo |= _module_imports(name, root) - seen
    return frozenset(seen)


def _package_files(directory: Path) -> set[Path]:
    return {p for p in directory.rglob("*.py")
            if not any(part == "__pycache__" or part.startswith(".") for part in p.relative_to(directory).parts[:-1])}


def files_of(modules: Iterable[str], package_dir: Path | str | None = None) -> set[Path]:
    """The files of a closure (each module's own file; a subpackage's ``__init__.py``)."""
    root = _root(package_dir)
    return {_module_file(m, root) for m in modules}


def module_names(modules: Iterable[str], package_dir: Path | str | None = None) -> list[str]:
    """A closure as the sorted names :func:`isoslide.store.provenance.code_hash` takes for the same files.

    A subpackage every file of which is in the closure is named by itself (``"peers"``: all of
    its files); otherwise each file is named, its ``__init__`` as ``"<subpackage>.__init__"``.
    """
    root = _root(package_dir)
    files = files_of(modules, root)
    names = set()
    covered: set[Path] = set()
    packages = sorted((f.parent for f in files if f.name == "__init__.py" and f.parent != root),
                      key=lambda p: len(p.parts))
    for pkg in packages:
        if pkg / "__init__.py" in covered:
            continue
        members = _package_files(pkg)
        if members <= files:
            names.add(pkg.relative_to(root).as_posix().replace("/", "."))
            covered |= members
    for f in files - covered:
        rel = f.relative_to(root).with_suffix("").as_posix().replace("/", ".")
        names.add(rel)
    return sorted(names)
