"""The kinds of ``eccjump map`` as small job classes: the JARM classification
(:func:`eccjump.region`), the full motion to the first landing (:func:`eccjump.motion_map`) and
P(JARM) under tolerances (:func:`eccjump.uncertainty_map`).
Each holds its options and file attributes, computes one chunk, counts the finished points
and writes its summary lines and figure: a :class:`eccjump.maps.runner.Job`, which the
runner computes in chunks, resumes and writes for all."""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from eccjump import plot
from eccjump.classification.classify import region
from eccjump.classification.dataset import load
from eccjump.classification.fields import JARM, map_attrs
from eccjump.cli._output import save_figure
from eccjump.cli.uncertainty import _value  # --sd's numbers, as eccjump uncertainty's
from eccjump.maps import load as load_map
from eccjump.maps.kinds import MapKind
from eccjump.motion import maps as motion_maps
from eccjump.motion.fields import MOTION, sequence_name
from eccjump.studies.uncertainty.map import MAP_PARAMETERS, UncertaintyMap, uncertainty_map
from eccjump.studies.uncertainty.map_fields import UNCERTAINTY

#: Options of a JARM map that must match the store for --resume (attribute names).
MAP_OPTIONS = (
    "mu_s",
    "n",
    "rule",
    "method",
    "theta0",
    "omega0",
    "rtol",
    "atol",
    "integrator",
    "max_turns",
    "refine_extrema",
    "stop_at_slip",
)
#: The same for a motion map.
MOTION_OPTIONS = (
    "mu_s",
    "mu_k",
    "restitution",
    "rule",
    "theta0",
    "omega0",
    "t_max",
    "max_transitions",
    "rtol",
    "atol",
    "integrator",
)
#: The value of an option a store written before the option was recorded was made with.
UNRECORDED = {"integrator": "RK45", "stop_at_slip": False}


class JarmJob:
    """``--kind jarm``: the JARM classification of each point (:func:`eccjump.region`)."""

    kind: MapKind = JARM
    matched = MAP_OPTIONS
    unrecorded = UNRECORDED
    counted = ("is_jarm", "n")

    def __init__(self, args: argparse.Namespace) -> None:
        self.opts = {
            "mu_s": float(args.mu_s),
            "n": args.n,
            "rule": args.rule,
            "method": args.route.replace("-", "_"),
            "theta0": math.radians(args.theta0),
            "omega0": float(args.omega0),
            "rtol": float(args.rtol),
            "atol": float(args.atol),
            "integrator": args.integrator,
            "max_turns": int(args.max_turns),
            "refine_extrema": False,
            "stop_at_slip": bool(args.stop_at_slip),
        }
        self.attrs = map_attrs(**self.opts)
        self.points = self.jarm = 0
        self.per_n: dict[int, int] = {}

    def compute(
        self, alpha: NDArray, chi: NDArray, km: NDArray, threads: int
    ) -> dict[str, NDArray]:
        o = self.opts
        reg = region(
            mu_s=o["mu_s"],
            n=o["n"],
            alpha=alpha,
            chi=chi,
            km_frac=km,
            n_threads=threads,
            **{k: v for k, v in o.items() if k not in ("mu_s", "n")},
        )
        return {f: getattr(reg.result, f) for f in self.kind.fields}

    def count(self, part: dict[str, NDArray]) -> None:
        is_jarm = np.asarray(part["is_jarm"], dtype=bool)
        self.points += is_jarm.size
        turns = np.asarray(part["n"])[is_jarm]
        self.jarm += turns.size
        values, counts = np.unique(turns, return_counts=True)
        for v, c in zip(values.tolist(), counts.tolist(), strict=True):
            self.per_n[v] = self.per_n.get(v, 0) + c

    def lines(self) -> list[str]:
        lines = [jarm_line(self.jarm, self.points)]
        shown = sorted(self.per_n)[:10]
        for v in shown:
            lines.append(f"  n = {v:<8}  {share(self.per_n[v], self.points)}")
        rest = sum(c for v, c in self.per_n.items() if v not in shown)
        if rest:
            lines.append(f"  n > {shown[-1]:<8}  {share(rest, self.points)}")
        return lines

    def draw(self, path: str, figure: Path) -> None:
        save_figure("--figure", plot.region_map(load(path)), figure, dpi=110)


class MotionJob:
    """``--kind motion``: the full motion of each point to its first landing
    (:func:`eccjump.motion_map`)."""

    kind: MapKind = MOTION
    matched = MOTION_OPTIONS
    unrecorded = UNRECORDED
    counted = ("sequence", "jarm", "slipped_first", "status")

    def __init__(self, args: argparse.Namespace) -> None:
        mu_s = float(args.mu_s)
        self.opts = {
            "mu_s": mu_s,
            "mu_k": mu_s if args.mu_k is None else float(args.mu_k),
            "restitution": float(args.restitution),
            "rule": args.rule,
            "theta0": math.radians(args.theta0),
            "omega0": float(args.omega0),
            "t_max": float(args.t_max),
            "max_transitions": int(args.max_transitions),
            "rtol": float(args.rtol),
            "atol": float(args.atol),
            "integrator": args.integrator,
        }
        self.attrs = {
            "title": "motion map of an eccentric cylinder on a ramp (eccjump)",
            "kind": "motion",
            "eccjump_version": motion_maps._core.VERSION,
            **self.opts,
            "units": "g = R = M = 1: angles in rad, times in sqrt(R/g), lengths in R",
        }
        self.points = self.jarm = self.slipped = self.invalid = 0
        self.per_sequence: dict[int, int] = {}

    def compute(
        self, alpha: NDArray, chi: NDArray, km: NDArray, threads: int
    ) -> dict[str, NDArray]:
        m = motion_maps.motion_map(alpha=alpha, chi=chi, km_frac=km, n_threads=threads, **self.opts)
        assert isinstance(m, motion_maps.MotionMap)
        return {f: m.fields[f] for f in self.kind.fields}

    def count(self, part: dict[str, NDArray]) -> None:
        self.points += part["jarm"].size
        self.jarm += int(np.count_nonzero(part["jarm"]))
        self.slipped += int(np.count_nonzero(part["slipped_first"]))
        self.invalid += int(np.count_nonzero(part["status"] == motion_maps.INVALID))
        codes, counts = np.unique(part["sequence"], return_counts=True)
        for c, k in zip(codes.tolist(), counts.tolist(), strict=True):
            self.per_sequence[c] = self.per_sequence.get(c, 0) + k

    def lines(self) -> list[str]:
        p = self.points
        lines = [
            jarm_line(self.jarm, p),
            f"slips first   {share(self.slipped, p)}",
        ]
        if self.invalid:
            lines.append(f"invalid       {share(self.invalid, p)} (km = 0 or mu_k > mu_s)")
        lines.append("sequences (first modes, to the mode after the first landing):")
        top = sorted(self.per_sequence.items(), key=lambda kv: (-kv[1], kv[0]))
        for code, n in top[:10]:
            lines.append(f"  {sequence_name(code) or '(not run)':<44} {share(n, p)}")
        rest = sum(n for _, n in top[10:])
        if rest:
            lines.append(f"  {f'{len(top) - 10} other sequences':<44} {share(rest, p)}")
        return lines

    def draw(self, path: str, figure: Path) -> None:
        save_figure("--figure", plot.sequence_map(motion_maps.load(path)), figure, dpi=110)


#: The same for an uncertainty map.
UNCERTAINTY_OPTIONS = ("mu_s", "n", "seed", "confidence", "rule", "sampling", "invalid", "sd")


def tolerances(given: list[str]) -> dict[str, float]:
    """``--sd NAME=SD[,NAME=SD...]`` (repeatable) as the API's dict, α in degrees on the
    command line as every angle (ValueError naming --sd)."""
    sd: dict[str, float] = {}
    for item in (part for text in given for part in text.split(",") if part.strip()):
        name, sep, value = (x.strip() for x in item.partition("="))
        if not sep or name not in MAP_PARAMETERS:
            raise ValueError(
                f"--sd {item[:30]!r}: use NAME=SD with NAME one of {', '.join(MAP_PARAMETERS)}"
            )
        if name in sd:
            raise ValueError(f"--sd {name}: given twice")
        try:
            sd[name] = _value(name, value)
        except ValueError as err:
            raise ValueError(f"--sd {err}") from None
    return sd


class UncertaintyJob:
    """``--kind uncertainty``: P(JARM) under the tolerances ``--sd`` at each point
    (:func:`eccjump.uncertainty_map`, the same unit-cube points at every point: a chunk's
    points are those of the whole map)."""

    kind: MapKind = UNCERTAINTY
    matched = UNCERTAINTY_OPTIONS
    unrecorded = UNRECORDED
    counted = ("p_jarm", "p_jarm_low")

    def __init__(self, args: argparse.Namespace) -> None:
        if args.theta0 or args.omega0:
            raise ValueError("--theta0, --omega0: --kind uncertainty starts at rest at 0")
        self.opts: dict[str, Any] = {
            "mu_s": float(args.mu_s),
            "sd": tolerances(args.sd),
            "n": int(args.samples),
            "seed": int(args.seed),
            "sampling": args.sampling,
            "confidence": float(args.confidence),
            "rule": args.rule,
        }
        #: Work per point, in classifications (the runner's chunk size).
        self.cost = self.opts["n"]
        empty = np.zeros(0)  # checks every option, computes nothing
        self.attrs = uncertainty_map(empty, empty, empty, **self.opts).attrs()
        self.points = self.sure = self.even = 0
        self.total = 0.0

    def compute(
        self, alpha: NDArray, chi: NDArray, km: NDArray, threads: int
    ) -> dict[str, NDArray]:
        m = uncertainty_map(alpha, chi, km, n_threads=threads, **self.opts)
        return dict(m.fields)

    def count(self, part: dict[str, NDArray]) -> None:
        p = np.asarray(part["p_jarm"], dtype=np.float64)
        self.points += p.size
        self.total += float(np.nansum(p))
        self.even += int(np.count_nonzero(p >= 0.5))
        self.sure += int(np.count_nonzero(np.asarray(part["p_jarm_low"]) >= 0.95))

    def lines(self) -> list[str]:
        n = self.points
        mean = f"{self.total / n:.6f}" if n else "n/a"
        return [
            f"P(JARM)       mean {mean} over the finished points",
            f"P >= 0.5      {share(self.even, n)}",
            f"95 % sure     {share(self.sure, n)} (the interval's lower end >= 0.95)",
        ]

    def draw(self, path: str, figure: Path) -> None:
        m = load_map(path)
        assert isinstance(m, UncertaintyMap)
        save_figure("--figure", plot.probability_map(m), figure, dpi=110)


Job = JarmJob | MotionJob | UncertaintyJob


#: The most turns of a JARM search (the core's ``jarm::MAX_TURNS``; the user guide's "Limits").
MAX_TURNS = 10**6

#: The options of one kind only, by dest, with their defaults. The parser leaves them None
#: when not given (``--n`` and ``--mu-k`` are None by default too, which means the same).
KIND_OPTIONS: dict[str, dict[str, Any]] = {
    "jarm": {"n": None, "route": "closed-form", "max_turns": 10_000, "stop_at_slip": False},
    "motion": {"mu_k": None, "restitution": 0.0, "t_max": 100.0, "max_transitions": 100},
    "uncertainty": {
        "sd": [],
        "samples": 2000,
        "seed": 0,
        "sampling": "random",
        "confidence": 0.95,
    },
}


def kind_options(args: argparse.Namespace) -> None:
    """One rule for the options that belong to one ``--kind``: given with the other kind, a
    ValueError naming the option and its kind (--max-turns with --kind motion once passed
    unchecked, while --n was refused); not given, their defaults, in place."""
    for kind, defaults in KIND_OPTIONS.items():
        for dest, default in defaults.items():
            if getattr(args, dest) is None:
                setattr(args, dest, default)
            elif kind != args.kind:
                option = "--" + dest.replace("_", "-")
                raise ValueError(f"{option} is an option of --kind {kind}, not --kind {args.kind}")


def job(args: argparse.Namespace) -> Job:
    """The job of ``args.kind``, once its options are checked (:func:`kind_options`)."""
    kind_options(args)
    jobs: dict[str, type[Job]] = {
        "jarm": JarmJob,
        "motion": MotionJob,
        "uncertainty": UncertaintyJob,
    }
    return jobs[args.kind](args)


def share(k: int, points: int) -> str:
    return f"{k / points:.6f} ({k})" if points else "n/a"


def jarm_line(k: int, points: int) -> str:
    share = f"{k / points:.6f}" if points else "n/a"
    return f"JARM          {share} of the finished points ({k})"
