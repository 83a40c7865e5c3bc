"""Building result objects fast: a run of a few microseconds should not spend as long again
in Python making the objects that hold it.

A frozen dataclass's ``__init__`` calls ``object.__setattr__`` once per field, which costs
more than the short runs of :func:`eccjump.roll` and :func:`eccjump.simulate` themselves.
The results are the same objects, only made without those calls. (Their records, the
NamedTuples, come from the bridge ready made: ``rust/eccjump-py/src/records.rs``.)
"""

from __future__ import annotations

from typing import Any, TypeVar

T = TypeVar("T")


def frozen(cls: type[T], values: dict[str, Any]) -> T:
    """An instance of the frozen dataclass ``cls`` whose ``__dict__`` is ``values``, which
    must hold every field of ``cls`` in its declaration order (the tests check each result
    type against :func:`dataclasses.fields`)."""
    result = object.__new__(cls)
    object.__setattr__(result, "__dict__", values)
    return result
