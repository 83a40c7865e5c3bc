"""How often a filtered hypothesis property reaches its assertion: a property that filters
its draws (``assume``) must still test something in most examples, and this measures it
over the property's own strategy."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from hypothesis import given, settings
from hypothesis import strategies as st


def reach_rate(strategy: st.SearchStrategy[Any], reaches: Callable[[Any], bool]) -> float:
    """The share of 100 derandomized draws of ``strategy`` for which ``reaches`` (the
    property's filter) is true."""
    seen: list[bool] = []

    @settings(max_examples=100, database=None, derandomize=True, deadline=None)
    @given(strategy)
    def draw(example: Any) -> None:
        seen.append(bool(reaches(example)))

    draw()
    return sum(seen) / len(seen)
