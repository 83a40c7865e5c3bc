"""The held-out campaign of ``eccjump.analyze`` (issue 48): seeded tracks of the independent
model (``reference_tracks.py``) at 60, 240 and 1000 fps with 0.2 to 2 px of noise, the
confusion table of the verdicts and the coverage of the 95 % intervals.

``python tests/verdict_campaign.py [--seed S] [--quick] [--measured 0.05]`` prints them
(``--measured``: with mu_s measured apart from the track, to 5 %);
``pytest -m campaign tests/test_analysis_verdict.py`` checks the targets.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from collections import Counter
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import numpy as np
import reference_tracks as rt

from eccjump.studies.experiment import analyze

NOISES = (0.2, 0.5, 2.0)
FPS = (60.0, 240.0, 1000.0)


def cases(seed: int = 0, quick: bool = False) -> list[tuple[rt.Case, dict]]:
    """(case, analyze keywords) of the campaign: per frame rate 4 JARM, 4 short slips (1-10
    frames), 2 long ones and the stick-slip body; at 240 fps 4 misstated setups."""
    out: list[tuple[rt.Case, dict]] = []
    per = {"jarm": 4, "slip": 4, "long_slip": 2} if not quick else {"jarm": 1, "slip": 1}
    k = 0
    for fps in FPS:
        for family, n in per.items():
            for _ in range(n):
                noise = NOISES[k % 3]
                out.append((rt.draw(family, seed * 1000 + k, fps, noise), {}))
                k += 1
        out.append((rt.draw("stick_slip", seed * 1000 + k, fps, NOISES[k % 3]), {}))
        k += 1
    if not quick:
        for j, (kind, sign) in enumerate(
            (("roll", 1), ("roll", -1), ("radius", 1), ("radius", -1))
        ):
            base = rt.draw("jarm" if j % 2 else "slip", seed * 1000 + k, 240.0, 0.5)
            k += 1
            out.append(rt.systematic(base, kind, sign))
    return out


def expected(frames: float) -> str:
    """What a right verdict is for a true total slip of ``frames`` before the lift-off."""
    return "jarm" if frames == 0 else "slip_first"


def judge(case: rt.Case, kwargs: dict, measured: float = 0.0) -> dict:
    """Analyse the track of ``case``; the verdict against the truth and the coverage. With
    ``measured`` > 0, analyze is also told mu_s as a tilt test would give it: the truth
    plus a normal error of ``measured`` times it (seeded by the case), with that error."""
    made = rt.film(case)
    args = {"radius": case.radius, "chi": case.chi, "km": case.km, "alpha": case.alpha,
            "marker_angle": case.marker_angle,
            "marker_radius": case.marker_in_r * case.radius} | kwargs  # fmt: skip
    if measured > 0:
        err = measured * case.mu_s
        draw = np.random.default_rng([case.seed, 48]).standard_normal()
        args |= {"mu_s": max(case.mu_s + err * draw, 1e-3), "mu_s_err": err}
    started = time.perf_counter()
    res = analyze(made.track, **args)
    frames = made.slip_frames
    truth = expected(frames)
    wrong = (res.verdict == "jarm" and frames >= 1) or (res.verdict == "slip_first" and frames == 0)
    lo, hi = res.mu_k_interval
    lift_ok = abs(res.liftoff_t - made.liftoff) <= 1.96 * res.liftoff_err
    if res.verdict == "undetermined" and res.reason == "model":
        lift_ok = lift_ok or not math.isfinite(res.liftoff_err)
    return {
        "family": case.family
        + ("/" + next(iter(kwargs)) if kwargs else "")
        + ("/roll" if case.roll_deg else ""),
        "fps": case.fps,
        "noise": case.noise_px,
        "frames": frames,
        "episodes": len(made.slips),
        "truth": truth,
        "verdict": res.verdict,
        "reason": res.reason,
        "wrong": wrong,
        "lift_ok": lift_ok,
        "lift_se": (res.liftoff_t - made.liftoff) / res.liftoff_err
        if res.liftoff_err
        else math.inf,
        "mu_k_ok": lo <= case.mu_k <= hi,
        "mu_k_determined": hi - lo < 2.9,
        "mu_s_ok": _covers(res.parameters()["mu_s"], case.mu_s),
        "mu_s_status": res.parameters()["mu_s"]["status"],
        "chi2": res.fit.chi2_reduced,
        "dchi2": res.delta_chi2,
        "inflation": res.fit.correlation,
        "seconds": time.perf_counter() - started,
    }


def _covers(p: dict, truth: float) -> bool:
    """Whether a printed mu_s covers the truth: its interval, its lower bound, or anything
    when it is not determined."""
    if p["status"] == "lower_bound":
        return truth >= p["lo"]
    return p["status"] == "not_determined" or p["lo"] <= truth <= p["hi"]


def summary(rows: list[dict]) -> str:
    """The confusion table (truth bins by verdict) and the coverage."""

    def bin_of(r: dict) -> str:
        if r["family"].count("/"):
            return "misstated"
        f = r["frames"]
        return (
            "no slip"
            if f == 0
            else "<1 frame"
            if f < 1
            else "1-3 frames"
            if f < 3
            else ">=3 frames"
        )

    table = Counter(
        (bin_of(r), r["verdict"] + (f" ({r['reason']})" if r["reason"] else "")) for r in rows
    )
    lines = [f"{len(rows)} tracks; confusion (truth bin: verdict count):"]
    for b in ("no slip", "<1 frame", "1-3 frames", ">=3 frames", "misstated"):
        cells = sorted((v, n) for (bb, v), n in table.items() if bb == b)
        if cells:
            lines.append(f"  {b:11s} " + ", ".join(f"{v}: {n}" for v, n in cells))
    wrong = [r for r in rows if r["wrong"]]
    lines.append(f"confidently wrong: {len(wrong)}")
    ge3 = [r for r in rows if r["frames"] >= 3 and "/" not in r["family"]]
    j = [r for r in rows if r["frames"] == 0 and "/" not in r["family"]]
    lines.append(
        f"slips >= 3 frames called slip_first: "
        f"{sum(r['verdict'] == 'slip_first' for r in ge3)} / {len(ge3)}"
    )
    lines.append(f"JARM called jarm: {sum(r['verdict'] == 'jarm' for r in j)} / {len(j)}")
    lines.append(f"lift-off covered (95 %): {sum(r['lift_ok'] for r in rows)} / {len(rows)}")
    det = [r for r in rows if r["mu_k_determined"]]
    lines.append(f"mu_k covered: {sum(r['mu_k_ok'] for r in rows)} / {len(rows)} "
                 f"({sum(r['mu_k_ok'] for r in det)} / {len(det)} where determined)")  # fmt: skip
    val = [r for r in rows if r.get("mu_s_status") == "value"]
    lines.append(f"mu_s covered: {sum(r.get('mu_s_ok', True) for r in rows)} / {len(rows)} "
                 f"({sum(r['mu_s_ok'] for r in val)} / {len(val)} as values)")  # fmt: skip
    return "\n".join(lines)


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--quick", action="store_true")
    p.add_argument(
        "--measured", type=float, default=0.0,
        help="tell analyze mu_s with this relative error (a tilt test's; e.g. 0.05)",
    )  # fmt: skip
    args = p.parse_args()
    rows = []
    for case, kwargs in cases(args.seed, args.quick):
        r = judge(case, kwargs, args.measured)
        rows.append(r)
        line = (f"{k}={v:.3g}" if isinstance(v, float) else f"{k}={v}" for k, v in r.items())
        print(" ".join(line), flush=True)
    print(summary(rows))


if __name__ == "__main__":
    main()
