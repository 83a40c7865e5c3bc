"""JARM classification: the closed forms, the result fields, :func:`jarm` and :func:`region`,
JARM maps in files and datasets (``dataset``), the boundary searches and the initial
conditions (``starts``). The layer above the maps; its public names are those of
``eccjump.classification.classify`` and ``eccjump.classification.dataset``, re-exported here."""

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
    region_layout,
)
from eccjump.classification.dataset import load, region_dataset, to_region

__all__ = [
    "FIELDS",
    "JarmResult",
    "Method",
    "Reason",
    "Region",
    "Rule",
    "jarm",
    "load",
    "region",
    "region_attrs",
    "region_dataset",
    "region_layout",
    "to_region",
]
