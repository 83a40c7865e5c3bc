"""A result's fields as a tree of JSON values plus named numpy arrays, and back, bit for bit:
the one encoding behind every result file (:mod:`eccjump.maps.results`).

The tree holds ``None``, booleans, integers, floats (NaN and infinities as Python's ``json``
writes them) and text as they are; an array or numpy scalar as ``{"__array__": key}`` (the
array itself goes into ``arrays`` under ``key``, the path of its field); a tuple as
``{"__tuple__": [...]}``; a dict (text keys) as ``{"__dict__": {...}}``; a dataclass or named
tuple of eccjump as ``{"__record__": "module:Class", "fields": {...}}`` (its ``__init__``
fields). A record is read back only as a class of an eccjump module already imported (never
by importing a module a file names), and only a dataclass or a named tuple.
"""

from __future__ import annotations

import dataclasses
import sys
from collections.abc import Mapping
from typing import Any

import numpy as np


def encode(value: Any, arrays: dict[str, np.ndarray], key: str, unsaved: tuple = ()) -> Any:
    """The tree of ``value``, its arrays added to ``arrays`` under paths starting at ``key``;
    ``unsaved`` names fields of ``value`` stored as None (a dense solution). TypeError naming
    the path for a value that has no encoding."""
    if value is None or isinstance(value, bool | int | float | str):
        return value
    if isinstance(value, np.generic) or hasattr(value, "__array__"):
        return _encode_array(value, arrays, key)
    if dataclasses.is_dataclass(value) or hasattr(value, "_fields"):
        return _encode_record(value, arrays, key, unsaved)
    if isinstance(value, tuple | list):
        items = [encode(v, arrays, f"{key}.{i}") for i, v in enumerate(value)]
        return {"__tuple__": items} if isinstance(value, tuple) else items
    if isinstance(value, dict) and all(isinstance(k, str) for k in value):
        return {"__dict__": {k: encode(v, arrays, f"{key}.{k}") for k, v in value.items()}}
    raise TypeError(f"{key}: a {type(value).__name__} cannot be saved")


def _encode_array(value: Any, arrays: dict[str, np.ndarray], key: str) -> dict[str, Any]:
    a = np.asarray(value)  # (a dask array is computed here)
    if a.dtype.kind not in "biuf":
        raise TypeError(f"{key}: an array of dtype {a.dtype} cannot be saved")
    arrays[key] = a
    return (
        {"__array__": key, "scalar": True} if isinstance(value, np.generic) else {"__array__": key}
    )


def _encode_record(value: Any, arrays: dict[str, np.ndarray], key: str, unsaved: tuple) -> Any:
    cls = type(value)
    if not cls.__module__.startswith("eccjump."):
        raise TypeError(f"{key}: a {cls.__name__} cannot be saved")
    names = _field_names(cls)
    skip = set(unsaved) | set(getattr(cls, "_unsaved", ()))
    fields = {
        n: None if n in skip else encode(getattr(value, n), arrays, _join(key, n)) for n in names
    }
    return {"__record__": f"{cls.__module__}:{cls.__qualname__}", "fields": fields}


def _join(key: str, name: str) -> str:
    return f"{key}.{name}" if key else name


def _field_names(cls: type) -> tuple[str, ...]:
    if dataclasses.is_dataclass(cls):
        return tuple(f.name for f in dataclasses.fields(cls) if f.init)
    return tuple(cls._fields)  # type: ignore[attr-defined]


def decode(tree: Any, arrays: Mapping[str, np.ndarray]) -> Any:
    """The value of a tree of :func:`encode`. KeyError, TypeError or ValueError for a tree
    that no value gives (a damaged or foreign file: the reader names it)."""
    if tree is None or isinstance(tree, bool | int | float | str):
        return tree
    if isinstance(tree, list):
        return [decode(v, arrays) for v in tree]
    if not isinstance(tree, dict):
        raise TypeError(f"no value is encoded as a {type(tree).__name__}")
    if "__array__" in tree:
        a = np.asarray(arrays[tree["__array__"]])
        return a[()] if tree.get("scalar") else a
    if "__tuple__" in tree:
        return tuple(decode(v, arrays) for v in tree["__tuple__"])
    if "__dict__" in tree:
        return {str(k): decode(v, arrays) for k, v in dict(tree["__dict__"]).items()}
    cls = record_class(tree["__record__"])
    return cls(**{str(k): decode(v, arrays) for k, v in dict(tree["fields"]).items()})


def record_class(name: object) -> type:
    """The dataclass or named tuple ``"module:Class"`` of an imported eccjump module."""
    module, _, qualname = str(name).partition(":")
    found = (
        getattr(sys.modules.get(module), qualname, None) if module.startswith("eccjump.") else None
    )
    if not isinstance(found, type) or not (
        dataclasses.is_dataclass(found) or hasattr(found, "_fields")
    ):
        raise ValueError(f"no result record is called {str(name)[:60]!r}")
    return found
