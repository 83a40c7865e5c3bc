"""The optional dependencies (the extras of ``pyproject.toml``): imported when a feature needs
them, never by ``import eccjump``, and missing ones named with the pip command that installs
them -- one helper, :func:`require`, for every extra."""

from __future__ import annotations

import importlib
from types import ModuleType


def require(module: str, *, purpose: str, extra: str) -> ModuleType:
    """Import ``module``, or raise ImportError saying what needs it (``purpose``) and how to
    install it (``pip install eccjump[extra]``)."""
    try:
        return importlib.import_module(module)
    except ImportError as err:
        raise ImportError(
            f"{module} is needed for {purpose}: pip install eccjump[{extra}]"
        ) from err
