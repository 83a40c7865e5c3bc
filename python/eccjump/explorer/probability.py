"""The explorer's P(JARM) panel: an uncertainty map (:func:`eccjump.uncertainty_map`) given
to the explorer (``eccjump explore --uncertainty FILE``, ``eccjump.explore(uncertainty=...)``)
is checked once here, and :func:`panel` cuts the slice the page draws beside the JARM region.
"""

from __future__ import annotations

import math
import os
from typing import Any

import numpy as np

from eccjump._base.checks import MAX_MESSAGE, file_error
from eccjump.maps import load
from eccjump.maps.map import Map
from eccjump.studies.uncertainty.map import UncertaintyMap
from eccjump.studies.uncertainty.map_fields import PROBABILITY_LEVELS

#: How an uncertainty map is made, for the message that refuses another kind.
_MAKE = "make one with eccjump.uncertainty_map or eccjump map --kind uncertainty"


def checked_map(value: object, name: str) -> UncertaintyMap:
    """``value`` (an :class:`UncertaintyMap` or the path of its file) as a computed map, or
    the error naming ``name`` (the keyword or the option): a map of another kind is named."""
    path = value if isinstance(value, str | os.PathLike) else None
    if path is not None:
        try:
            value = load(path)
        except ValueError as err:  # (an OSError names the path itself)
            raise ValueError(_cut(f"{name}: {err}")) from None
    if not isinstance(value, Map):
        raise TypeError(
            f"{name} must be an UncertaintyMap or the path of its file, not {type(value).__name__}"
        )
    if not isinstance(value, UncertaintyMap):
        what = f"a {value.kind!r} map, not an uncertainty map ({_MAKE})"
        if path is None:
            raise ValueError(f"{name} is {what}")
        raise file_error(path, f"holds {what}", name=name)
    return value.compute()  # a lazy map once, not at every request


def panel(m: UncertaintyMap, km: float, chi: float) -> dict[str, Any]:
    """P(JARM) and its interval on the map's km_frac slice nearest to the point's
    k_m / (1 − χ), on the map's own (χ, α) grid with each cell's edges (halfway to its
    neighbours), for the page to draw on the JARM region's axes."""
    wanted = km / (1.0 - chi) if chi < 1.0 else math.inf
    k = int(np.argmin(np.abs(m.km_frac - min(wanted, 1.0))))
    # a map's axes may come in any order; the page draws them ascending
    ia, ic = np.argsort(m.alpha, kind="stable"), np.argsort(m.chi, kind="stable")
    fields = {f: np.asarray(m.fields[f], dtype=np.float64)[ia][:, ic, k] for f in _SENT}
    return {
        "available": True,
        "chi_edges": _edges(m.chi[ic], 0.0, 1.0),
        "alpha_edges": _edges(np.degrees(m.alpha[ia]), 0.0, 90.0),
        # row j (alpha), column i (chi): j * len(chi) + i, as the region's codes
        **{f: _listed(v) for f, v in fields.items()},
        "km_frac": float(m.km_frac[k]),
        "wanted_km_frac": None if math.isinf(wanted) else wanted,
        "levels": list(PROBABILITY_LEVELS),
        "mu_s": float(m.mu_s),
        "rule": m.rule,
        "n": int(m.n),
        "confidence": float(m.confidence),
        "tolerances": tolerances(m),
    }


#: The fields the page shows: P(JARM) and its interval.
_SENT = ("p_jarm", "p_jarm_low", "p_jarm_high")


def tolerances(m: UncertaintyMap) -> str:
    """The map's tolerances in the explorer's units (α in degrees)."""

    def unit(key: str, x: float) -> str:
        return f"{math.degrees(x):.3g}°" if key == "alpha" else f"{x:.3g}"

    out = [f"{k} ± {unit(k, v)}" for k, v in m.sd.items() if v > 0]
    out += [f"{k} + [{unit(k, lo)}, {unit(k, hi)}]" for k, (lo, hi) in m.bounds.items()]
    return "; ".join(out) or "none"


def _edges(centres: np.ndarray, lo: float, hi: float) -> list[float]:
    """The cells' edges around ascending ``centres``: halfway between neighbours, a half step
    beyond the ends (a lone centre: 1 % of the axis each side), within [lo, hi]."""
    c = np.asarray(centres, dtype=np.float64)
    half = np.diff(c) / 2.0 if c.size > 1 else np.array([0.01 * (hi - lo)])
    edges = np.concatenate(([c[0] - half[0]], c[:-1] + half, [c[-1] + half[-1]]))
    return np.round(np.clip(edges, lo, hi), 6).tolist()


def _listed(a: np.ndarray) -> list[float | None]:
    """A slice row by row as a list for JSON: 4 decimals, NaN (no valid sample) as None."""
    flat = np.round(a.ravel(), 4)
    return [None if math.isnan(x) else x for x in flat.tolist()]


def _cut(text: str) -> str:
    return text if len(text) <= MAX_MESSAGE else text[: MAX_MESSAGE - 3] + "..."
