"""JARM classification: the closed forms, the result fields, :func:`jarm` and :func:`region`,
the boundary searches and the initial conditions (``starts``). The layer above the maps; its
public names are those of ``eccjump.classification.classify``, re-exported here."""

from eccjump.classification.classify import (
    FIELDS,
    JarmResult,
    Method,
    Reason,
    Region,
    Rule,
    jarm,
    region,
    region_attrs,
    region_dataset,
    region_layout,
)

__all__ = [
    "FIELDS",
    "JarmResult",
    "Method",
    "Reason",
    "Region",
    "Rule",
    "jarm",
    "region",
    "region_attrs",
    "region_dataset",
    "region_layout",
]
