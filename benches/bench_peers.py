"""eccjump side by side with the ODE peers a user could pick from PyPI (issue 10 baseline).

One process, same equation, same tolerances (rtol 1e-10, atol 1e-12 unless told), CPU time
(``time.process_time``) and wall time, and a check that every peer finds the same lift-off
angle theta_J as eccjump (the largest difference is printed).

a. ``roll``: one pure-rolling run from rest at theta = 0 to the paper's lift-off
   (L = chi theta'^2 cos theta - cos alpha, rising) for a few (alpha, chi, k_m):
   eccjump.roll against scipy solve_ivp (RK45, DOP853; terminal event), numbalsoda's dop853
   in a numba loop, pydiffsol (tsit45, a DiffSL ``stop`` event) and diffrax (Dopri5, Dopri8,
   ``diffrax.Event`` with an optimistix Newton root finder; jitted, x64, CPU).
   numbalsoda has no events; what a user does (and this file does): integrate in windows on
   a t_eval grid (dense output, samples every ~2 pi/``--samples-per-turn`` of theta), find
   the first sample where an event function has changed sign, then locate the root by
   Illinois (regula falsi) on re-integrations from the sample before it.
a'. ``--parts accuracy``: the same runs at equal accuracy instead of equal tolerances: each
   route (eccjump RK45 and DOP853, numbalsoda, pydiffsol) on an rtol ladder 1e-6 ... 1e-12,
   its error against the exact theta_J of the closed form, and its CPU time at the loosest
   rtol from which on it stays within 1e-8, 1e-9, 1e-10 rad (a work-precision comparison).
b. a batch of random points (alpha in (0, pi/2), chi in (1e-3, 1), k_m = u (1 - chi),
   mu_s = 1) to the FIRST event (lift-off L >= 0, F_y <= 0, mu_s F_y - |F_x| < 0, or
   theta = 2 pi n*): ``eccjump.jarm(method="ode")`` against a numba loop over numbalsoda's
   dop853 doing the same first-event classification (no continuation after a slip).
c. closed form: ``eccjump.jarm`` on 10^6 random points and ``eccjump.region`` on the 100^3
   grid of bench_region.py (targets < 1 s, < 0.7 s), and the ODE route's map (target < 10 s;
   by default timed on a 40^3 sub-grid of the 100^3 axes and extrapolated, ``--ode-grid 100``
   for the full map).
d. ``--write-snapshot`` / ``--check-snapshot``: SHA-256 digests and per-reason counts of the
   100^3 closed-form map and the 10^6 random points (reasons, theta_J bytes) in
   ``benches/snapshot.json``; the check recomputes with 1 thread and with all threads.

Peers that are not installed are skipped with a note (``pip install -e '.[bench]'``).

Run:  python benches/bench_peers.py [--parts roll,accuracy,batch,closed,ode] [--batch 10000]
                                   [--json PATH]

Every part's figures also go to ``--json`` (default bench_peers.json in the current directory).
"""

from __future__ import annotations

import argparse
import hashlib
import json
import math
import os
import platform
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import results

import eccjump

HERE = Path(__file__).resolve().parent
SNAPSHOT = HERE / "snapshot.json"
TAU = 2.0 * math.pi
MU_S = 1.0
#: eccjump's Runge-Kutta pairs (the ``integrator`` argument)
INTEGRATORS = ("RK45", "DOP853", "Vern9")
ROOT_TOL = 1e-12  # diffrax event: optimistix Newton tolerance (1e-14 does not converge)
# (alpha [deg], chi, k_m): runs that end at the paper's lift-off (F_y stays > 0 before it)
CASES = [(40.0, 0.15, 0.02), (70.0, 0.1, 0.27), (30.0, 0.1, 0.09), (10.0, 0.1, 0.54)]

NOTES: list[str] = []
#: every part's figures, by part, for the results file
RESULTS: dict[str, Any] = {}


def note(msg: str) -> None:
    NOTES.append(msg)
    print(f"note: {msg}")


# ------------------------------------------------------------------------------------------
# timing
# ------------------------------------------------------------------------------------------
def per_call(fn: Callable[[], object], number: int, repeat: int) -> tuple[float, float]:
    """(wall, CPU) seconds per call: the best mean of `repeat` rounds of `number` calls."""
    best_w = best_c = math.inf
    for _ in range(max(1, repeat)):
        t0, c0 = time.perf_counter(), time.process_time()
        for _ in range(max(1, number)):
            fn()
        best_w = min(best_w, (time.perf_counter() - t0) / number)
        best_c = min(best_c, (time.process_time() - c0) / number)
    return best_w, best_c


def timed(fn: Callable[[], object]) -> tuple[float, float, object]:
    t0, c0 = time.perf_counter(), time.process_time()
    out = fn()
    return time.perf_counter() - t0, time.process_time() - c0, out


def params(alpha: float, chi: float, km: float) -> np.ndarray:
    """[chi, sin alpha, cos alpha, I~_C]: what every peer's right-hand side needs."""
    ic = km + chi * chi / (1.0 - km)
    return np.array([chi, math.sin(alpha), math.cos(alpha), ic])


# ------------------------------------------------------------------------------------------
# peers, imported lazily (each returns None with a note when missing)
# ------------------------------------------------------------------------------------------
def scipy_peer(method: str):
    try:
        from bench_roll import scipy_roll  # the user's scipy script of bench_roll.py
    except ImportError as e:  # pragma: no cover - scipy is in the test extra
        note(f"scipy not installed ({e}); skipped")
        return None

    def run(p: np.ndarray, rtol: float, atol: float) -> float:
        chi, sa, ca, ic = (float(v) for v in p)
        return scipy_roll(math.atan2(sa, ca), chi, ic, rtol, atol, method)

    return run


_NB: dict | None = None


def numba_kernels():
    """numba-compiled first-event search over numbalsoda's dop853 (None if missing)."""
    global _NB
    if _NB is not None:
        return _NB or None
    try:
        import numba as nb
        from numbalsoda import dop853, lsoda_sig
    except ImportError as e:
        note(f"numbalsoda/numba not installed ({e}); skipped")
        _NB = {}
        return None

    @nb.cfunc(lsoda_sig)
    def rhs(t, u, du, p):  # p: chi, sin alpha, cos alpha, I~_C
        chi, sa, ca, ic = p[0], p[1], p[2], p[3]
        s, c = math.sin(u[0]), math.cos(u[0])
        w = u[1]
        du[0] = w
        du[1] = (chi * w * w * s + chi * (sa * c + ca * s) + sa) / (ic + 1.0 + 2.0 * chi * c)

    @nb.njit(cache=False)
    def event(th, w, p, mu, th_end, k):
        """Event function k (violated when >= 0; slip when > 0): 0 L, 1 -F_y,
        2 |F_x| - mu F_y, 3 theta - theta_end."""
        if k == 3:
            return th - th_end
        chi, sa, ca, ic = p[0], p[1], p[2], p[3]
        s, c = math.sin(th), math.cos(th)
        w2 = w * w
        if k == 0:
            return chi * w2 * c - ca
        wdd = (chi * w2 * s + chi * (sa * c + ca * s) + sa) / (ic + 1.0 + 2.0 * chi * c)
        fy = ca - chi * w2 * c - chi * wdd * s
        if k == 1:
            return -fy
        fx = -sa - chi * w2 * s + (1.0 + chi * c) * wdd
        return abs(fx) - mu * fy

    @nb.njit(cache=False)
    def violated(b, k):
        return b > 0.0 if k == 2 else b >= 0.0

    @nb.njit(cache=False)
    def illinois(fp, p, mu, th_end, k, ya, ta, tb, fa, fb, rtol, atol):
        """Root of event k in (ta, tb] by Illinois; y(t) by re-integrating from (ta, ya)."""
        t0 = ta
        te = np.empty(2)
        te[0] = t0
        tc, yc0, yc1 = tb, 0.0, 0.0
        side = 0
        for _ in range(60):
            tc = (ta * fb - tb * fa) / (fb - fa)
            if not (ta < tc < tb):
                tc = 0.5 * (ta + tb)
            te[1] = tc
            us, _ok = dop853(fp, ya, te, p, rtol, atol, 100000)
            yc0, yc1 = us[1, 0], us[1, 1]
            fc = event(yc0, yc1, p, mu, th_end, k)
            if violated(fc, k):
                tb, fb = tc, fc
                if side == -1:
                    fa *= 0.5
                side = -1
            else:
                ta, fa = tc, fc
                if side == 1:
                    fb *= 0.5
                side = 1
            if fc == 0.0 or tb - ta <= 1e-15 * (1.0 + abs(tc)):
                break
        return tc, yc0, yc1

    @nb.njit(cache=False)
    def first_event(fp, p, mu, th_end, nev, rtol, atol, spt, t_max):
        """First event among 0..nev-1 along rolling from rest: (kind, t, theta, omega);
        kind -1: t_max reached, -2: the integrator failed."""
        hth = 2.0 * math.pi / spt
        K = spt  # samples per window
        y = np.zeros(2)
        t = 0.0
        for k in range(nev):
            if violated(event(0.0, 0.0, p, mu, th_end, k), k):
                return k, 0.0, 0.0, 0.0
        te = np.empty(K + 1)
        chi, sa, ca, ic = p[0], p[1], p[2], p[3]
        while t < t_max:
            s, c = math.sin(y[0]), math.cos(y[0])
            wdd = (chi * y[1] ** 2 * s + chi * (sa * c + ca * s) + sa) / (ic + 1 + 2 * chi * c)
            # Delta theta per sample <= ~hth from the speed and from the acceleration
            dt = hth / (abs(y[1]) + math.sqrt(hth * K * abs(wdd)) + 1e-300)
            for j in range(K + 1):
                te[j] = t + j * dt
            us, ok = dop853(fp, y, te, p, rtol, atol, 1000000)
            if not ok:
                return -2, t, y[0], y[1]
            for j in range(1, K + 1):
                hit = False
                for k in range(nev):
                    if violated(event(us[j, 0], us[j, 1], p, mu, th_end, k), k):
                        hit = True
                if hit:
                    ya = us[j - 1].copy()
                    best_k, best_t, bth, bw = -1, math.inf, 0.0, 0.0
                    for k in range(nev):
                        fb = event(us[j, 0], us[j, 1], p, mu, th_end, k)
                        if violated(fb, k):
                            fa = event(ya[0], ya[1], p, mu, th_end, k)
                            tk, th, w = illinois(
                                fp, p, mu, th_end, k, ya, te[j - 1], te[j], fa, fb, rtol, atol
                            )
                            if best_k < 0 or tk < best_t - 1e-12 * (1.0 + abs(best_t)):
                                best_k, best_t, bth, bw = k, tk, th, w
                    return best_k, best_t, bth, bw
            y = us[K].copy()
            t = te[K]
        return -1, t, y[0], y[1]

    @nb.njit(cache=False)
    def roll_liftoff(fp, p, rtol, atol, spt):
        kind, _t, th, _w = first_event(fp, p, 0.0, 0.0, 1, rtol, atol, spt, 1e3)
        return th if kind == 0 else math.nan

    @nb.njit(cache=False)
    def classify(fp, alpha, chi, km, mu, rtol, atol, spt, max_turns, reason, theta):
        """Reason code (eccjump's numbering; a slip is 4, no continuation) and theta of the
        first event, for 0 < alpha < pi/2, 0 < chi < 1, 0 <= km < 1 - chi."""
        p = np.empty(4)
        for i in range(alpha.size):
            a, c, k = alpha[i], chi[i], km[i]
            ic = k + c * c / (1.0 - k)
            icm = k * (1.0 - k + c * c) / (1.0 - k)
            p[0], p[1], p[2], p[3] = c, math.sin(a), math.cos(a), ic
            gamma = (ic + 1.0 + 2.0 * c) / (4.0 * math.pi * c)
            ta = math.tan(a)
            n_star = math.floor(gamma / ta) + 1 if gamma / ta < 1e15 else max_turns + 1
            while n_star - 1 >= 1 and (n_star - 1) * ta > gamma:
                n_star -= 1
            while n_star * ta <= gamma:
                n_star += 1
            th_end = 2.0 * math.pi * min(n_star, max_turns)
            kind, _t, th, _w = first_event(fp, p, mu, th_end, 4, rtol, atol, spt, 1e12)
            theta[i] = th
            if kind == 0:  # the paper's lift-off: judge it (green window, Njumpfn, ineq2)
                n = math.ceil(th / (2.0 * math.pi))
                s, cs = math.sin(th), math.cos(th)
                ip = ic + 1.0 + 2.0 * c * cs
                fyj = -c * (1.0 + c * cs) * (s / cs) * math.sin(a + th) / ip
                if th <= 0.0:
                    reason[i] = 2
                elif not (n >= 1 and 2 * math.pi * n - a < th < 2 * math.pi * n) or fyj <= 0:
                    reason[i] = 3
                elif -(icm + c * c * s * s) / (c * s * (1.0 + c * cs)) > mu:
                    reason[i] = 5
                else:
                    reason[i] = 0
            elif kind == 1:
                reason[i] = 3
            elif kind == 2:
                reason[i] = 4
            elif kind == 3:
                reason[i] = 7 if n_star > max_turns else 1
                theta[i] = math.nan
            else:
                reason[i] = 9
                theta[i] = math.nan

    _NB = dict(fp=rhs.address, roll=roll_liftoff, classify=classify)
    return _NB


def numbalsoda_peer(spt: int):
    kern = numba_kernels()
    if kern is None:
        return None
    fp, roll = kern["fp"], kern["roll"]

    def run(p: np.ndarray, rtol: float, atol: float) -> float:
        return roll(fp, p, rtol, atol, spt)

    return run


def pydiffsol_peer():
    try:
        import pydiffsol as ds
    except ImportError as e:
        note(f"pydiffsol not installed ({e}); skipped")
        return None
    code = """
in_i { chi = 0.15, sa = 0.5, ca = 0.8, ic = 0.1 }
u_i { th = 0, w = 0 }
F_i { w, (chi * w * w * sin(th) + chi * (sa * cos(th) + ca * sin(th)) + sa)
         / (ic + 1 + 2 * chi * cos(th)) }
stop_i { chi * w * w * cos(th) - ca }
"""
    try:
        ode = ds.Ode(code, ode_solver=ds.tsit45)
    except Exception as e:  # no JIT backend in this wheel, etc.
        note(f"pydiffsol installed but the DiffSL model does not compile ({e}); skipped")
        return None

    def run(p: np.ndarray, rtol: float, atol: float) -> float:
        if ode.rtol != rtol or ode.atol != atol:
            ode.rtol, ode.atol = rtol, atol
        sol = ode.solve(p, 1e3)
        return float(sol.ys[0, -1])

    return run


def diffrax_peer(solver_name: str):
    try:
        os.environ.setdefault("JAX_PLATFORMS", "cpu")
        import jax

        jax.config.update("jax_enable_x64", True)
        import diffrax
        import jax.numpy as jnp
        import optimistix as optx
    except ImportError as e:
        note(f"diffrax/jax not installed ({e}); skipped")
        return None

    def vf(t, y, args):
        chi, sa, ca, ic = args[0], args[1], args[2], args[3]
        s, c = jnp.sin(y[0]), jnp.cos(y[0])
        w = y[1]
        return jnp.stack(
            [w, (chi * w * w * s + chi * (sa * c + ca * s) + sa) / (ic + 1 + 2 * chi * c)]
        )

    def cond(t, y, args, **kwargs):
        return args[0] * y[1] * y[1] * jnp.cos(y[0]) - args[2]

    solver = getattr(diffrax, solver_name)()
    compiled: dict[tuple[float, float], Callable] = {}

    def make(rtol: float, atol: float):
        @jax.jit
        def go(args):
            sol = diffrax.diffeqsolve(
                diffrax.ODETerm(vf),
                solver,
                0.0,
                1e3,
                None,
                jnp.zeros(2),
                args=args,
                stepsize_controller=diffrax.PIDController(rtol=rtol, atol=atol),
                max_steps=1_000_000,
                event=diffrax.Event(cond, optx.Newton(rtol=ROOT_TOL, atol=ROOT_TOL)),
                saveat=diffrax.SaveAt(t1=True),
            )
            return sol.ys[-1, 0]

        return go

    def run(p: np.ndarray, rtol: float, atol: float) -> float:
        key = (rtol, atol)
        if key not in compiled:
            compiled[key] = make(rtol, atol)
        return float(compiled[key](jnp.asarray(p)).block_until_ready())

    return run


# ------------------------------------------------------------------------------------------
# a. roll
# ------------------------------------------------------------------------------------------
def part_roll(args) -> None:
    rtol, atol = args.rtol, args.atol
    peers: list[tuple[str, Callable | None, int, int]] = [
        ("scipy solve_ivp RK45", scipy_peer("RK45"), 3, 2),
        ("scipy solve_ivp DOP853", scipy_peer("DOP853"), 3, 2),
        ("numbalsoda dop853 (numba)", numbalsoda_peer(args.samples_per_turn), 5, args.number),
        ("pydiffsol tsit45", pydiffsol_peer(), 5, args.number),
        ("diffrax Dopri5 (jit)", diffrax_peer("Dopri5"), 3, max(1, args.number // 2)),
        ("diffrax Dopri8 (jit)", diffrax_peer("Dopri8"), 3, max(1, args.number // 2)),
    ]
    print(f"\n== a. roll: rest -> paper's lift-off, rtol {rtol:g}, atol {atol:g} ==")
    hdr = (
        f"{'case (alpha deg, chi, km)':<26}{'route':<28}{'theta_J [deg]':>20}"
        f"{'|dtheta| rad':>13}{'us/call wall':>14}{'us/call CPU':>13}{'peer/ecc CPU':>13}"
    )
    print(hdr)
    print("-" * len(hdr))
    worst: dict[str, float] = {}
    ratios: dict[str, list[float]] = {}
    rows: list[dict[str, Any]] = []
    for a_deg, chi, km in CASES:
        alpha = math.radians(a_deg)
        body = eccjump.Cylinder(chi, km)
        kw = {"rtol": rtol, "atol": atol, "integrator": args.integrator}
        res = eccjump.roll(body, alpha, **kw)
        if res.terminal_event != "liftoff":
            raise SystemExit(f"case {a_deg, chi, km} ends at {res.terminal_event}, not liftoff")
        ref = float(res.theta[-1])
        tw, tc = per_call(lambda: eccjump.roll(body, alpha, **kw), 5, args.number)  # noqa: B023
        case = f"({a_deg:g}, {chi:g}, {km:g})"
        print(
            f"{case:<26}{'eccjump.roll ' + args.integrator:<28}{math.degrees(ref):>20.12f}{'':>13}"
            f"{tw * 1e6:>14.2f}{tc * 1e6:>13.2f}{1.0:>13.2f}"
        )
        rows.append(
            {
                "case": [a_deg, chi, km],
                "route": f"eccjump.roll {args.integrator}",
                "theta_J_deg": math.degrees(ref),
                "us_wall": tw * 1e6,
                "us_cpu": tc * 1e6,
                "peer_over_eccjump_cpu": 1.0,
            }
        )
        p = params(alpha, chi, km)
        for name, fn, rep, num in peers:
            if fn is None:
                continue
            try:
                th = fn(p, rtol, atol)  # warm-up (JIT compilation) and the result
            except Exception as e:  # e.g. diffrax's Newton root find not converging
                msg = str(e).replace("\n", " ")
                i = msg.find("_EquinoxRuntimeError")
                msg = msg[i:] if i >= 0 else msg
                print(f"{'':<26}{name:<28}  FAILED: {msg[:150]}")
                note(f"{name} failed on case {case}: {msg[:300]}")
                rows.append({"case": [a_deg, chi, km], "route": name, "failed": msg[:300]})
                continue
            pw, pc = per_call(lambda: fn(p, rtol, atol), num, rep)  # noqa: B023
            d = abs(th - ref)
            wrong = d > 1e-6
            if wrong:
                note(
                    f"{name} on case {case}: stops at theta = {math.degrees(th)!r} deg, not at "
                    f"eccjump's lift-off {math.degrees(ref)!r} deg (a missed event)"
                )
            else:
                worst[name] = max(worst.get(name, 0.0), d)
                ratios.setdefault(name, []).append(pc / tc)
            print(
                f"{'':<26}{name:<28}{math.degrees(th):>20.12f}{d:>13.1e}"
                f"{pw * 1e6:>14.2f}{pc * 1e6:>13.2f}{pc / tc:>13.2f}"
                f"{'  WRONG EVENT' if wrong else ''}"
            )
            rows.append(
                {
                    "case": [a_deg, chi, km],
                    "route": name,
                    "theta_J_deg": math.degrees(th),
                    "dtheta_rad": d,
                    "us_wall": pw * 1e6,
                    "us_cpu": pc * 1e6,
                    "peer_over_eccjump_cpu": pc / tc,
                    "wrong_event": wrong,
                }
            )
    print(
        "largest |theta_J(peer) - theta_J(eccjump)| over the cases where the peer found "
        "the same event [rad]: " + ", ".join(f"{k} {v:.1e}" for k, v in worst.items())
    )
    print(
        "peer CPU time / eccjump CPU time per call (min-max over the cases; > 1: eccjump "
        "faster): " + ", ".join(f"{k} {min(v):.2f}-{max(v):.2f}" for k, v in ratios.items())
    )
    RESULTS["roll"] = {
        "rtol": rtol,
        "atol": atol,
        "integrator": args.integrator,
        "rows": rows,
        "largest_dtheta_rad": worst,
        "peer_over_eccjump_cpu_min_max": {k: [min(v), max(v)] for k, v in ratios.items()},
    }


# ------------------------------------------------------------------------------------------
# a'. roll at equal accuracy (work-precision)
# ------------------------------------------------------------------------------------------
#: rtol ladder of the work-precision part: 1e-6 ... 1e-12 in half decades (atol = rtol / 100)
LADDER = [10.0 ** (-k / 2) for k in range(12, 25)]
#: accuracy levels |theta_J - exact| [rad] at which the routes are compared
ACCURACY = [1e-8, 1e-9, 1e-10]


def exact_theta_J(alpha: float, chi: float, km: float) -> float:
    """The paper's lift-off angle from rest by the closed form (no slip: mu_s huge), an
    independent route to the integrations' theta_J."""
    return float(eccjump.jarm(alpha, chi, km, 1e9).theta_J)


def reached(errors: list[float], level: float) -> int | None:
    """Index of the loosest rung of LADDER from which on every tighter rung has an error
    <= level (None if not even the tightest has): where a route reliably reaches it."""
    i = None
    for k in range(len(errors) - 1, -1, -1):
        if not errors[k] <= level:
            break
        i = k
    return i


def equal_accuracy_table(
    table: dict[str, list[tuple[float, float]]],
    ladder: list[float],
    name_width: int,
    width: int,
    cell: Callable[[float, float, float | None], str],
    out: list[dict[str, Any]] | None = None,
) -> dict[tuple[str, float], float]:
    """Prints, for each route of `table` (rows of (error, cost) along `ladder`) and each
    level of ACCURACY, the cost at the loosest rung that reaches the level (`reached`), as
    cell(cost, rtol, ratio); eccjump's routes come first and set the best cost per level,
    and a peer's ratio is its cost over that best (None for eccjump). Returns the peers'
    ratios by (route, level). Each cell also goes to `out` (if given) as a dict."""
    print(
        f"{'route':<{name_width}}"
        + "".join(f"{'<= ' + format(lv, 'g'):>{width}}" for lv in ACCURACY)
    )
    best: dict[float, float] = {}
    ratios: dict[tuple[str, float], float] = {}
    for name, rows in table.items():
        cells = []
        for lv in ACCURACY:
            i = reached([e for e, _ in rows], lv)
            if i is None:
                cells.append(f"{'not reached':>{width}}")
                if out is not None:
                    out.append({"route": name, "level": lv, "reached": False})
                continue
            cost = rows[i][1]
            ratio = None
            if name.startswith("eccjump"):
                best[lv] = min(best.get(lv, math.inf), cost)
            else:
                ratio = cost / best[lv] if lv in best else math.nan
                ratios[(name, lv)] = ratio
            cells.append(cell(cost, ladder[i], ratio).rjust(width))
            if out is not None:
                out.append(
                    {
                        "route": name,
                        "level": lv,
                        "reached": True,
                        "rtol": ladder[i],
                        "cost": cost,
                        "ratio": ratio,
                    }
                )
        print(f"{name:<{name_width}}" + "".join(cells))
    return ratios


def renamed_cost(cells: list[dict[str, Any]], key: str, scale: float) -> list[dict[str, Any]]:
    """equal_accuracy_table's cells with their "cost" as `key`, in its unit (cost x scale)."""
    return [
        {k: v for k, v in d.items() if k != "cost"}
        | ({key: d["cost"] * scale} if "cost" in d else {})
        for d in cells
    ]


def part_accuracy(args) -> None:
    """Each route's CPU time per call at the loosest tolerance that reaches an accuracy
    level, against the exact theta_J of the closed form: the comparison at equal accuracy
    (equal tolerances give each route a different error)."""
    peers = [
        ("numbalsoda dop853 (numba)", numbalsoda_peer(args.samples_per_turn)),
        ("pydiffsol tsit45", pydiffsol_peer()),
    ]
    print("\n== a'. roll at equal accuracy: CPU us per call at the loosest rtol (atol = rtol/100)")
    print("   of 1e-6 ... 1e-12 (half decades) from which on |theta_J - exact| <= the level ==")
    cells: dict[str, dict[tuple[str, float], float]] = {}  # case -> (peer, level) -> ratio
    cases_out: list[dict[str, Any]] = []
    for a_deg, chi, km in CASES:
        alpha = math.radians(a_deg)
        body = eccjump.Cylinder(chi, km)
        p = params(alpha, chi, km)
        # every route as f(rtol, atol) -> theta_J of this case
        routes: list[tuple[str, Callable]] = [
            (
                f"eccjump.roll {integ}",
                lambda r, a, i=integ: float(
                    eccjump.roll(body, alpha, rtol=r, atol=a, integrator=i).theta[-1]  # noqa: B023
                ),
            )
            for integ in INTEGRATORS
        ]
        routes += [(n, lambda r, a, f=f: f(p, r, a)) for n, f in peers if f is not None]  # noqa: B023
        exact = exact_theta_J(alpha, chi, km)
        case = f"({a_deg:g}, {chi:g}, {km:g})"
        print(f"\ncase {case}: exact theta_J {exact!r} rad")
        table: dict[str, list[tuple[float, float]]] = {}
        for name, fn in routes:
            rows = []
            for rtol in LADDER:
                atol = rtol / 100.0
                try:
                    th = fn(rtol, atol)
                except Exception:  # a peer failing at a rung: that rung is not reached
                    rows.append((math.inf, math.nan))
                    continue
                _w, c = per_call(
                    lambda: fn(rtol, atol),  # noqa: B023
                    max(1, args.number // 4),
                    args.rung_repeat,
                )
                rows.append((abs(th - exact), c))
            table[name] = rows
        reached_out: list[dict[str, Any]] = []
        ratios = equal_accuracy_table(
            table,
            LADDER,
            28,
            22,
            lambda c, rtol, _r: f"{c * 1e6:>10.2f} us @{rtol:<8.0e}",
            reached_out,
        )
        cells[case] = ratios
        cases_out.append(
            {
                "case": [a_deg, chi, km],
                "exact_theta_J": exact,
                "ladder": [
                    {"route": n, "rtol": r, "error": e, "cpu_us": c * 1e6}
                    for n, rows in table.items()
                    for r, (e, c) in zip(LADDER, rows, strict=True)
                ],
                "at_level": renamed_cost(reached_out, "cpu_us", 1e6),
            }
        )
    summary: dict[tuple[str, float], list[float]] = {}
    for ratios in cells.values():
        for key, ratio in ratios.items():
            summary.setdefault(key, []).append(ratio)
    print(
        "\npeer CPU / eccjump CPU (the fastest of its integrators) at equal accuracy, "
        "min-max over the cases:"
    )
    for (name, lv), v in sorted(summary.items()):
        if not name.startswith("eccjump"):
            print(f"  {name:<28} <= {lv:g} rad: {min(v):.2f}-{max(v):.2f}")
    RESULTS["accuracy"] = {
        "levels_rad": ACCURACY,
        "cases": cases_out,
        **cell_table(cells, [n for n, f in peers if f is not None]),
    }


def cell_table(
    cells: dict[str, dict[tuple[str, float], float]], peers: list[str]
) -> dict[str, Any]:
    """Prints every cell (case x peer x accuracy level) of the equal-accuracy comparison,
    peer CPU / eccjump CPU, and how many reach issue 10's target of 3x (a cell a peer did
    not reach counts as reached by eccjump; one eccjump did not reach, as missed). Returns
    the cells and the count for the results file."""
    if not peers:
        return {"cells": [], "cells_met": 0, "cells_total": 0}
    head = "".join(
        f"{p.split()[0] + ' <= ' + format(lv, 'g'):>22}" for p in peers for lv in ACCURACY
    )
    print(f"\nevery cell, peer CPU / eccjump CPU:\n{'case':<20}{head}")
    met = total = 0
    out = []
    for case, ratios in cells.items():
        row = []
        for p in peers:
            for lv in ACCURACY:
                r = ratios.get((p, lv), math.inf)
                total += 1
                met += r >= 3.0  # NaN: eccjump did not reach the level
                row.append(f"{r:>22.2f}")
                out.append(
                    {
                        "case": case,
                        "peer": p,
                        "level": lv,
                        "ratio": r,
                        "peer_reached": not math.isinf(r),
                        "eccjump_reached": not math.isnan(r),
                        "met": bool(r >= 3.0),
                    }
                )
        print(f"{case:<20}" + "".join(row))
    print(f"cells at >= 3x: {met} of {total}")
    return {"cells": out, "cells_met": int(met), "cells_total": total}


# ------------------------------------------------------------------------------------------
# b. batch to the first event
# ------------------------------------------------------------------------------------------
def random_points(n: int, seed: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """alpha ~ U(0, pi/2), chi ~ U(1e-3, 1), k_m = u (1 - chi), u ~ U(0, 1) (the issue's)."""
    rng = np.random.default_rng(seed)
    alpha = rng.uniform(0.0, math.pi / 2, n)
    chi = rng.uniform(1e-3, 1.0, n)
    km = rng.uniform(0.0, 1.0, n) * (1.0 - chi)
    return alpha, chi, km


def first_class(reason: np.ndarray) -> np.ndarray:
    """The first event's verdict: SLIP_AT_JUMP (5), SLIP_BEFORE (4) and SLIP (10, from
    ``stop_at_slip``) all mean "slipped first" (telling the first two apart needs the
    continuation the peer loop does not do)."""
    r = reason.astype(np.int64)
    r[(r == 5) | (r == 10)] = 4
    return r


def part_batch(args) -> None:
    print(f"\n== b. {args.batch} random points to the first event (mu_s = 1), ODE route ==")
    kern = numba_kernels()
    a, c, k = random_points(args.batch, args.seed)
    eccjump.jarm(a[:10], c[:10], k[:10], MU_S, method="ode", integrator=args.integrator)
    rows = []
    for thr in (1, 0):
        w, cpu, res = timed(
            lambda thr=thr: eccjump.jarm(
                a,
                c,
                k,
                MU_S,
                method="ode",
                rtol=args.rtol,
                atol=args.atol,
                n_threads=thr,
                integrator=args.integrator,
                stop_at_slip=args.stop_at_slip,
            )
        )
        rows.append((f"eccjump.jarm ode, {thr or os.cpu_count()} thr", w, cpu))
    ecc = res
    if kern is not None:
        reason = np.empty(a.size, np.uint8)
        theta = np.empty(a.size)
        fp, classify = kern["fp"], kern["classify"]
        classify(
            fp,
            a[:10],
            c[:10],
            k[:10],
            MU_S,
            args.rtol,
            args.atol,
            args.samples_per_turn,
            10_000,
            reason[:10],
            theta[:10],
        )
        w, cpu, _ = timed(
            lambda: classify(
                fp,
                a,
                c,
                k,
                MU_S,
                args.rtol,
                args.atol,
                args.samples_per_turn,
                10_000,
                reason,
                theta,
            )
        )
        rows.append(("numba loop, numbalsoda dop853", w, cpu))
    print(f"{'route':<34}{'wall s':>9}{'CPU s':>9}{'us/pt CPU':>11}{'CPU vs numba':>14}")
    for name, w, cpu in rows:
        rel = f"{cpu / rows[-1][2]:.2f}" if kern is not None else "-"
        print(f"{name:<34}{w:>9.3f}{cpu:>9.3f}{cpu / a.size * 1e6:>11.1f}{rel:>14}")
    RESULTS["batch"] = {
        "points": int(a.size),
        "rtol": args.rtol,
        "atol": args.atol,
        "integrator": args.integrator,
        "stop_at_slip": args.stop_at_slip,
        "rows": [
            {
                "route": name,
                "wall_s": w,
                "cpu_s": cpu,
                "us_per_point_cpu": cpu / a.size * 1e6,
                "cpu_vs_numba": cpu / rows[-1][2] if kern is not None else None,
            }
            for name, w, cpu in rows
        ],
    }
    if kern is None:
        return
    er = ecc.reason
    eth = np.where(er == 0, ecc.theta_J, ecc.theta_event)
    same_j = int(np.sum((er == 0) == (reason == 0)))
    fc_e, fc_p = first_class(er), first_class(reason)
    same_c = int(np.sum(fc_e == fc_p))
    both = (fc_e == fc_p) & np.isfinite(eth) & np.isfinite(theta)
    d = np.abs(eth[both] - theta[both])
    print(
        f"agree: is_jarm {same_j}/{a.size} (JARMs: eccjump {int(np.sum(er == 0))}, numba "
        f"{int(np.sum(reason == 0))}); first-event verdict {same_c}/{a.size}; "
        f"theta of the event, {int(both.sum())} points: max |d| {d.max():.1e} rad, "
        f"median {np.median(d):.1e}, > 1e-8 rad at {int(np.sum(d > 1e-8))}"
    )
    RESULTS["batch"]["agree"] = {
        "is_jarm": same_j,
        "jarms_eccjump": int(np.sum(er == 0)),
        "jarms_numba": int(np.sum(reason == 0)),
        "first_event_verdict": same_c,
        "theta_points": int(both.sum()),
        "theta_max_diff_rad": float(d.max()) if d.size else math.nan,
        "theta_median_diff_rad": float(np.median(d)) if d.size else math.nan,
        "theta_over_1e-8": int(np.sum(d > 1e-8)),
    }
    bad = np.flatnonzero(fc_e != fc_p)
    for i in bad[: args.show]:
        print(
            f"  differs: alpha {a[i]!r}, chi {c[i]!r}, km {k[i]!r}: eccjump "
            f"{eccjump.Reason(int(er[i])).name} at {eth[i]!r}, numba code {int(reason[i])} "
            f"at {theta[i]!r}"
        )


def first_theta(reason: np.ndarray, theta_j: np.ndarray, theta_event: np.ndarray) -> np.ndarray:
    """theta of the first event of a classification: theta_J for a JARM, else theta_event."""
    return np.where(reason == 0, theta_j, theta_event)


def part_batch_accuracy(args) -> None:
    """Part b at equal accuracy: the ODE route (both pairs) and the numba loop on an rtol
    ladder over the same random points, each rung's CPU time (one thread) and error of the
    first event's angle against the closed form (exact), at the points where the route's
    first-event verdict is the closed form's. A route reaches an accuracy level at the
    loosest rung from which on the 99th percentile of the relative error stays within it."""
    kern = numba_kernels()
    n = args.batch
    print(f"\n== b'. {n} random points to the first event at equal accuracy (mu_s = 1) ==")
    a, c, k = random_points(n, args.seed)
    cf = eccjump.jarm(a, c, k, MU_S)
    ref_class = first_class(cf.reason)
    ref = first_theta(cf.reason, cf.theta_J, cf.theta_event)
    ladder = [10.0 ** (-q / 2) for q in range(12, 23)]  # 1e-6 ... 1e-11
    routes: list[tuple[str, Callable]] = []
    for integ in INTEGRATORS:

        def ecc(rtol, integ=integ):
            r = eccjump.jarm(
                a,
                c,
                k,
                MU_S,
                method="ode",
                rtol=rtol,
                atol=rtol / 100,
                n_threads=1,
                integrator=integ,
                stop_at_slip=args.stop_at_slip,
            )
            return first_class(r.reason), first_theta(r.reason, r.theta_J, r.theta_event)

        routes.append((f"eccjump.jarm ode {integ}", ecc))
    if kern is not None:
        fp, classify = kern["fp"], kern["classify"]
        reason = np.empty(n, np.uint8)
        theta = np.empty(n)
        spt = args.samples_per_turn
        classify(
            fp, a[:10], c[:10], k[:10], MU_S, 1e-8, 1e-10, spt, 10_000, reason[:10], theta[:10]
        )

        def numba_loop(rtol):
            classify(fp, a, c, k, MU_S, rtol, rtol / 100, spt, 10_000, reason, theta)
            return first_class(reason), theta.copy()

        routes.append(("numba loop, numbalsoda dop853", numba_loop))
    print(
        f"{'route':<32}{'rtol':>8}{'CPU s':>8}{'verdict differs':>17}{'p99 rel err':>13}"
        f"{'max rel err':>13}"
    )
    table: dict[str, list[tuple[float, float]]] = {}
    rungs: list[dict[str, Any]] = []
    for name, fn in routes:
        rows = []
        for rtol in ladder:
            t0 = time.process_time()
            cls, th = fn(rtol)
            cpu = time.process_time() - t0
            same = (cls == ref_class) & np.isfinite(th) & np.isfinite(ref)
            rel = np.abs(th[same] - ref[same]) / np.maximum(1.0, np.abs(ref[same]))
            p99 = float(np.quantile(rel, 0.99)) if rel.size else math.inf
            print(
                f"{name:<32}{rtol:>8.0e}{cpu:>8.2f}{int(np.sum(cls != ref_class)):>17}"
                f"{p99:>13.1e}{float(rel.max()) if rel.size else math.inf:>13.1e}"
            )
            rows.append((p99, cpu))
            rungs.append(
                {
                    "route": name,
                    "rtol": rtol,
                    "cpu_s": cpu,
                    "verdict_differs": int(np.sum(cls != ref_class)),
                    "p99_rel_error": p99,
                    "max_rel_error": float(rel.max()) if rel.size else math.inf,
                }
            )
        table[name] = rows
    print("\nCPU s for the batch at the loosest rtol from which on the p99 relative error stays")
    print("within the level (one thread):")
    at_level: list[dict[str, Any]] = []
    equal_accuracy_table(
        table,
        ladder,
        32,
        26,
        lambda c, rtol, r: f"{c:.3f} s @{rtol:.0e}" + (f" ({r:.2f}x)" if r is not None else ""),
        at_level,
    )
    RESULTS["batch_accuracy"] = {
        "points": n,
        "stop_at_slip": args.stop_at_slip,
        "levels_p99_rel": ACCURACY,
        "rungs": rungs,
        "at_level": renamed_cost(at_level, "cpu_s", 1.0),
    }


# ------------------------------------------------------------------------------------------
# c. closed form and ODE maps; d. snapshot
# ------------------------------------------------------------------------------------------
def grid(n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """bench_region.py's grid: alpha = linspace(pi/2n, pi/2, n), chi = (j + 1/2)/n,
    frac = l/n."""
    return (
        np.linspace(math.pi / (2 * n), math.pi / 2, n),
        (np.arange(n) + 0.5) / n,
        np.arange(n) / n,
    )


def best_of(fn: Callable[[], object], repeat: int) -> tuple[float, float, object]:
    best = (math.inf, math.inf, None)
    for _ in range(max(1, repeat)):
        w, c, out = timed(fn)
        if w < best[0]:
            best = (w, c, out)
        out = None
    return best


def verdict(value: float, target: float) -> str:
    return f"{'met' if value < target else 'NOT met'} (target < {target:g} s)"


def part_closed(args) -> None:
    print("\n== c. closed form (mu_s = 1, automatic n, paper rule, all threads) ==")
    a, c, k = random_points(args.points, args.seed)
    eccjump.jarm(a[:100], c[:100], k[:100], MU_S)
    stop = args.stop_at_slip
    w, cpu, res = best_of(lambda: eccjump.jarm(a, c, k, MU_S, stop_at_slip=stop), args.repeat)
    print(
        f"jarm, {args.points} random points: wall {w:.3f} s, CPU {cpu:.3f} s; "
        f"{verdict(w, 1.0) if args.points == 10**6 else ''}  JARMs {int(res.is_jarm.sum())}"
    )
    out: dict[str, Any] = {"stop_at_slip": stop, "repeat": args.repeat}
    out["jarm_random"] = {
        "points": args.points,
        "wall_s": w,
        "cpu_s": cpu,
        "jarms": int(res.is_jarm.sum()),
        "target_s": 1.0 if args.points == 10**6 else None,
    }
    ga, gc, gf = grid(args.grid)
    w, cpu, reg = best_of(
        lambda: eccjump.region(mu_s=MU_S, alpha=ga, chi=gc, km_frac=gf, stop_at_slip=stop),
        args.repeat,
    )
    print(
        f"region, {args.grid}^3 grid: wall {w:.3f} s, CPU {cpu:.3f} s; "
        f"{verdict(w, 0.7) if args.grid == 100 else ''}  JARMs {int(reg.is_jarm.sum())}"
    )
    out["region_grid"] = {
        "grid": args.grid,
        "wall_s": w,
        "cpu_s": cpu,
        "jarms": int(reg.is_jarm.sum()),
        "target_s": 0.7 if args.grid == 100 else None,
    }
    RESULTS["closed"] = out


def part_ode(args) -> None:
    print(
        f"\n== c. ODE route map (method='ode', {args.integrator}, rtol 1e-10, atol 1e-12, "
        f"stop_at_slip={args.stop_at_slip}, all threads) =="
    )
    ga, gc, gf = grid(100)
    m = args.ode_grid
    idx = np.unique(np.round(np.linspace(0, 99, m)).astype(int))
    sa, sc, sf = ga[idx], gc[idx], gf[idx]
    eccjump.region(mu_s=MU_S, alpha=sa[:3], chi=sc[:3], km_frac=sf[:3], method="ode")
    w, cpu, reg = timed(
        lambda: eccjump.region(
            mu_s=MU_S,
            alpha=sa,
            chi=sc,
            km_frac=sf,
            method="ode",
            integrator=args.integrator,
            stop_at_slip=args.stop_at_slip,
        )
    )
    n = reg.is_jarm.size
    RESULTS["ode"] = {
        "integrator": args.integrator,
        "stop_at_slip": args.stop_at_slip,
        "sub_grid": m,
        "points": int(n),
        "wall_s": w,
        "cpu_s": cpu,
        "extrapolated_1e6_wall_s": w * 1e6 / n,
        "target_s": 10.0,
    }
    if m >= 100:
        print(f"region ode, 100^3: wall {w:.2f} s, CPU {cpu:.2f} s; {verdict(w, 10.0)}")
    else:
        scale = 1e6 / n
        print(
            f"region ode, {m}^3 sub-grid of the 100^3 axes ({n} points): wall {w:.2f} s, "
            f"CPU {cpu:.2f} s; extrapolated to 10^6 points (x{scale:.1f}, an estimate: the "
            f"cost per point varies with alpha): wall ~{w * scale:.0f} s, CPU "
            f"~{cpu * scale:.0f} s; {verdict(w * scale, 10.0)}"
        )


def digest(x: np.ndarray) -> str:
    return hashlib.sha256(np.ascontiguousarray(x).tobytes()).hexdigest()


def summary(res) -> dict:
    codes = np.bincount(res.reason.ravel(), minlength=10)
    return {
        "reason_sha256": digest(res.reason.astype(np.uint8)),
        "theta_J_sha256": digest(res.theta_J.astype("<f8")),
        "counts": {eccjump.Reason(i).name: int(v) for i, v in enumerate(codes) if v},
    }


def snapshot_now(threads: int, seed: int) -> dict:
    ga, gc, gf = grid(100)
    reg = eccjump.region(mu_s=MU_S, alpha=ga, chi=gc, km_frac=gf, n_threads=threads)
    a, c, k = random_points(10**6, seed)
    pts = eccjump.jarm(a, c, k, MU_S, n_threads=threads)
    return {
        "map_100": {
            "what": "eccjump.region(alpha=linspace(pi/200, pi/2, 100), chi=(j+0.5)/100, "
            "km_frac=l/100, mu_s=1.0), closed form, paper rule, automatic n; reason as uint8, "
            "theta_J as "
            "little-endian float64, C order",
            "inputs_sha256": digest(np.concatenate([ga, gc, gf])),
            **summary(reg.result),
        },
        "random_1e6": {
            "what": f"eccjump.jarm(alpha, chi, km, 1.0) at 10^6 points of numpy "
            f"default_rng({seed}): alpha = uniform(0, pi/2), chi = uniform(1e-3, 1), "
            "km = uniform(0, 1) * (1 - chi), drawn in that order",
            "inputs_sha256": digest(np.concatenate([a, c, k])),
            **summary(pts),
        },
    }


def part_snapshot(args) -> None:
    if args.write_snapshot:
        snap = snapshot_now(0, args.seed)
        snap["written"] = f"eccjump {eccjump.__version__}, {time.strftime('%Y-%m-%d')}"
        SNAPSHOT.write_text(json.dumps(snap, indent=1) + "\n")
        print(f"\nsnapshot written to {SNAPSHOT}")
    if args.check_snapshot:
        saved = json.loads(SNAPSHOT.read_text())
        print(f"\n== d. snapshot check against {SNAPSHOT.name} ({saved.get('written', '?')}) ==")
        ok = True
        checks = []
        for threads in (1, 0):
            now = snapshot_now(threads, args.seed)
            for key in ("map_100", "random_1e6"):
                s, n = saved[key], now[key]
                inputs = s["inputs_sha256"] == n["inputs_sha256"]
                reasons = s["reason_sha256"] == n["reason_sha256"] and s["counts"] == n["counts"]
                theta = s["theta_J_sha256"] == n["theta_J_sha256"]
                ok &= inputs and reasons
                checks.append(
                    {
                        "key": key,
                        "threads": threads or os.cpu_count(),
                        "inputs_same": inputs,
                        "reasons_identical": reasons,
                        "theta_J_digest_matches": theta,
                    }
                )
                print(
                    f"{key:<11} threads {threads or os.cpu_count()}: inputs "
                    f"{'same' if inputs else 'DIFFER'}, reasons "
                    f"{'identical' if reasons else 'DIFFER'}, theta_J digest "
                    f"{'matches' if theta else 'differs'}"
                )
                if not reasons:
                    print(f"  counts saved {s['counts']}\n  counts now   {n['counts']}")
        RESULTS["snapshot"] = {"saved": saved.get("written"), "ok": bool(ok), "checks": checks}
        if not ok:
            raise SystemExit("snapshot check failed")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument(
        "--parts",
        default="roll,accuracy,batch,closed,ode",
        help="comma-separated: roll, accuracy, batch, batch-accuracy, closed, ode (default: "
        "all but batch-accuracy)",
    )
    p.add_argument("--rtol", type=float, default=1e-10)
    p.add_argument(
        "--integrator",
        default="RK45",
        choices=INTEGRATORS,
        help="eccjump's Runge-Kutta pair in parts a, b and the ODE map of c (RK45)",
    )
    p.add_argument("--atol", type=float, default=1e-12)
    p.add_argument(
        "--stop-at-slip",
        action="store_true",
        help="eccjump stops at the first slip (reason SLIP, stop_at_slip=True) in parts b, b' "
        "and c, as the numba loop does; default: it continues to tell SLIP_BEFORE from "
        "SLIP_AT_JUMP",
    )
    p.add_argument("--number", type=int, default=200, help="calls per timing round (roll)")
    p.add_argument(
        "--rung-repeat",
        type=int,
        default=5,
        help="part a': timing rounds of number/4 calls per route and rtol, best (5)",
    )
    p.add_argument("--batch", type=int, default=10_000, help="points of part b (10000)")
    p.add_argument(
        "--samples-per-turn",
        type=int,
        default=100,
        help="numbalsoda event scan: t_eval samples per ~turn of theta (100)",
    )
    p.add_argument("--points", type=int, default=10**6, help="random points of part c (10^6)")
    p.add_argument("--grid", type=int, default=100, help="closed-form grid N (100)")
    p.add_argument(
        "--ode-grid",
        type=int,
        default=40,
        help="ODE map: M^3 sub-grid of the 100^3 axes, 100 = full map (40)",
    )
    p.add_argument("--repeat", type=int, default=2, help="closed-form runs, best time (2)")
    p.add_argument("--seed", type=int, default=20261123)
    p.add_argument("--show", type=int, default=5, help="part b: differing points to print")
    p.add_argument("--write-snapshot", action="store_true", help="write benches/snapshot.json")
    p.add_argument(
        "--check-snapshot",
        action="store_true",
        help="recompute (1 thread and all threads) and compare with snapshot.json",
    )
    results.add_json_option(p, "peers")
    args = p.parse_args()
    load = os.getloadavg()
    print(
        f"machine: {platform.machine()} ({cpu_model()}), {os.cpu_count()} logical CPUs, python "
        f"{platform.python_version()}, numpy {np.__version__}, eccjump {eccjump.__version__}; "
        f"load average {load[0]:.2f}"
    )
    print("peers: " + ", ".join(f"{k} {v or 'missing'}" for k, v in peer_versions().items()))
    parts = set(args.parts.split(",")) if args.parts else set()
    if args.write_snapshot or args.check_snapshot:
        parts = set() if args.parts == p.get_default("parts") else parts
    if "roll" in parts:
        part_roll(args)
    if "accuracy" in parts:
        part_accuracy(args)
    if "batch" in parts:
        part_batch(args)
    if "batch-accuracy" in parts:
        part_batch_accuracy(args)
    if "closed" in parts:
        part_closed(args)
    if "ode" in parts:
        part_ode(args)
    try:
        part_snapshot(args)
    finally:  # a failed snapshot check still leaves the parts' figures (and its own) on file
        print(f"\nload average (1 min) at the end {os.getloadavg()[0]:.2f}")
        for n in NOTES:
            print("note:", n)
        results.write(args.json, "peers", args, **RESULTS, notes=NOTES)


#: the processor's model name (the ratios to the peers depend on it, not only on the code)
cpu_model = results.cpu_model


def peer_versions() -> dict[str, str | None]:
    """scipy's and the peers' versions (None: not installed)."""
    v = results.versions()
    return {k: v[k] for k in ("scipy", "numba", "numbalsoda", "pydiffsol", "diffrax", "jax")}


if __name__ == "__main__":
    main()
