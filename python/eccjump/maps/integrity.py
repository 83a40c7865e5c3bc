"""The one integrity policy of the map files: damage is found by the formats' own checksums,
never read as other numbers.

- ``.npz``: each member of the zip archive carries its CRC-32, which numpy's reading checks
  (a damaged member is a ``BadZipFile``, refused); nothing to add.
- ``.nc``: every numeric variable is written with HDF5's Fletcher-32 checksum
  (:func:`netcdf_encoding`), which the library checks on reading (in the probe child of
  :func:`eccjump.store.probe_netcdf`).
- ``.zarr``: every array is written with the crc32c codec after zstd (:func:`zarr_codecs`),
  and every chunk is stored, even one of fill values: a missing chunk is damage
  (:func:`check_zarr`), except a field's chunk of α slices not marked done (an
  interrupted map) and a chunk of ``alpha_done`` (read as not done: a resume computes it
  again). The metadata files are bounded in size before they are read
  (:data:`METADATA_BYTES`).

A file written before checksums (.nc and .zarr maps of earlier 0.2 builds) is still loaded,
with an :class:`UncheckedMapWarning` saying that its damage cannot be found (the chunks of
fill values its writer left out read as the fill value, as they always did); saving it
again adds them. The values themselves are checked against their physical ranges by
:mod:`eccjump.maps.check`, whatever the format.
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import numpy as np

from eccjump._base.checks import shown
from eccjump.maps.check import Invalid

#: Most bytes of a zarr metadata file (``zarr.json``): an eccjump map's are a few kB, its
#: consolidated metadata some 100 kB.
METADATA_BYTES = 16 * 2**20


class UncheckedMapWarning(UserWarning):
    """A map file without checksums (written before they were): damage to it cannot be told
    from data."""


def zarr_codecs() -> tuple[Any, ...]:
    """The bytes-to-bytes codecs of every array of a zarr map: zstd, then the crc32c checksum
    of the compressed chunk."""
    from zarr.codecs import Crc32cCodec, ZstdCodec

    return (ZstdCodec(level=0), Crc32cCodec())


def netcdf_encoding(variables: Iterable[tuple[Any, Any]]) -> dict[Any, dict[str, Any]]:
    """The netCDF encoding of ``variables`` (name, array pairs): Fletcher-32 on each numeric
    one (HDF5 has no filters on strings: the names of ``wrt`` are checked by their values)."""
    return {name: {"fletcher32": True} for name, v in variables if v.dtype.kind in "biuf"}


def check_metadata_size(path: str | os.PathLike) -> None:
    """:class:`Invalid` naming the metadata file of the zarr store ``path`` (its own, or one
    of an array in it) that is larger than :data:`METADATA_BYTES`, before any is read: a
    sparse 1 TB ``zarr.json`` would fill the memory."""
    root = Path(path)
    files = [root / "zarr.json"]
    try:
        files += [e / "zarr.json" for e in root.iterdir() if e.is_dir() and not e.is_symlink()]
    except OSError:
        return  # the reader says what is wrong
    for meta in files:
        try:
            size = meta.stat().st_size
        except OSError:
            continue
        if size > METADATA_BYTES:
            raise Invalid(
                f"has a metadata file {meta.relative_to(root)} of {size:,} bytes; it is read "
                f"only up to {METADATA_BYTES // 2**20} MiB"
            )


def check_zarr(path: str | os.PathLike, group: Any) -> None:
    """:class:`Invalid` if a chunk of the zarr map ``group`` (opened from ``path``) is
    missing; an :class:`UncheckedMapWarning` if an array has no checksum (then its missing
    chunks read as its fill value, as they were written)."""
    arrays = dict(group.arrays())
    done = np.asarray(arrays["alpha_done"][:], dtype=bool) if "alpha_done" in arrays else None
    unchecked = [name for name, arr in arrays.items() if not _checksummed(arr)]
    for name, arr in arrays.items():
        if name == "alpha_done" or name in unchecked:
            # alpha_done: a missing chunk reads as not done, computed again on resume; the
            # writers of maps without checksums did not store chunks of fill values
            continue
        along_alpha = (arr.metadata.dimension_names or ("",))[0] == "alpha"
        step = arr.chunks[0] if arr.ndim else 1
        for index in np.ndindex(*arr.cdata_shape):
            rows = slice(index[0] * step, (index[0] + 1) * step) if index else slice(0)
            if done is not None and along_alpha and not done[rows].all():
                continue  # not computed yet: no chunk written
            key = arr.metadata.encode_chunk_key(index)
            if not (Path(path) / name / key).is_file():
                raise Invalid(f"is a damaged map: the chunk {name}/{key} is missing")
    if unchecked:
        warn_unchecked(path, unchecked[0])


def _checksummed(arr: Any) -> bool:
    """Whether the chunks of the zarr array ``arr`` carry a checksum: crc32c, or zstd's own
    (the fields of a ``eccjump map`` store before crc32c)."""
    for codec in arr.metadata.codecs:
        spec = codec.to_dict()
        if spec["name"] == "crc32c" or (
            spec["name"] == "zstd" and spec.get("configuration", {}).get("checksum")
        ):
            return True
    return False


def check_netcdf(path: str | os.PathLike, ds: Any) -> None:
    """An :class:`UncheckedMapWarning` if a numeric variable of the netCDF map ``ds`` has no
    Fletcher-32 checksum (the library checks those it has when it reads them)."""
    for name, var in ds.variables.items():
        if var.dtype.kind in "biuf" and not var.encoding.get("fletcher32"):
            warn_unchecked(path, name)
            return


def warn_unchecked(path: str | os.PathLike, name: str) -> None:
    warnings.warn(
        f"{shown(path)} has no checksums (an older eccjump wrote it): damage to {name[:30]} "
        "cannot be found; save it again to add them",
        UncheckedMapWarning,
        stacklevel=4,
    )
