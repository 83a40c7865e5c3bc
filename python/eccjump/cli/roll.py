"""``eccjump roll``: one pure-rolling run, printed as a table or JSON."""

from __future__ import annotations

import argparse
import json
import math

from eccjump._base.body import Cylinder
from eccjump.cli._args import RAMP_RADIANS, Degrees, add_integrator
from eccjump.cli._output import bounded
from eccjump.motion.roll import RollResult, roll


def _add_body_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("--chi", type=float, required=True, help="CM offset d/R, in [0, 1]")
    p.add_argument("--km", type=float, required=True, help="shell mass fraction, in [0, 1-chi]")


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "roll",
        help="integrate pure rolling until lift-off, slip or a limit",
        description="Integrate pure rolling from (theta0, omega0) until an "
        "event ends it; print what happened.",
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
    _add_body_args(p)
    p.add_argument("--mu-s", type=float, default=None, help="static friction coefficient")
    p.add_argument("--theta0", action=Degrees, default=0.0, help="initial angle [deg]")
    p.add_argument(
        "--omega0", type=float, default=0.0, help="initial angular velocity [sqrt(g/R) rad]"
    )
    p.add_argument("--theta-max", action=Degrees, default=math.inf, help="stop at this angle [deg]")
    p.add_argument("--t-max", type=float, default=1000.0, help="stop at this time [sqrt(R/g)]")
    p.add_argument(
        "--rule",
        choices=("paper", "normal_force"),
        default="paper",
        help="lift-off rule (default: the paper's)",
    )
    p.add_argument("--rtol", type=float, default=1e-10)
    p.add_argument("--atol", type=float, default=1e-12)
    add_integrator(p)
    p.add_argument("--json", action="store_true", help="print machine-readable JSON")
    p.set_defaults(func=_cmd_roll)


def _roll_summary(res: RollResult, alpha_deg: float, integrator: str) -> dict[str, object]:
    end = len(res.t) - 1
    return {
        "body": {"chi": res.body.chi, "km": res.body.km, "Ic": res.body.Ic, "Icm": res.body.Icm},
        "alpha_deg": alpha_deg,
        "mu_s": res.mu_s,
        "rule": res.rule,
        "integrator": integrator,
        "status": res.status,
        "message": res.message,
        "terminal_event": res.terminal_event,
        "t": float(res.t[end]),
        "theta_deg": math.degrees(res.theta[end]),
        "omega": float(res.omega[end]),
        "Fx": float(res.Fx[end]),
        "Fy": float(res.Fy[end]),
        "friction_ratio": (  # the core's |Fx|/Fy; +inf (F_y <= 0) is not JSON: None
            float(res.friction_ratio[end]) if math.isfinite(res.friction_ratio[end]) else None
        ),
        "events": [
            {"name": e.name, "t": e.t, "theta_deg": math.degrees(e.theta), "omega": e.omega}
            for e in res.events
        ],
        "steps": end,
        "nfev": res.nfev,
        "units": "g = R = M = 1: time in sqrt(R/g), omega in sqrt(g/R) rad, forces in M g",
    }


def _mu(mu_s: float | None) -> str:
    return "None (enough friction)" if mu_s is None else f"{mu_s:g}"


def _cmd_roll(args: argparse.Namespace) -> int:
    body = Cylinder(args.chi, args.km)
    res = roll(
        body,
        math.radians(args.alpha),
        theta0=math.radians(args.theta0),
        omega0=args.omega0,
        mu_s=args.mu_s,
        t_max=args.t_max,
        theta_max=math.radians(args.theta_max),
        rtol=args.rtol,
        atol=args.atol,
        rule=args.rule,
        integrator=args.integrator,
    )
    s = _roll_summary(res, args.alpha, args.integrator)
    if args.json:
        print(json.dumps(s, indent=2))
        return 0
    ratio = s["friction_ratio"]
    rows = [
        (
            "body",
            f"chi = {body.chi:g}, km = {body.km:g}  (I_C = {body.Ic:.6g}, I_CM = {body.Icm:.6g} "
            "M R^2)",
        ),
        ("ramp", f"alpha = {args.alpha:g} deg, mu_s = {_mu(args.mu_s)}, rule = {args.rule}"),
        ("outcome", f"{res.message}"),
        ("time t", f"{s['t']:.10g} sqrt(R/g)"),
        ("angle theta", f"{s['theta_deg']:.10g} deg"),
        ("rate theta'", f"{s['omega']:.10g} sqrt(g/R)"),
        ("friction Fx", f"{s['Fx']:+.6e} M g"),
        ("normal Fy", f"{s['Fy']:+.6e} M g"),
        ("|Fx|/Fy", "n/a (Fy <= 0)" if ratio is None else f"{ratio:.6g}"),
        ("integrator", args.integrator),
        ("steps", f"{s['steps']} accepted, {res.nfev} evaluations"),
    ]
    width = max(len(k) for k, _ in rows)
    for k, v in rows:
        print(f"{k:<{width}}  {v}")
    if res.events:
        print("\nevents")
        head = ("name", "t [sqrt(R/g)]", "theta [deg]", "omega [sqrt(g/R)]")
        print("  {:<18} {:>16} {:>16} {:>17}".format(*head))
        for e in res.events:
            t, theta, omega = (bounded(x, ".10f") for x in (e.t, math.degrees(e.theta), e.omega))
            print(f"  {e.name:<18} {t:>16} {theta:>16} {omega:>17}")
    return 0
