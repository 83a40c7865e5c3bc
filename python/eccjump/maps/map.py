"""What every map result has, JARM maps (:class:`~eccjump.Region`) and motion maps
(:class:`~eccjump.MotionMap`) alike: the swept coordinates, one array per field, the JARM
fraction and the labelled form.

Writing a map of either kind is :func:`eccjump.maps.save`, reading it back
:func:`eccjump.maps.load`; this module knows neither kind nor files, so both kinds build on
it and the files on them.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, ClassVar

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr


class Map:
    """A map of eccjump: one array per field over the product of its swept coordinates.

    The common base of :class:`~eccjump.Region` (from :func:`~eccjump.region`) and
    :class:`~eccjump.MotionMap` (from :func:`~eccjump.motion_map`). ``coords`` gives the
    swept axes by dimension name in grid order (1-D arrays, angles in rad), ``fields`` the
    results by name (each of shape :attr:`shape`), :meth:`fraction` the share of grid points
    that are a JARM, ``to_xarray()`` the labelled form; :func:`eccjump.maps.save` writes it
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

    if TYPE_CHECKING:  # each kind defines them as its data allows (a field or a property)

        @property
        def coords(self) -> Mapping[str, NDArray[np.float64]]: ...

        @property
        def fields(self) -> Mapping[str, NDArray]: ...

        def to_xarray(self) -> xr.Dataset: ...

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
