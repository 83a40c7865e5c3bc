"""What the command line writes besides its tables: figures and animations, through one
checked path (:func:`check_output` before the work, :func:`write_output` after it), and
numbers with a bounded number of digits (:func:`bounded`)."""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Iterable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from eccjump._base.optional import require
from eccjump.cli._args import short_text
from eccjump.maps import store

#: ``--dpi`` of the PNG writers: at 600 dpi a 12 x 9 inch figure is already 150 MB of pixels.
DPI_RANGE = (20, 600)

#: Formats matplotlib hands to pillow (written only if this pillow can save them).
_PILLOW_FORMATS = frozenset({"jpg", "jpeg", "tif", "tiff", "webp", "gif", "avif"})

#: The suffix of an animation (pillow's GIF writer, :func:`eccjump.plot.animate_motion`).
ANIMATION_SUFFIXES = frozenset({".gif"})


class OutputError(Exception):
    """A file could not be written (exit status 1); the message names the option and path."""


def figure_suffixes() -> frozenset[str]:
    """The suffixes ``Figure.savefig`` can write here, e.g. ``.png``, ``.pdf``, ``.svg``.
    Not ``.pgf``: matplotlib runs LaTeX for it, which fails only after the work."""
    canvas = require("matplotlib.backend_bases", purpose="figures", extra="plot")
    image = require("PIL.Image", purpose="figures", extra="plot")
    image.init()
    pillow = {ext for ext, fmt in image.registered_extensions().items() if fmt in image.SAVE}
    return frozenset(
        f".{name}"
        for name in canvas.FigureCanvasBase.get_supported_filetypes()
        if name != "pgf" and (name not in _PILLOW_FORMATS or f".{name}" in pillow)
    )


def _shown(option: str, path: object) -> str:
    return f"{option} {short_text(str(path), 60)!r}"


def _why(err: OSError) -> str:
    return err.strerror or str(err) or type(err).__name__


def _temporary(path: Path) -> Path:
    """Where ``path`` is written before it is renamed into place: the store's temporary
    sibling, with ``path``'s suffix again (matplotlib and pillow choose the format by it)."""
    tmp = store.temp_sibling(path)
    return tmp.with_name(tmp.name + path.suffix)


def check_output(option: str, path: str | os.PathLike, suffixes: Iterable[str]) -> Path:
    """``path`` as a Path if a file can be written there, else ValueError naming ``option``:
    checked before the work, so that a bad path costs nothing. The suffix must be one of
    ``suffixes``; the directory must exist (it is not created), be a directory and be
    writable; the path must not be a directory; the name must leave room for the temporary
    sibling's longer one."""
    text = os.fspath(path)
    if not text or "\0" in text:
        raise ValueError(f"{_shown(option, text)}: give a file name")
    path = Path(text)
    allowed = sorted(suffixes)
    if path.suffix.lower() not in allowed:  # the path is not shown: the list is long
        what = f"the suffix {short_text(path.suffix, 20)!r} is not" if path.suffix else "no suffix:"
        raise ValueError(f"{option}: {what} one of {' '.join(allowed)}")
    try:
        parent = path.absolute().parent
        longest = store.name_room(path, _temporary(path))
        if len(os.fsencode(path.name)) > longest:
            raise ValueError(f"{_shown(option, path)}: the name is longer than {longest} bytes")
        store.check_parent(path)
        if path.is_dir():
            raise ValueError(f"{_shown(option, path)}: is a directory")
        if not os.access(parent, os.W_OK | os.X_OK):
            raise ValueError(f"{_shown(option, path)}: its directory is not writable")
    except OSError as err:
        raise ValueError(f"{_shown(option, path)}: {_why(err)}") from None
    return path


def check_outputs(option: str, paths: Iterable[Path], suffixes: Iterable[str]) -> list[Path]:
    """:func:`check_output` of each path."""
    return [check_output(option, p, suffixes) for p in paths]


@contextmanager
def writing(option: str, path: Path) -> Iterator[None]:
    """The one handler of the command line's writes: an OSError (a full disk, a name too
    long) or the RuntimeError netCDF4 raises for a failed write ("NetCDF: HDF error") inside
    becomes an :class:`OutputError` naming ``option`` and ``path``: one line, exit status 1."""
    try:
        yield
    except (OSError, RuntimeError) as err:
        why = _why(err) if isinstance(err, OSError) else str(err) or type(err).__name__
        raise OutputError(f"{_shown(option, path)}: cannot write it: {why}") from err


def write_output(option: str, path: Path, save: Callable[[Path], object]) -> Path:
    """Write ``path`` (checked by :func:`check_output`) by calling ``save`` on a temporary
    sibling, then renaming it into place: a failure or a Ctrl-C leaves no partial file, and
    a failed write is an :class:`OutputError` naming ``option`` and the path (:func:`writing`)."""
    tmp = _temporary(path)
    try:
        with writing(option, path):
            save(tmp)
            if path.is_dir():  # made while we worked: install would swap it out
                raise IsADirectoryError(21, "is a directory", str(path))
            store.install(tmp, path)
    finally:
        store.remove(tmp)
    return path


def save_figure(option: str, fig: Any, path: Path, dpi: int) -> Path:
    """Write the matplotlib figure ``fig`` to ``path`` by :func:`write_output`, then close it
    (pyplot keeps every figure open until then)."""
    import matplotlib.pyplot as plt

    try:
        return write_output(option, path, lambda tmp: fig.savefig(tmp, dpi=dpi))
    finally:
        plt.close(fig)


def bounded(x: float, spec: str) -> str:
    """``format(x, spec)``, but a fixed-point spec (``"14.8f"``) turns to exponent notation
    from 1e15 on: ``:f`` writes every digit of 1e300."""
    x = float(x)
    if spec.endswith("f") and math.isfinite(x) and abs(x) >= 1e15:
        spec = spec[:-1] + "e"
    return format(x, spec)
