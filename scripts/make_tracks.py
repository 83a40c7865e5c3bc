"""Write the small synthetic tracks of tests/data/ (python scripts/make_tracks.py [--check]).

Each is filmed from `eccjump.simulate` by `eccjump.studies.experiment.synthetic.synthetic_track`:
frames at the given rate, Gaussian pixel noise on a 1000-pixel field, positions in pixels
(CSV, with the scale in a comment line) or in metres (the Tracker export). The tests read
them and regenerate them with `--check` (the files must come out the same).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

import eccjump
from eccjump.studies.experiment.synthetic import SyntheticTrack, synthetic_track
from eccjump.studies.experiment.track import write_csv

DATA = Path(__file__).resolve().parent.parent / "tests" / "data"

#: name: (body, alpha [deg], friction and start, camera)
CASES = {
    # eccjump design --alpha-range 40 70 --mu-s 1 --min-apex 0.0075 --radius 0.05: a JARM
    "jarm_240fps": dict(chi=0.10927, km=0.0777, alpha=66.087, mu_s=1.0, mu_k=0.8,
                        fps=240.0, noise_px=0.5, marker_angle=0.6, seed=11),
    # the paper's Fig. 3b body on 30 deg with less friction: slips (long) before lifting off
    "slip_240fps": dict(chi=0.5, km=0.4, alpha=30.0, mu_s=0.4, mu_k=0.3,
                        fps=240.0, noise_px=0.5, marker_angle=-1.0, seed=12, theta0=3.6,
                        omega0=2.0, radius=0.04),
}  # fmt: skip


def make(case: dict) -> SyntheticTrack:
    c = dict(case)
    body = eccjump.Cylinder(chi=c.pop("chi"), km=c.pop("km"))
    alpha = math.radians(c.pop("alpha"))
    return synthetic_track(body, alpha, **c)


def csv_text(name: str, case: dict) -> str:
    st = make(case)
    head = f"# synthetic track {name}: scale {st.scale:.6f} px/m; {json.dumps(case)}\n"
    return head + write_csv(st.track, scale=st.scale)


def tracker_text() -> str:
    """Tracker 6's export of two point tracks (File | Export | Data, tab-delimited, the
    table's columns t, x, y of each track; world units metres): '#multi:', a line naming
    the tracks over their columns, the column names, then one row per frame. An unmarked
    frame at the start has empty cells (Tracker leaves them blank)."""
    st = make(CASES["jarm_240fps"] | {"fps": 120.0, "seed": 5})
    rows = ["#multi:", "\taxle\t\tmarker\t", "t\tx\ty\tx\ty"]
    rows.append(f"{-1 / 120:.4f}\t\t\t\t")
    for i in range(st.track.n):
        x = (*st.track.c[i], *st.track.m[i])
        rows.append(f"{st.track.t[i]:.4f}\t" + "\t".join(f"{v:.4E}" for v in x))
    return "\n".join(rows) + "\n"


def files() -> dict[str, str]:
    out = {f"{name}.csv": csv_text(name, case) for name, case in CASES.items()}
    out["tracker_sample.txt"] = tracker_text()
    return out


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="compare, do not write")
    args = parser.parse_args()
    stale = []
    for name, text in files().items():
        path = DATA / name
        if args.check:
            if not path.exists() or path.read_text() != text:
                stale.append(name)
        else:
            path.write_text(text)
            print(f"{path}: {len(text)} bytes")
    if stale:
        print(f"stale: {', '.join(stale)}", file=sys.stderr)
    return 1 if stale else 0


if __name__ == "__main__":
    sys.exit(main())
