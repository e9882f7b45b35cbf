"""Files written whole or not at all: a temporary file beside the target, renamed over it.

A reader (another job, numba, a rerun after a kill) sees either the old file or the complete new
one, never a truncated file; on any error the temporary file is removed and the target is
untouched. Standard library only, so the kernel modules can use it at import.
"""
from __future__ import annotations

import os
import tempfile
from contextlib import contextmanager
from pathlib import Path


@contextmanager
def atomic_path(path, suffix: str = ".tmp"):
    """Yield a temporary path in ``path``'s directory; rename it to ``path`` when the block succeeds.

    Parameters
    ----------
    path : str or pathlib.Path
        The file to write (its directory is created if missing).
    suffix : str
        Suffix of the temporary file (e.g. ``".png"`` for writers that look at it).
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=suffix, dir=path.parent)
    os.close(fd)
    try:
        yield tmp
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
