"""``eccjump simulate``: the full motion (rolling, slipping, flight, landing), printed as a
table of its transitions (or JSON), optionally drawn as a figure and an animated GIF.

Uses only the documented fields of ``MotionResult`` (the user guide's "The full motion",
``eccjump.simulate``).
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path
from typing import Any

import numpy as np

from eccjump import plot
from eccjump._base.body import Cylinder
from eccjump.cli._args import RAMP_RADIANS, Degrees, add_integrator, int_at_least
from eccjump.cli._output import (
    ANIMATION_SUFFIXES,
    bounded,
    check_output,
    figure_suffixes,
    save_figure,
    write_output,
)
from eccjump.motion.simulation import MODES, simulate

UNITS = (
    "g = R = M = 1: time in sqrt(R/g), lengths in R, omega in sqrt(g/R) rad, "
    "velocities in sqrt(g R), energy in M g R"
)


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "simulate",
        help="follow the full motion (roll, slip, flight, landing) and list its transitions",
        description="Integrate the full motion from (theta0, omega0, slip0) through every mode "
        "(ROLL, SLIP, FLIGHT) and every landing until t_max, l_max, max_transitions or an "
        "outcome the rigid model cannot continue; print one row per transition, then the "
        "flights and the energy ledger.",
    )
    p.add_argument(
        "--alpha",
        action=Degrees,
        lo=0.0,
        hi=90.0,
        radians_up_to=RAMP_RADIANS,
        required=True,
        help="ramp angle [deg], in [0, 90]",
    )
    p.add_argument("--chi", type=float, required=True, help="CM offset d/R, in [0, 1]")
    p.add_argument("--km", type=float, required=True, help="shell mass fraction, in [0, 1-chi]")
    p.add_argument("--mu-s", type=float, required=True, help="static friction coefficient")
    p.add_argument(
        "--mu-k", type=float, default=None, help="kinetic friction coefficient (default: mu_s)"
    )
    p.add_argument(
        "--restitution",
        type=float,
        default=0.0,
        help="energetic coefficient of restitution e of the impacts, in [0, 1] (default 0)",
    )
    p.add_argument(
        "--rule",
        choices=("paper", "normal_force"),
        default="paper",
        help="lift-off rule from rolling (default: the paper's)",
    )
    p.add_argument("--theta0", action=Degrees, default=0.0, help="initial angle [deg]")
    p.add_argument(
        "--omega0", type=float, default=0.0, help="initial angular velocity [sqrt(g/R) rad]"
    )
    p.add_argument(
        "--slip0",
        type=float,
        default=0.0,
        help="initial slip velocity l' - theta' [sqrt(g R)] (default 0)",
    )
    p.add_argument("--t-max", type=float, default=100.0, help="stop at this time [sqrt(R/g)]")
    p.add_argument(
        "--l-max", type=float, default=math.inf, help="stop when C has travelled this far [R]"
    )
    p.add_argument(
        "--max-transitions",
        type=int_at_least(1),
        default=100,
        help="stop after this many transitions (default 100)",
    )
    p.add_argument("--rtol", type=float, default=1e-10)
    p.add_argument("--atol", type=float, default=1e-12)
    add_integrator(p)
    p.add_argument("--json", action="store_true", help="print machine-readable JSON")
    p.add_argument(
        "--figure", default=None, help="draw the motion to this image (needs eccjump[plot])"
    )
    p.add_argument(
        "--animate",
        default=None,
        help="write an animation of the motion to this .gif (needs eccjump[plot])",
    )
    p.set_defaults(func=_cmd_simulate)


# --------------------------------------------------------------------------------------------
# the summary
# --------------------------------------------------------------------------------------------


def _num(x: Any) -> float | None:
    """A float for JSON: NaN and infinities (not JSON) become None."""
    x = float(x)
    return x if math.isfinite(x) else None


def state_energy(body: Cylinder, alpha: float, s: Any) -> float:
    """E = kinetic + potential (per M g R) of a state with fields θ, omega, l, ldot, b,
    bdot (the user guide's "The full motion", Energy ledger)."""
    chi, st, ct = body.chi, math.sin(s.theta), math.cos(s.theta)
    vx = s.ldot + chi * ct * s.omega
    vy = s.bdot - chi * st * s.omega
    return (
        0.5 * (vx * vx + vy * vy)
        + 0.5 * body.Icm * s.omega**2
        - (s.l + chi * st) * math.sin(alpha)
        + (s.b + chi * ct) * math.cos(alpha)
    )


def transition_energies(result: Any, body: Cylinder, alpha: float) -> list[float]:
    """The mechanical energy just after each transition: ``result.energy`` at the recorded
    point that starts the new segment (the second of the two points at the transition time,
    or the first point for ``start``), found in order along the arrays; computed from the
    transition's state where no recorded point matches."""
    t = np.asarray(result.t, dtype=float)
    mode = np.asarray(result.mode)
    energy = np.asarray(result.energy, dtype=float)
    out: list[float] = []
    cursor = 0
    for tr in result.transitions:
        tol = 1e-12 * (1.0 + abs(tr.t))
        code = MODES.index(tr.to_mode) if tr.to_mode in MODES else -1
        hits = np.flatnonzero((np.abs(t[cursor:] - tr.t) <= tol) & (mode[cursor:] == code))
        hits += cursor
        # the start of a segment: the first point, or the second of a repeated time
        starts = [i for i in hits if i == 0 or abs(t[i - 1] - t[i]) <= tol]
        pick = starts[0] if starts else (int(hits[0]) if hits.size else None)
        if pick is None:
            out.append(state_energy(body, alpha, tr))
        else:
            out.append(float(energy[pick]))
            cursor = int(pick) + 1
    return out


def summary(result: Any, body: Cylinder, alpha_deg: float, args: argparse.Namespace) -> dict:
    """Everything the table prints, as plain JSON-ready data."""
    alpha = math.radians(alpha_deg)
    energies = transition_energies(result, body, alpha)
    transitions = [
        {
            "t": _num(tr.t),
            "theta_deg": _num(math.degrees(tr.theta)),
            "from": tr.from_mode,
            "to": tr.to_mode,
            "reason": tr.reason,
            "energy": _num(e),
            "omega": _num(tr.omega),
            "l": _num(tr.l),
            "ldot": _num(tr.ldot),
            "b": _num(tr.b),
            "bdot": _num(tr.bdot),
        }
        for tr, e in zip(result.transitions, energies, strict=True)
    ]
    flights = [
        {
            "t_liftoff": _num(f.t_liftoff),
            "t_landing": _num(f.t_landing),
            "theta_liftoff_deg": _num(math.degrees(f.theta_liftoff)),
            "theta_landing_deg": _num(math.degrees(f.theta_landing)),
            "apex": _num(f.apex),
            "distance": _num(f.distance),
        }
        for f in result.flights
    ]
    impacts = [
        {
            "t": _num(i.t),
            "normal_speed": _num(i.normal_speed),
            "pt": _num(i.pt),
            "pn": _num(i.pn),
            "energy_lost": _num(i.energy_lost),
            "sticking": bool(i.sticking),
            "outcome": i.outcome,
        }
        for i in result.impacts
    ]
    e_end = float(result.energy[-1]) if len(result.energy) else math.nan
    d_end = float(result.dissipated[-1]) if len(result.dissipated) else math.nan
    ledger = {
        "energy0": _num(result.energy0),
        "energy_end": _num(e_end),
        "dissipated_slip": _num(result.dissipated_slip),
        "dissipated_impacts": _num(result.dissipated_impacts),
        "dissipated": _num(d_end),
        "balance": _num(e_end + d_end - result.energy0),
    }
    return {
        "parameters": {
            "alpha_deg": alpha_deg,
            "chi": body.chi,
            "km": body.km,
            "mu_s": args.mu_s,
            "mu_k": args.mu_s if args.mu_k is None else args.mu_k,
            "restitution": args.restitution,
            "rule": args.rule,
            "theta0_deg": args.theta0,
            "omega0": args.omega0,
            "slip0": args.slip0,
            "integrator": args.integrator,
        },
        "status": result.status,
        "message": result.message,
        "t_end": _num(result.t[-1]) if len(result.t) else None,
        "transitions": transitions,
        "flights": flights,
        "impacts": impacts,
        "ledger": ledger,
        "points": len(result.t),
        "nfev": int(result.nfev),
        "units": UNITS,
    }


def _g(x: float | None, fmt: str) -> str:
    return "n/a" if x is None else bounded(x, fmt)


def print_table(s: dict) -> None:
    p = s["parameters"]
    print(
        f"simulate  alpha = {p['alpha_deg']:g} deg, chi = {p['chi']:g}, km = {p['km']:g}, "
        f"mu_s = {p['mu_s']:g}, mu_k = {p['mu_k']:g}, e = {p['restitution']:g}, "
        f"rule = {p['rule']}"
    )
    print(
        f"\n{'#':>3} {'t [sqrt(R/g)]':>14} {'theta [deg]':>14}  {'from -> to':<18} {'reason':<18} "
        f"{'energy [M g R]':>14}"
    )
    for k, tr in enumerate(s["transitions"]):
        arrow = f"{tr['from'] or '-':>6} -> {tr['to']}"
        print(
            f"{k:>3} {_g(tr['t'], '14.8f')} {_g(tr['theta_deg'], '14.6f')}  {arrow:<18} "
            f"{tr['reason']:<18} {_g(tr['energy'], '+14.8f')}"
        )
    led = s["ledger"]
    rows = [("status", f"{s['status']}: {s['message']}")]
    if s["t_end"] is not None:
        rows.append(("end", f"t = {s['t_end']:.8g} sqrt(R/g)"))
    fl = s["flights"]
    rows.append(("flights", f"{len(fl)}"))
    if fl:
        f = fl[0]
        landing = (
            "not landed by the end"
            if f["t_landing"] is None
            else f"landing at t = {f['t_landing']:.8g} "
            f"(theta = {_g(f['theta_landing_deg'], '.6g')} deg)"
        )
        rows.append(
            (
                "first flight",
                f"lift-off at t = {_g(f['t_liftoff'], '.8g')} "
                f"(theta = {_g(f['theta_liftoff_deg'], '.6g')} deg), {landing}",
            )
        )
        rows.append(
            (
                "",
                f"apex = {_g(f['apex'], '.6g')} R, distance = {_g(f['distance'], '.6g')} R",
            )
        )
    rows.append(("impacts", f"{len(s['impacts'])}"))
    rows.append(
        (
            "energy",
            f"E(0) = {_g(led['energy0'], '.8g')}, E(end) = {_g(led['energy_end'], '.8g')} M g R",
        )
    )
    rows.append(
        (
            "dissipated",
            f"slip = {_g(led['dissipated_slip'], '.8g')}, "
            f"impacts = {_g(led['dissipated_impacts'], '.8g')} M g R "
            f"(E + dissipated - E(0) = {_g(led['balance'], '.0e')})",
        )
    )
    rows.append(("integrator", p["integrator"]))
    rows.append(("steps", f"{s['points']} recorded points, {s['nfev']} evaluations"))
    width = max(len(name) for name, _ in rows)
    print()
    for name, value in rows:
        print(f"{name:<{width}}  {value}")


# --------------------------------------------------------------------------------------------
# the command
# --------------------------------------------------------------------------------------------


def _check_outputs(args: argparse.Namespace) -> tuple[Path | None, Path | None]:
    """The paths of --figure and --animate, checked before the run (None: not asked for)."""
    figure = animation = None
    if args.figure is not None:
        figure = check_output("--figure", args.figure, figure_suffixes())
    if args.animate is not None:
        animation = check_output("--animate", args.animate, ANIMATION_SUFFIXES)
    return figure, animation


def _cmd_simulate(args: argparse.Namespace) -> int:
    figure, animation = _check_outputs(args)
    body = Cylinder(args.chi, args.km)
    alpha = math.radians(args.alpha)
    res = simulate(
        body,
        alpha,
        mu_s=args.mu_s,
        mu_k=args.mu_k,
        restitution=args.restitution,
        rule=args.rule,
        theta0=math.radians(args.theta0),
        omega0=args.omega0,
        slip0=args.slip0,
        t_max=args.t_max,
        l_max=args.l_max,
        max_transitions=args.max_transitions,
        rtol=args.rtol,
        atol=args.atol,
        integrator=args.integrator,
        dense_output=animation is not None,
    )
    s = summary(res, body, args.alpha, args)
    if args.json:
        print(json.dumps(s, indent=2))
    else:
        print_table(s)
    if figure is not None or animation is not None:
        import matplotlib

        matplotlib.use("Agg")
    if figure is not None:
        save_figure("--figure", plot.motion(res, body=body, alpha=alpha), figure, dpi=110)
        if not args.json:
            print(f"figure: {figure}")
    if animation is not None:
        write_output(
            "--animate",
            animation,
            lambda tmp: plot.animate_motion(res, tmp, body=body, alpha=alpha),
        )
        if not args.json:
            print(f"animation: {animation}")
    return 0
