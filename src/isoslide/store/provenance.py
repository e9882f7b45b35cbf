"""Where a result comes from: the package version and git commit, hashes of the code, job logs.

* :func:`source_text` (with :func:`git_commit`) is the ``source`` attribute of every dataset;
* :func:`code_hash` hashes the source files of named modules of the package; the workflow passes
  it as a rule parameter, so that editing the modules a rule runs reruns that rule's jobs and
  nothing else (Snakemake's own ``code`` trigger only sees the rule's script);
* :func:`log_to` sends a pipeline job's :mod:`logging` records (and its traceback, if it fails)
  to the job's log file.

Module names are relative to the package, with dots for subpackages: ``"solver"``,
``"peers.reference"``, or ``"records"`` for every file of the subpackage ``isoslide.records``
(or for the module ``records.py``, whichever the package holds).
"""

from __future__ import annotations

import contextlib
import functools
import hashlib
import logging
import subprocess
from collections.abc import Iterable
from pathlib import Path

from .. import __version__
from ..budget import seconds_since_process_start

PACKAGE_DIR = Path(__file__).resolve().parents[1]
"""The directory of the installed ``isoslide`` package."""


@functools.lru_cache(maxsize=1)
def git_commit() -> str:
    """Git commit of the isoslide source tree, ``"+dirty"`` if the package differs from it.

    ``"unknown"`` when the package is not in a git checkout (e.g. a wheel).
    """
    pkg = PACKAGE_DIR
    try:
        sha = subprocess.run(["git", "-C", str(pkg), "rev-parse", "HEAD"], capture_output=True,
                             text=True, timeout=10, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(pkg), "diff", "--quiet", "HEAD", "--", "."],
                               capture_output=True, timeout=10).returncode != 0
    except (OSError, subprocess.SubprocessError):
        return "unknown"
    return sha + ("+dirty" if dirty else "")


def source_text() -> str:
    """``source`` attribute: package version and git commit."""
    return f"isoslide {__version__} (git {git_commit()}), exact event-driven stick-slip solver"


def _python_files(directory: Path) -> list[Path]:
    """Every ``.py`` file below ``directory`` (caches and hidden directories left out)."""
    return sorted(p for p in directory.rglob("*.py")
                  if not any(part == "__pycache__" or part.startswith(".")
                             for part in p.relative_to(directory).parts[:-1]))


def module_files(name: str, package_dir: Path | str | None = None) -> list[Path]:
    """Source files of the module or subpackage ``name`` of the package.

    Parameters
    ----------
    name : str
        Dotted name relative to the package: ``"solver"``, ``"peers.reference"``, ``"records"``.
        A subpackage stands for all of its files (what Python imports when both a subpackage and
        a module of that name exist).
    package_dir : path, optional
        The package directory; default :data:`PACKAGE_DIR`.

    Raises
    ------
    ValueError
        If the package has no such module or subpackage.
    """
    root = PACKAGE_DIR if package_dir is None else Path(package_dir)
    parts = name.split(".")
    if not name or not all(part.isidentifier() for part in parts):
        raise ValueError(f"{name!r} is not a module name of isoslide (use e.g. 'solver' or 'peers.reference')")
    base = root.joinpath(*parts)
    if (base / "__init__.py").is_file():
        return _python_files(base)
    module = base.with_name(parts[-1] + ".py")
    if module.is_file():
        return [module]
    raise ValueError(f"isoslide has no module {name!r}: neither {module} nor {base / '__init__.py'} "
                     f"exists (renamed or moved? update the module list that names it)")


def code_hash(include: Iterable[str] | None = None, exclude: Iterable[str] = (),
              package_dir: Path | str | None = None) -> str:
    """SHA-256 (first 16 hex digits) of the source of isoslide's modules.

    Each file enters with its path relative to the package, so moving code between modules
    changes the hash, and the same files give the same hash wherever the package is installed.

    Parameters
    ----------
    include : iterable of str, optional
        Module or subpackage names (see :func:`module_files`); default: every file of the package.
    exclude : iterable of str
        Module or subpackage names to leave out.
    package_dir : path, optional
        The package directory; default :data:`PACKAGE_DIR`.

    Raises
    ------
    ValueError
        If a name in ``include`` or ``exclude`` is not a module or subpackage of the package.
    """
    root = PACKAGE_DIR if package_dir is None else Path(package_dir)
    if include is None:
        files = set(_python_files(root))
    else:
        if isinstance(include, str):
            raise TypeError(f"include must be a collection of module names, not the string {include!r}")
        files = {f for name in include for f in module_files(name, root)}
    if isinstance(exclude, str):
        raise TypeError(f"exclude must be a collection of module names, not the string {exclude!r}")
    files -= {f for name in exclude for f in module_files(name, root)}
    h = hashlib.sha256()
    for f in sorted(files, key=lambda p: p.relative_to(root).as_posix()):
        h.update(f.relative_to(root).as_posix().encode() + b"\0" + f.read_bytes() + b"\0")
    return h.hexdigest()[:16]


@contextlib.contextmanager
def log_to(path, level: int = logging.INFO):
    """Send the :mod:`logging` records of a pipeline job to the log file ``path``.

    The file starts with :func:`source_text` and the job's start-up time (interpreter and imports,
    as phase ``start-up``, see :mod:`isoslide.budget`); warnings are logged too; if the block raises, the
    traceback is logged before the exception propagates; a successful block ends with ``done``.
    The handler is removed on exit.  Yields the logger ``isoslide.job``.

    Parameters
    ----------
    path : path
        The log file (overwritten; its directory is created).
    level : int
        Lowest level written (default ``logging.INFO``).
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    handler = logging.FileHandler(path, mode="w", encoding="utf-8")
    handler.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(name)s: %(message)s"))
    handler.setLevel(level)
    root = logging.getLogger()
    old_level = root.level
    root.addHandler(handler)
    if old_level == logging.NOTSET or old_level > level:
        root.setLevel(level)
    logging.captureWarnings(True)
    job = logging.getLogger("isoslide.job")
    try:
        job.info("%s", source_text())
        startup = seconds_since_process_start()
        if startup is not None:
            job.info("phase start-up %.3f s", startup)
        try:
            yield job
        except BaseException:
            job.exception("failed")
            raise
        job.info("done")
    finally:
        logging.captureWarnings(False)
        root.removeHandler(handler)
        root.setLevel(old_level)
        handler.close()
