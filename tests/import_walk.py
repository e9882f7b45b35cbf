"""The import statements of a source, read with a full parse: the tests' own reading, apart from the package's."""

import ast
import importlib.util


def import_targets(source: str, package: str | None = None):
    """Every import statement of ``source`` with the dotted names it imports.

    Parameters
    ----------
    source : str
        Python source.
    package : str, optional
        The package relative imports are resolved against (``isoslide.studies`` for a module of it);
        without it, relative imports are passed over.

    Yields
    ------
    node, names
        The ``ast.Import`` or ``ast.ImportFrom`` node, and the modules and names it imports
        (``a.b`` and ``a.b.c`` for ``from a.b import c``).
    """
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.ImportFrom):
            if node.level and package is None:
                continue
            mod = importlib.util.resolve_name("." * node.level + (node.module or ""), package) if node.level \
                else node.module or ""
            yield node, [mod] + [f"{mod}.{a.name}" for a in node.names]
        elif isinstance(node, ast.Import):
            yield node, [a.name for a in node.names]
