"""The module paths of eccjump before its modules moved into layers (0.2): each old path still
imports, for one release, as the very module at its new path, with a ``DeprecationWarning``
naming the new one. One table (:data:`MOVED`) and one import hook (:class:`_Finder`), installed
by ``eccjump/__init__.py``; the public names (``eccjump.roll``, ``eccjump.store``, ...) never
needed it and do not warn.

The names that left a module of the map layer when it stopped knowing the kinds of map
(``eccjump.maps.Region``, ``eccjump.maps.xarray.region_dataset``, ...) are served likewise,
by the module's ``__getattr__`` and :func:`moved_name`, from one table (:data:`MOVED_NAMES`):
the object at its new place, with a warning naming it. The table names the new places as
text, so the map layer imports nothing above it.

``import eccjump.rolling`` imports ``eccjump.motion.roll`` and registers that same module under
the old name, so ``eccjump.rolling.roll is eccjump.roll``. A module below an old package path
(``eccjump.design.search``) follows its package (``eccjump.studies.design.search``).
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.machinery
import sys
import types
import warnings
from collections.abc import Sequence
from typing import Any

#: Old dotted path -> new dotted path. ``eccjump.motion``, ``eccjump.classification`` and
#: ``eccjump.maps`` need no entry: they are packages now, re-exporting the old module's names.
MOVED: dict[str, str] = {
    f"eccjump.{old}": f"eccjump.{new}"
    for old, new in {
        "_arrays": "_base.arrays",
        "_bridge": "_base.bridge",
        "_checks": "_base.checks",
        "_html": "_base.html",
        "_overwrite": "_base.overwrite",
        "_sizes": "_base.sizes",
        "_userfiles": "_base.userfiles",
        "body": "_base.body",
        "units": "_base.units",
        "_integrity": "maps.integrity",
        "_layout": "maps.layout",
        "_map": "maps.map",
        "_mapcheck": "maps.check",
        "labelled": "maps.xarray",
        "map_kinds": "maps.kinds",
        "scale": "maps.dask",
        "store": "maps.store",
        "_derivatives": "classification.derivatives",
        "boundary": "classification.boundary",
        "closed_form": "classification.closed_form",
        "fields": "classification.fields",
        "starts": "classification.starts",
        "dense": "motion.dense",
        "motion_fields": "motion.fields",
        "motion_maps": "motion.maps",
        "motion_points": "motion.points",
        "rolling": "motion.roll",
        "design": "studies.design",
        "uncertainty": "studies.uncertainty",
        "experiment": "studies.experiment",
        # modules that a function of their package, of the same name, hid (0.2)
        "plot.trajectory": "plot.trajectories",
        "plot.uncertainty": "plot.uncertainty_study",
        "studies.design.build": "studies.design.physical",
        "studies.experiment.reconstruct": "studies.experiment.reconstruction",
    }.items()
}

_FIELDS, _CLASSIFY = "eccjump.classification.fields", "eccjump.classification.classify"
_CLASSIFICATION = "eccjump.classification"

#: Module -> {name that left it: its new place, ``"module"`` (the same name there) or
#: ``"module:name"``}.
MOVED_NAMES: dict[str, dict[str, str]] = {
    "eccjump.maps": {
        "Region": _CLASSIFICATION,
        "region": _CLASSIFICATION,
        "MotionMap": "eccjump.motion.maps",
        "motion_map": "eccjump.motion.maps",
    },
    "eccjump.maps.store": {"load": _CLASSIFICATION},
    "eccjump.maps.kinds": {
        "JARM": _FIELDS,
        "MOTION": "eccjump.motion.fields",
        "valid_sequences": "eccjump.motion.fields",
    },
    "eccjump.maps.xarray": {
        "DTYPES": _FIELDS,
        "FILL": _FIELDS,
        "reason_table": _FIELDS,
        "map_attrs": _FIELDS,
        "field_var": f"{_FIELDS}:cf_attrs",
        "SWEEPABLE": "eccjump.classification.dataset",
        "region_attrs": _CLASSIFY,
        "region_dataset": _CLASSIFICATION,
        "region_layout": _CLASSIFY,
        "to_region": _CLASSIFICATION,
    },
}


def new_name(name: str) -> str | None:
    """The new dotted path of the old path ``name`` (a module below an old package path
    included), or None for a path that did not move."""
    package = name
    while package:
        if package in MOVED:
            return MOVED[package] + name[len(package) :]
        package = package.rpartition(".")[0]
    return None


def _stacklevel() -> int:
    """The stack level of the code that imports, from the caller's frame: the first frame
    above this module, eccjump's ``__getattr__`` and importlib, so that the warning points to
    the user's line and shows under the default filters. ``warnings`` itself skips (does not
    count) the frames of importlib's bootstrap."""

    def bootstrap(frame: types.FrameType) -> bool:
        name = frame.f_code.co_filename
        return "importlib" in name and "_bootstrap" in name

    def ours(frame: types.FrameType) -> bool:  # this module, or a module's __getattr__
        module = frame.f_globals.get("__name__", "")
        return module in (__name__, "eccjump") or (
            frame.f_code.co_name == "__getattr__" and module.startswith("eccjump.")
        )

    frame, level = sys._getframe(1), 1
    while frame.f_back is not None and (
        bootstrap(frame)
        or frame.f_globals.get("__name__", "").partition(".")[0] == "importlib"
        or ours(frame)
    ):
        frame = frame.f_back
        level += not bootstrap(frame)
    return level


class _Loader(importlib.abc.Loader):
    """Loads an old path as the module at its new path (the same object, not a copy)."""

    def __init__(self, new: str) -> None:
        self.new = new
        self.spec: importlib.machinery.ModuleSpec | None = None

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> types.ModuleType:
        warnings.warn(
            f"{spec.name} is deprecated: import {self.new} (the old path works until the "
            "next release)",
            DeprecationWarning,
            stacklevel=_stacklevel(),
        )
        module = importlib.import_module(self.new)
        self.spec = module.__spec__
        # the import system then binds the module as an attribute of its parent package
        parent = sys.modules[spec.name.rpartition(".")[0]]
        if not isinstance(parent, _Package):
            parent.__class__ = _Package
        return module

    def exec_module(self, module: types.ModuleType) -> None:
        # the import system gave the module the old path's spec: it keeps its own
        module.__spec__ = self.spec


class _Finder(importlib.abc.MetaPathFinder):
    """Finds the old paths of :data:`MOVED` (first on ``sys.meta_path``: a module below an old
    package path would otherwise be found in the new package's folder and run twice)."""

    def find_spec(
        self,
        fullname: str,
        path: Sequence[str] | None,
        target: types.ModuleType | None = None,
    ) -> importlib.machinery.ModuleSpec | None:
        new = new_name(fullname) if fullname.startswith("eccjump.") else None
        if new is None:
            return None
        return importlib.machinery.ModuleSpec(fullname, _Loader(new))


class _Package(types.ModuleType):
    """The class of ``eccjump`` and of every package an old path was imported from: importing
    an old path named like a function of its package (``import eccjump.design.search``,
    ``import eccjump.plot.trajectory``) leaves the function (``eccjump.design``,
    ``eccjump.plot.trajectory``) bound, not the module."""

    def __setattr__(self, name: str, value: Any) -> None:
        bound = self.__dict__.get(name)
        if (
            isinstance(value, types.ModuleType)
            and f"{self.__name__}.{name}" in MOVED
            and bound is not None
            and not isinstance(bound, types.ModuleType)
        ):
            return
        super().__setattr__(name, value)


def old_attribute(name: str) -> types.ModuleType:
    """``eccjump.<name>`` for an old module path not imported yet (``eccjump.rolling.roll``
    after ``import eccjump``): the module at its new path, with the warning."""
    if f"eccjump.{name}" not in MOVED:
        raise AttributeError(f"module 'eccjump' has no attribute {name!r}")
    return importlib.import_module(f"eccjump.{name}")


def moved_name(module: str, name: str) -> Any:
    """``module.name`` for a name that left ``module`` (:data:`MOVED_NAMES`): the object at
    its new place, with the warning naming it; AttributeError for any other name."""
    new = MOVED_NAMES.get(module, {}).get(name)
    if new is None:
        raise AttributeError(f"module {module!r} has no attribute {name!r}")
    path, _, attr = new.partition(":")
    warnings.warn(
        f"{module}.{name} is deprecated: use {path}.{attr or name} (the old name works until "
        "the next release)",
        DeprecationWarning,
        stacklevel=_stacklevel(),
    )
    return getattr(importlib.import_module(path), attr or name)


def install(package: types.ModuleType) -> None:
    """Put the finder first on ``sys.meta_path`` (once) and give ``package`` its class."""
    if not any(isinstance(f, _Finder) for f in sys.meta_path):
        sys.meta_path.insert(0, _Finder())
    package.__class__ = _Package
