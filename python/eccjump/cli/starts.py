"""``eccjump starts``: the JARM fraction against the start (theta0, omega0), the start that
maximises it, and what blocks a JARM at a start -- every number and figure of
the user guide's "Initial conditions" page in one command."""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

from eccjump import plot
from eccjump.classification.classify import Region, region
from eccjump.classification.starts import GRID_MAX, STARTS_MAX, optimal_start, start_map
from eccjump.cli._args import directory, int_in, short_text, shows_progress
from eccjump.cli._output import DPI_RANGE, check_outputs, save_figure


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "starts",
        help="JARM fraction against the start (theta0, omega0) and the best start",
        description="For each mu_s: the JARM fraction of the (alpha, chi, k_m) cube from rest, "
        "the start (theta0, omega0) that maximises it with its uncertainty (grid and twice "
        "the grid), and a map of the fraction and of the shares blocked at the start "
        "(immediate flight, rocking back) over theta0 in [0, 360) deg and omega0 in "
        "[0, omega-max]. With -o, write the figures of docs/initial_conditions.md.",
    )
    p.add_argument(
        "--mu-s",
        type=float,
        nargs="+",
        default=[0.7, 1.0],
        help=f"static friction, 1 ... {MAX_MU_VALUES} values (default 0.7 1)",
    )
    p.add_argument(
        "--grid",
        type=int_in(2, 64),
        default=24,
        help="points per axis of the optimiser's grid, 2 ... 64 (the fine grid is twice it; "
        "default 24)",
    )
    p.add_argument(
        "--lattice",
        type=int_in(2, 1000),
        nargs=2,
        default=[24, 12],
        metavar=("N_THETA", "N_OMEGA"),
        help="the optimiser's first lattice of starts, each 2 ... 1000 (default 24 12)",
    )
    p.add_argument(
        "--map-grid",
        type=int_in(2, GRID_MAX),
        default=20,
        help=f"points per axis of each start's grid in the map, 2 ... {GRID_MAX} (default 20)",
    )
    p.add_argument(
        "--map-size",
        type=int_in(2, STARTS_MAX // 2),
        nargs=2,
        default=[72, 31],
        metavar=("N_THETA", "N_OMEGA"),
        help=f"starts of the map, theta0 x omega0, at most {STARTS_MAX} (default 72 31)",
    )
    p.add_argument("--no-map", action="store_true", help="skip the map of starts")
    p.add_argument("--omega-max", type=float, default=3.0, help="largest omega0 [sqrt(g/R)]")
    p.add_argument(
        "--rule", choices=("paper", "normal_force"), default="paper", help="lift-off rule"
    )
    p.add_argument(
        "--threads", type=int_in(0, 256), default=0, help="threads, 0 ... 256 (0: one per core)"
    )
    p.add_argument(
        "-o", "--outdir", type=directory, default=None, help="write the figures here (a directory)"
    )
    p.add_argument(
        "--dpi",
        type=int_in(*DPI_RANGE),
        default=90,
        help=f"resolution of the PNGs, {DPI_RANGE[0]} ... {DPI_RANGE[1]} (default 90)",
    )
    p.add_argument("--json", action="store_true", help="print machine-readable JSON")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress on stderr")
    p.set_defaults(func=_cmd_starts)


#: The most friction coefficients of one run (each is a search over the starts).
MAX_MU_VALUES = 16


def _say(args: argparse.Namespace, text: str) -> None:
    if not args.quiet:
        print(text, file=sys.stderr, flush=True)


def _tag(mu: float) -> str:
    return f"{mu:g}".replace(".", "p")


def _figure_paths(args: argparse.Namespace) -> dict[str, Path]:
    """The figures -o asks for, by name, checked before any work ({} without -o)."""
    if args.outdir is None:
        return {}
    shown = f"--outdir {short_text(str(args.outdir), 60)!r}"
    try:
        is_dir = args.outdir.is_dir()
    except OSError as err:  # a name too long, a loop of links: checked before the work too
        raise ValueError(f"{shown}: {err.strerror or err}") from None
    if not is_dir:
        raise ValueError(f"{shown} is not a directory")
    names = []
    for mu in args.mu_s:
        if not args.no_map:
            names.append(f"starts_mu{_tag(mu)}")
        names += [f"starts_region_{where}_mu{_tag(mu)}" for where in ("rest", "optimum")]
    paths = check_outputs("--outdir", (args.outdir / f"{n}.png" for n in names), {".png"})
    return dict(zip(names, paths, strict=True))


def _cmd_starts(args: argparse.Namespace) -> int:
    if len(args.mu_s) > MAX_MU_VALUES:
        raise ValueError(f"--mu-s: {len(args.mu_s)} values; at most {MAX_MU_VALUES}")
    n_th, n_om = args.map_size
    if not args.no_map and n_th * n_om > STARTS_MAX:  # refused before the search, not after
        raise ValueError(f"--map-size {n_th} {n_om}: {n_th * n_om} starts; at most {STARTS_MAX}")
    figures = _figure_paths(args)
    if figures:
        import matplotlib

        matplotlib.use("Agg")
    results: list[dict[str, Any]] = []
    for mu in args.mu_s:
        start = time.perf_counter()
        _say(args, f"mu_s = {mu:g}: optimising over the start (grid {args.grid})")
        opt = optimal_start(
            mu,
            grid=args.grid,
            omega_max=args.omega_max,
            lattice=tuple(args.lattice),
            rule=args.rule,
            n_threads=args.threads,
            progress=shows_progress(args),
        )
        out: dict[str, Any] = {**opt.as_dict(), "seconds_optimum": time.perf_counter() - start}
        smap = None
        if not args.no_map:
            start = time.perf_counter()
            thetas = np.linspace(0.0, 2.0 * math.pi, n_th, endpoint=False)
            omegas = np.linspace(0.0, args.omega_max, n_om)
            smap = start_map(mu, thetas, omegas, grid=args.map_grid, rule=args.rule,
                             n_threads=args.threads, progress=shows_progress(args))  # fmt: skip
            out["map"] = {
                "grid": args.map_grid,
                "starts": [n_th, n_om],
                "no_jarm_starts": int(smap.impossible.sum()),
                "max_immediate_flight": float(smap.immediate_flight.max()),
                "max_rocks_back": float(smap.rocks_back.max()),
                "best_on_lattice": list(smap.best()),
                "seconds": time.perf_counter() - start,
            }
        written = []
        if figures and smap is not None:
            fig = plot.fraction_map(smap, optimum=opt)
            path = figures[f"starts_mu{_tag(mu)}"]
            written.append(save_figure("--outdir", fig, path, args.dpi))
        g = 2 * opt.grid
        u = (np.arange(g) + 0.5) / g
        out["regions"] = {}
        for name, th, om in (("rest", 0.0, 0.0), ("optimum", opt.theta0, opt.omega0)):
            reg = region(mu_s=mu, alpha=u * math.pi / 2, chi=u, km_frac=u, theta0=th, omega0=om,
                         rule=args.rule, n_threads=args.threads,
                         progress=shows_progress(args))  # fmt: skip
            out["regions"][name] = _region_summary(reg)
            if figures:
                path = figures[f"starts_region_{name}_mu{_tag(mu)}"]
                written.append(save_figure("--outdir", plot.region_map(reg), path, args.dpi))
        if written:
            out["figures"] = [str(p) for p in written]
        results.append(out)
        if not args.json:
            _print(out)
    if args.json:
        print(json.dumps(results, indent=2))
    return 0


def _region_summary(reg: Region) -> dict[str, Any]:
    """Where the JARM points of a map lie: their share per turn and their ranges."""
    res = reg.result
    jarm = np.asarray(res.is_jarm)
    n = np.asarray(res.n)[jarm]
    size = max(jarm.size, 1)
    out: dict[str, Any] = {
        "fraction": reg.fraction(),
        "by_turn": {
            "1": int((n == 1).sum()) / size,
            "2": int((n == 2).sum()) / size,
            "3": int((n == 3).sum()) / size,
            ">3": int((n > 3).sum()) / size,
        },
    }
    if jarm.any():
        i, j, k = np.nonzero(jarm)
        out["alpha_deg"] = [float(np.degrees(reg.alpha[i].min())),
                            float(np.degrees(reg.alpha[i].max()))]  # fmt: skip
        out["chi"] = [float(reg.chi[j].min()), float(reg.chi[j].max())]
        out["km_frac"] = [float(reg.km_frac[k].min()), float(reg.km_frac[k].max())]
        out["alpha_deg_median"] = float(np.degrees(np.median(reg.alpha[i])))
        out["chi_median"] = float(np.median(reg.chi[j]))
    return out


def _gain(r: dict[str, Any]) -> str:
    """The optimum's fraction over the one from rest (which may be 0: no quotient then)."""
    if r["fraction_at_rest"] <= 0:
        return "no JARM from rest"
    return f"{r['fraction'] / r['fraction_at_rest']:.4g} x the rest value"


def _print(r: dict[str, Any]) -> None:
    # Every number printed here is bounded (fractions in [0, 1], angles in [0, 360), omega0
    # at most omega_max <= 100), so fixed-point formats print a few digits; _gain divides.
    fine = 2 * r["grid"]
    print(f"mu_s = {r['mu_s']:g}   (rule {r['rule']}, fraction on the {fine}^3 midpoint grid)")
    print(f"  from rest      fraction {r['fraction_at_rest']:.6f}")
    print(
        f"  optimum        theta0 = {r['theta0_deg']:.2f} +- {r['theta0_err_deg']:.2f} deg, "
        f"omega0 = {r['omega0']:.4f} +- {r['omega0_err']:.4f}"
    )
    print(
        f"                 fraction {r['fraction']:.6f} +- {r['fraction_err']:.6f} "
        f"({r['grid']}^3: {r['fraction_coarse']:.6f}); {_gain(r)}"
    )
    print(f"  search         {r['evaluations']} maps, {r['seconds_optimum']:.1f} s")
    m = r.get("map")
    if m is not None:
        th, om, f = m["best_on_lattice"]
        print(
            f"  map            {m['starts'][0]} x {m['starts'][1]} starts on {m['grid']}^3, "
            f"{m['seconds']:.1f} s; best lattice start {f:.4f} at "
            f"({math.degrees(th):.0f} deg, {om:.2f})"
        )
        print(
            f"  blocked        no JARM at {m['no_jarm_starts']} starts; immediate flight up "
            f"to {m['max_immediate_flight']:.3f}, rocking back up to {m['max_rocks_back']:.3f} "
            "of the cube"
        )
    for name, g in r["regions"].items():
        turns = ", ".join(f"n {k}: {v:.5f}" for k, v in g["by_turn"].items())
        print(f"  JARMs {name:<8} {turns}")
        if "alpha_deg" in g:
            print(
                f"                 alpha {g['alpha_deg'][0]:.1f}-{g['alpha_deg'][1]:.1f} deg "
                f"(median {g['alpha_deg_median']:.1f}), chi {g['chi'][0]:.3f}-{g['chi'][1]:.3f} "
                f"(median {g['chi_median']:.3f})"
            )
    for p in r.get("figures", []):
        print(f"  figure         {p}")
