"""What every map result has, JARM maps (:class:`~eccjump.Region`) and motion maps
(:class:`~eccjump.MotionMap`) alike: the swept coordinates, one array per field, the JARM
fraction, its layout and the labelled form; and the registry of the result class of each kind.

A result class names its kind when it is defined, ``class Region(Map, kind=JARM)``: then
:func:`eccjump.maps.load` reads a file of that kind back as that class (:meth:`Map.of_kind`
and :meth:`Map.from_layout`) and :func:`eccjump.maps.save` writes it (:meth:`Map.to_layout`),
without this layer knowing the class.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np
from numpy.typing import NDArray

from eccjump.maps.kinds import MapKind
from eccjump.maps.layout import Layout, layout_to_xarray

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr


class Map:
    """A map of eccjump: one array per field over the product of its swept coordinates.

    The common base of :class:`~eccjump.Region` (from :func:`~eccjump.region`) and
    :class:`~eccjump.MotionMap` (from :func:`~eccjump.motion_map`). ``coords`` gives the
    swept axes by dimension name in grid order (1-D arrays, angles in rad), ``fields`` the
    results by name (each of shape :attr:`shape`), :meth:`fraction` the share of grid points
    that are a JARM, :meth:`to_xarray` the labelled form; :func:`eccjump.maps.save` writes it
    and :func:`eccjump.maps.load` reads it back as the same kind.

    Examples
    --------
    >>> import numpy as np
    >>> import eccjump
    >>> m = eccjump.region(np.radians([35, 40, 45]), [0.1, 0.15], [0.0, 0.1], 1.0)
    >>> isinstance(m, eccjump.Map), m.shape, list(m.coords)
    (True, (3, 2, 2), ['alpha', 'chi', 'km_frac'])
    """

    #: ``"jarm"`` or ``"motion"``: the ``kind`` attribute of the map's files.
    kind: ClassVar[str]
    #: The boolean field that says whether a point is a JARM.
    jarm_field: ClassVar[str]
    #: The result class of each kind, by the kind's name (:meth:`of_kind`).
    _classes: ClassVar[dict[str, type[Map]]] = {}

    def __init_subclass__(cls, kind: MapKind | None = None, **kwargs: Any) -> None:
        """``class Region(Map, kind=JARM)``: the result class of the maps of ``kind``."""
        super().__init_subclass__(**kwargs)
        if kind is not None:
            if Map._classes.setdefault(kind.name, cls) is not cls:
                raise TypeError(f"the maps of kind {kind.name!r} have a class already")
            cls.kind = kind.name

    @staticmethod
    def of_kind(kind: MapKind) -> type[Map]:
        """The result class of the maps of ``kind``."""
        return Map._classes[kind.name]

    if TYPE_CHECKING:  # each kind defines them as its data allows (a field or a property)

        @property
        def coords(self) -> Mapping[str, NDArray[np.float64]]: ...

        @property
        def fields(self) -> Mapping[str, NDArray]: ...

    def to_layout(self) -> Layout:
        """The map as a layout (:mod:`eccjump.maps.layout`, numpy only; dask arrays if lazy)."""
        raise NotImplementedError

    @classmethod
    def from_layout(cls, lay: Layout, source: object) -> Map:
        """The map of the layout ``lay``, checked to be a valid map of the class's kind
        (:func:`eccjump.maps.check.check`), read from ``source`` (a path, for messages)."""
        raise NotImplementedError

    def compute(self, **kwargs: Any) -> Map:
        """The map with every field computed (a map that is not lazy: itself)."""
        return self

    def to_xarray(self) -> xr.Dataset:
        """The map as a labelled ``xarray.Dataset`` (dask-backed if the map is lazy).

        Returns
        -------
        xarray.Dataset
            One dimension per swept axis, one variable per field with its units and the
            codes of a coded field as CF flags, how the map was made as attributes
            (:mod:`eccjump.maps.xarray`, "Dataset layout").

        Raises
        ------
        ImportError
            Without xarray (``pip install "eccjump[xarray]"``).
        """
        return layout_to_xarray(self.to_layout())

    @property
    def shape(self) -> tuple[int, ...]:
        """The grid's shape: the lengths of :attr:`coords`, in order."""
        return tuple(c.size for c in self.coords.values())

    def fraction(self) -> float:
        """The share of grid points that are a JARM.

        Returns
        -------
        float
            In [0, 1]; invalid points count as not a JARM; 0.0 for an empty map.
        """
        jarm = np.asarray(self.fields[self.jarm_field])
        return float(np.mean(jarm)) if jarm.size else 0.0
