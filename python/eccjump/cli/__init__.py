"""The ``eccjump`` command line: one module per subcommand, each with ``add_parser(sub)``.

Angles are in degrees on the command line (radians in the Python API).
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from eccjump.cli import design, figures, map, roll, simulate, starts

#: The subcommands, in the order of ``eccjump --help``.
SUBCOMMANDS = (roll, simulate, map, starts, design, figures)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="eccjump",
        description="Dynamics of an eccentric cylinder on a ramp: lift-off, slip, JARM regions.",
    )
    sub = parser.add_subparsers(dest="command", required=True)
    for module in SUBCOMMANDS:
        module.add_parser(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``eccjump`` console script."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.func(args))
    except ValueError as err:
        print(f"eccjump: error: {err}", file=sys.stderr)
        return 2
    except BrokenPipeError:  # e.g. `eccjump roll ... | head`
        sys.stderr.close()
        return 0


if __name__ == "__main__":
    sys.exit(main())
