"""Reading a file the user names: the one guard every reader of a user's file goes through
(the track of ``eccjump.analyze``, a design sheet, a video for ``eccjump.track``).

Refused before a byte is read, with a ``ValueError`` naming the parameter:

* anything but a regular file. A FIFO or a terminal would block the read for ever, a device
  such as ``/dev/zero`` never ends, a directory or a socket holds no text. The path is
  stat'ed first; it is then opened with ``O_NONBLOCK`` (a FIFO swapped in after the stat
  cannot block the open) and the open file is fstat'ed again: what is read is what was
  checked;
* a file larger than :data:`MAX_BYTES` (a video: :data:`MAX_VIDEO_BYTES`), from its size,
  so that a sparse 1 TB file is refused at once. The read stops at ``MAX_BYTES + 1`` bytes
  anyway (a file that grows meanwhile).

``-`` is the standard input where the caller allows it, read with the same bound.

Text is UTF-8, or UTF-16/UTF-32 with a byte-order mark; a UTF-8 byte-order mark is dropped.
"""

from __future__ import annotations

import codecs
import os
import stat
import sys
from collections.abc import Callable
from typing import Any, BinaryIO, TypeVar

from eccjump._base.checks import path as path_arg

T = TypeVar("T")

#: The largest file read [bytes]: 64 MiB, the most frames of a track (10^4) even in a wide
#: Tracker export many times over (docs/limits.md). A design sheet is a few kilobytes.
MAX_BYTES = 64 * 2**20

#: The largest video read [bytes]: 8 GiB, a few minutes of a phone's 4K film. Its frames are
#: streamed, never held: what bounds the work is the frame count (``eccjump.track``).
MAX_VIDEO_BYTES = 8 * 2**30

#: Opens that cannot block on a FIFO swapped in after the stat (POSIX; 0 where there is none).
_NONBLOCK = getattr(os, "O_NONBLOCK", 0)

#: The byte-order marks read, the longest first (UTF-32-LE's starts like UTF-16-LE's).
_BOMS = (
    (codecs.BOM_UTF32_LE, "utf-32"),
    (codecs.BOM_UTF32_BE, "utf-32"),
    (codecs.BOM_UTF8, "utf-8-sig"),
    (codecs.BOM_UTF16_LE, "utf-16"),
    (codecs.BOM_UTF16_BE, "utf-16"),
)


def _shown(source: object) -> str:
    """A path for a message: its end, which names the file, cut to 60 characters, with
    "?" for what cannot be printed."""
    text = os.fspath(source) if isinstance(source, str | os.PathLike) else repr(source)
    text = "".join(c if c.isprintable() else "?" for c in str(text))  # one printable line
    return text if len(text) <= 60 else "..." + text[-57:]


def _kind(mode: int) -> str:
    for test, what in (
        (stat.S_ISFIFO, "a FIFO"),
        (stat.S_ISCHR, "a character device"),
        (stat.S_ISBLK, "a block device"),
        (stat.S_ISDIR, "a directory"),
        (stat.S_ISSOCK, "a socket"),
    ):
        if test(mode):
            return what
    return "not a regular file"


def _check_stat(name: str, source: object, st: os.stat_result, max_bytes: int = MAX_BYTES) -> None:
    if not stat.S_ISREG(st.st_mode):
        raise ValueError(f"{name}: {_shown(source)} is {_kind(st.st_mode)}, not a regular file")
    if st.st_size > max_bytes:
        raise ValueError(
            f"{name}: {_shown(source)} has {st.st_size:,} bytes, more than the "
            f"{max_bytes // 2**20:,} MiB allowed"
        )


def _read_bounded(name: str, source: object, read: Callable[[int], bytes]) -> bytes:
    """At most MAX_BYTES by ``read(n)``; ValueError if there is more."""
    chunks: list[bytes] = []
    size = 0
    while size <= MAX_BYTES:
        chunk = read(min(2**20, MAX_BYTES + 1 - size))
        if not chunk:
            return b"".join(chunks)
        chunks.append(chunk)
        size += len(chunk)
    raise ValueError(f"{name}: {_shown(source)} has more than the {MAX_BYTES // 2**20} MiB allowed")


def read_bytes(name: str, source: object, *, stdin: bool = False) -> bytes:
    """The bytes of the user's file ``source`` (a str or os.PathLike path; ``"-"`` is the
    standard input if ``stdin``), guarded as the module says; ``name`` is the parameter that
    messages name. An unreadable file is a ValueError too, naming it and saying why."""
    source = path_arg(name, source)
    if stdin and source == "-":
        return _read_stdin(name)
    _check_stat(name, source, _os_call(name, source, os.stat, source))
    fd = _os_call(name, source, os.open, source, os.O_RDONLY | _NONBLOCK)
    try:
        _check_stat(name, source, _os_call(name, source, os.fstat, fd))
        if _NONBLOCK:
            _os_call(name, source, os.set_blocking, fd, True)  # a regular file: reads never wait
        return _read_bounded(name, source, lambda n: _os_call(name, source, os.read, fd, n))
    finally:
        os.close(fd)


def open_binary(name: str, source: object, *, max_bytes: int = MAX_VIDEO_BYTES) -> BinaryIO:
    """The user's file ``source`` open for reading bytes (a seekable file object the caller
    closes), guarded as the module says with the size bound ``max_bytes``: for readers that
    stream a large file (a video) rather than read it whole."""
    source = path_arg(name, source)
    _check_stat(name, source, _os_call(name, source, os.stat, source), max_bytes)
    fd = _os_call(name, source, os.open, source, os.O_RDONLY | _NONBLOCK)
    try:
        _check_stat(name, source, _os_call(name, source, os.fstat, fd), max_bytes)
        if _NONBLOCK:
            _os_call(name, source, os.set_blocking, fd, True)
        return os.fdopen(fd, "rb")
    except BaseException:
        os.close(fd)
        raise


def _os_call(name: str, source: object, fn: Callable[..., T], *args: Any) -> T:
    """``fn(*args)``, its OSError (and os.stat's ValueError for a NUL in a path) as a
    ValueError naming ``name`` and the file."""
    try:
        return fn(*args)
    except OSError as err:
        raise ValueError(f"{name}: cannot read {_shown(source)}: {err.strerror}") from None
    except ValueError as err:  # "embedded null byte"
        raise ValueError(f"{name}: {_shown(source)} is no path: {err}") from None


def _read_stdin(name: str) -> bytes:
    stream = getattr(sys.stdin, "buffer", None)
    if stream is None:
        raise ValueError(f"{name}: '-' names the standard input, and there is none here")
    try:
        return _read_bounded(name, "standard input", stream.read)
    except OSError as err:
        raise ValueError(f"{name}: cannot read the standard input: {err.strerror}") from None


def read_text(name: str, source: object, *, stdin: bool = False) -> str:
    """The text of the user's file (:func:`read_bytes`): UTF-8, or the encoding its
    byte-order mark names (UTF-8, UTF-16, UTF-32); ValueError naming ``name`` if it is not
    text in one of them."""
    data = read_bytes(name, source, stdin=stdin)
    encoding = next((enc for bom, enc in _BOMS if data.startswith(bom)), "utf-8")
    try:
        return data.decode(encoding)
    except UnicodeDecodeError as err:
        raise ValueError(
            f"{name}: {_shown(source)} is not {encoding.upper()} text (byte {err.start})"
        ) from None
