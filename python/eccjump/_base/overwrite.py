"""The one overwrite policy of eccjump's writers (maps, and any other file a writer replaces):
what may be at a path a writer is about to replace.

- Nothing, or a dangling symbolic link (only the link is replaced): written.
- A regular file: replaced by a writer of files if it is one of the writer's own (``ours``,
  recognised by its content, never by its name) or if the caller said so (``overwrite``).
- A directory: replaced only by a writer of directories (a zarr map), and only if it is one
  of the writer's own: not even ``overwrite`` removes a tree of the user's files.
- Anything else (a FIFO, a socket, a device), or a file where a directory would go and the
  reverse: never replaced.

A refusal is an :class:`ExistsError` (both a ``FileExistsError`` and a ``ValueError``) naming
the path and, where it would help, the option that allows the replacement. The replacement
itself is the writer's: under a temporary sibling name, then renamed into place
(:func:`eccjump.store.install`), so that a fault keeps the old file.
"""

from __future__ import annotations

import os
import stat
from collections.abc import Callable
from pathlib import Path

from eccjump._base.checks import file_error


class ExistsError(FileExistsError, ValueError):
    """A path a writer would replace holds what it may not replace."""


def file_type(mode: int) -> str:
    """What ``mode`` (of ``os.stat``) is, in words: "a directory", "a FIFO", ..."""
    kinds = (
        (stat.S_ISDIR, "a directory"),
        (stat.S_ISREG, "a file"),
        (stat.S_ISFIFO, "a FIFO"),
        (stat.S_ISSOCK, "a socket"),
    )
    return next((name for test, name in kinds if test(mode)), "a device")


def check_overwrite(
    path: str | os.PathLike,
    *,
    overwrite: bool,
    option: str,
    ours: Callable[[Path], bool],
    what: str,
    directory: bool = False,
    name: str | None = None,
) -> None:
    """Return if a writer may replace what is at ``path``, else raise :class:`ExistsError`.

    Parameters
    ----------
    path : str or os.PathLike
        Where the writer writes.
    overwrite : bool
        The caller allows replacing a regular file that is not the writer's own.
    option : str
        How the caller allows it, for the message: ``"overwrite=True"``, ``"--overwrite"``.
    ours : callable
        Whether the file or directory at a path is one of the writer's own, by its content.
    what : str
        What the writer's own files are, for the message: ``"a map of eccjump"``.
    directory : bool, default False
        The writer writes a directory (a zarr store), not a file.
    name : str, optional
        The parameter or option that gave ``path`` (``"path"``, ``"--output"``), put before
        the message.
    """
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:  # nothing, or a dangling link: only the link is replaced
        return
    except OSError as err:
        raise file_error(path, f"cannot be replaced: {err.strerror}", ExistsError, name) from None
    if directory and stat.S_ISDIR(mode):
        if ours(Path(path)):
            return
        raise file_error(
            path, f"is a directory that is not {what}: not replaced", ExistsError, name
        )
    if not directory and stat.S_ISREG(mode):
        if overwrite or ours(Path(path)):
            return
        raise file_error(
            path,
            f"exists and is not {what}: not replaced; {option} replaces it",
            ExistsError,
            name,
        )
    want = f"a directory ({what})" if directory else "a file"
    raise file_error(path, f"is {file_type(mode)}, not {want}: not replaced", ExistsError, name)


def never(_: Path) -> bool:
    """``ours`` for a writer whose files are not recognised by content (a result's CSV):
    nothing is replaced without ``overwrite``."""
    return False
