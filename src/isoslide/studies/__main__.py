"""``python -m isoslide.studies [--write PROFILE]``: the SLURM groups of the study registry.

Prints ``groups:`` with one ``rule: group`` line per batched rule of
:func:`isoslide.studies.registry.slurm_groups`; with ``--write PROFILE`` it replaces the ``groups:``
block of that Snakemake profile (``profiles/slurm/config.yaml``) with them instead, leaving every other
line as it is.  Exit code 1 with ``--check PROFILE`` when the profile's block differs.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from .registry import slurm_groups

HEADER = "groups:"
COMMENT = "  # rule: group, written from the study registry by `python -m isoslide.studies --write <this file>`"


def groups_block(groups: dict | None = None) -> list[str]:
    """The lines of the ``groups:`` block (default: the registry's groups)."""
    groups = slurm_groups() if groups is None else groups
    return [HEADER, COMMENT] + [f"  {rule}: {group}" for rule, group in groups.items()]


def replace_block(text: str, block: list[str]) -> str:
    """A profile's text with its ``groups:`` block replaced by ``block``.

    The block is the ``groups:`` line and the indented lines after it.

    Raises
    ------
    ValueError
        If the profile has no top-level ``groups:`` line.
    """
    lines = text.splitlines()
    if HEADER not in lines:
        raise ValueError(f"profile text has no line {HEADER!r}; allowed: a profile with a top-level groups block")
    start = lines.index(HEADER)
    end = start + 1
    while end < len(lines) and (lines[end].startswith(" ") or not lines[end].strip()):
        end += 1
    while end > start + 1 and not lines[end - 1].strip():   # keep blank lines after the block
        end -= 1
    return "\n".join(lines[:start] + block + lines[end:]) + "\n"


def main(argv: list[str] | None = None) -> int:
    """Command line: print, write (``--write``) or check (``--check``) the groups block; the exit code."""
    parser = argparse.ArgumentParser(prog="python -m isoslide.studies", description=__doc__.splitlines()[0])
    action = parser.add_mutually_exclusive_group()
    action.add_argument("--write", metavar="PROFILE", help="replace the groups block of this profile file")
    action.add_argument("--check", metavar="PROFILE", help="exit 1 if this profile's groups block differs")
    args = parser.parse_args(argv)
    block = groups_block()
    if args.write or args.check:
        path = Path(args.write or args.check)
        text = path.read_text(encoding="utf-8")
        new = replace_block(text, block)
        if args.check:
            if new != text:
                print(f"{path}: the groups block differs from the study registry; "
                      f"run python -m isoslide.studies --write {path}", file=sys.stderr)
                return 1
            return 0
        path.write_text(new, encoding="utf-8")
        return 0
    print("\n".join(block))
    return 0


if __name__ == "__main__":
    sys.exit(main())
