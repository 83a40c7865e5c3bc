"""Building result records fast: a run of a few microseconds should not spend as long again
in Python making the objects that hold it.

A frozen dataclass's ``__init__`` calls ``object.__setattr__`` once per field, and a
NamedTuple's ``__new__`` is a Python function; both cost more than the short runs of
:func:`eccjump.roll` and :func:`eccjump.simulate` themselves. The results are the same
objects, only made without those calls.
"""

from __future__ import annotations

from functools import partial
from typing import Any, TypeVar

T = TypeVar("T")


def frozen(cls: type[T], values: dict[str, Any]) -> T:
    """An instance of the frozen dataclass ``cls`` whose ``__dict__`` is ``values``, which
    must hold every field of ``cls`` in its declaration order (the tests check each result
    type against :func:`dataclasses.fields`)."""
    result = object.__new__(cls)
    object.__setattr__(result, "__dict__", values)
    return result


def records(cls: type[T]) -> partial[T]:
    """A function making the NamedTuple ``cls`` from one tuple of its fields:
    ``tuple.__new__`` itself, at half the cost of ``cls(*fields)``."""
    return partial(tuple.__new__, cls)
