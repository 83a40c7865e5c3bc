"""The results file every bench script writes (``--json PATH``, default ``bench_<name>.json``
in the current directory): one JSON object with what is shared (the benchmark's name, the date,
the machine, the versions, the command's arguments) and the figures the script printed.

    {"benchmark": "bench_roll", "date": "2026-11-27", "machine": {...}, "versions": {...},
     "argv": [...], "args": {...}, ...the script's own keys}

Floats that are not finite (a level not reached, a ratio without a base) are written as
``null``, so that any JSON reader takes the file; numpy scalars and arrays become numbers and
lists.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import platform
import sys
from datetime import date
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path
from typing import Any

import numpy as np

#: the packages whose versions go into every file (the peers only where installed)
PACKAGES = ("eccjump", "numpy", "scipy", "numba", "numbalsoda", "pydiffsol", "diffrax", "jax")


def add_json_option(parser: argparse.ArgumentParser, name: str) -> None:
    """``--json PATH``: where the results go (default ``bench_<name>.json`` here)."""
    parser.add_argument(
        "--json",
        default=f"bench_{name}.json",
        metavar="PATH",
        help=f"results file, JSON (default: bench_{name}.json in the current directory)",
    )


def cpu_model() -> str:
    """The processor's model name (the ratios to the peers depend on it, not only on the
    code), or the platform's description where /proc/cpuinfo has none."""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown CPU"


def versions() -> dict[str, str | None]:
    """Installed versions of PACKAGES (None: not installed)."""
    out: dict[str, str | None] = {}
    for name in PACKAGES:
        try:
            out[name] = version(name)
        except PackageNotFoundError:
            out[name] = None
    return out


def header(name: str, args: argparse.Namespace | None) -> dict[str, Any]:
    """What every results file starts with."""
    load = os.getloadavg() if hasattr(os, "getloadavg") else (math.nan,) * 3
    return {
        "benchmark": f"bench_{name}",
        "date": date.today().isoformat(),
        "machine": {
            "cpu": cpu_model(),
            "arch": platform.machine(),
            "logical_cpus": os.cpu_count(),
            "system": platform.platform(),
            "load_average_1min": load[0],
        },
        "python": platform.python_version(),
        "versions": versions(),
        "argv": sys.argv[1:],
        "args": {k: v for k, v in vars(args).items() if k != "json"} if args else {},
    }


def plain(x: Any) -> Any:
    """x with numpy types made Python's, tuples made lists, keys made strings and
    non-finite floats made None."""
    if isinstance(x, dict):
        return {str(k): plain(v) for k, v in x.items()}
    if isinstance(x, list | tuple):
        return [plain(v) for v in x]
    if isinstance(x, np.ndarray):
        return plain(x.tolist())
    if isinstance(x, np.generic):
        return plain(x.item())
    if isinstance(x, float) and not math.isfinite(x):
        return None
    if isinstance(x, Path):
        return str(x)
    return x


def write(
    path: str | os.PathLike[str], name: str, args: argparse.Namespace | None, **figures: Any
) -> Path:
    """Write header(name, args) and the figures to path; returns the path."""
    out = Path(path)
    doc = plain({**header(name, args), **figures})
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(doc, indent=1, allow_nan=False, ensure_ascii=False) + "\n", "utf-8")
    print(f"results written to {out}")
    return out
