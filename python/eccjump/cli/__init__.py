"""The ``eccjump`` command line: one module per subcommand, each with ``add_parser(sub)``.

Angles are in degrees on the command line (radians in the Python API). Every failure is one
line on stderr and a non-zero exit status, never a traceback: 2 for a bad option (argparse's
or the library's ValueError/TypeError), 1 for a file that cannot be written or read (every
OSError, and a failed netCDF write, names the option and the path) or memory that runs out,
130 for Ctrl-C.
"""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Sequence
from pathlib import Path

from eccjump import __version__
from eccjump.cli import (
    analyze,
    design,
    explore,
    figures,
    map,
    roll,
    simulate,
    starts,
    track,
    uncertainty,
)
from eccjump.cli._args import Parser, one_line, short_text
from eccjump.cli._output import OutputError

#: The subcommands, in the order of ``eccjump --help``.
SUBCOMMANDS = (roll, simulate, map, starts, design, uncertainty, figures, track, analyze, explore)


def build_parser() -> Parser:
    parser = Parser(
        prog="eccjump",
        description="Dynamics of an eccentric cylinder on a ramp: lift-off, slip, JARM regions.",
    )
    parser.add_argument("--version", action="version", version=f"eccjump {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)  # of the class Parser too
    for module in SUBCOMMANDS:
        module.add_parser(sub)
    return parser


def _fail(message: object, code: int) -> int:
    print(one_line(f"eccjump: error: {message}"), file=sys.stderr)
    return code


def _file_error(args: argparse.Namespace, err: OSError) -> str:
    """An OSError outside the writes (:func:`~eccjump.cli._output.writing`) in one line: the
    option whose path it names (the path itself or a file under it), the path, the reason."""
    name = err.filename if err.filename is not None else err.filename2
    why = err.strerror or str(err) or type(err).__name__
    if name is None:
        return why
    where = Path(os.fsdecode(name))
    option = next(
        (
            "--" + dest.replace("_", "-")
            for dest, value in vars(args).items()
            if isinstance(value, str | os.PathLike)
            and os.fspath(value)
            and Path(value) in (where, *where.parents)
        ),
        None,
    )
    shown = f"{short_text(str(where), 60)!r}: {why}"
    return f"{option} {shown}" if option else shown


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``eccjump`` console script."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.func(args))
    except (ValueError, TypeError) as err:
        return _fail(err, 2)
    except (OutputError, MemoryError) as err:
        return _fail(str(err) or "out of memory", 1)
    except OSError as err:  # a file the command could not reach, whatever the subcommand
        return _fail(_file_error(args, err), 1)
    except ImportError as err:  # an optional extra (matplotlib, xarray) is missing
        return _fail(err, 1)
    except KeyboardInterrupt:
        print("eccjump: aborted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # e.g. `eccjump roll ... | head`
        sys.stderr.close()
        return 0


if __name__ == "__main__":
    sys.exit(main())
