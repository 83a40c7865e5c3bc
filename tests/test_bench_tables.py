"""The bookkeeping of ``benches/bench_peers.py``'s comparison at equal accuracy: which rung
a route reaches a level from, and how the cells that meet issue 10's 3x are counted. The
figures in benches/README.md rest on them, so they are tested like library code (no peer
is needed: the tables are made up)."""

from __future__ import annotations

import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benches"))
import bench_peers as bp


def test_a_level_is_reached_from_the_loosest_rung_after_which_every_rung_holds() -> None:
    # A lucky loose rung (index 1) does not count: rung 2 misses the level again.
    errors = [1e-7, 5e-10, 3e-9, 8e-10, 2e-10, 1e-10]
    assert bp.reached(errors, 1e-9) == 3
    assert bp.reached(errors, 1e-10) == 5
    assert bp.reached(errors, 1e-11) is None
    assert bp.reached([math.inf, 1e-12], 1e-10) == 1  # a failed rung never reaches


def test_cells_count_as_met_from_3x_and_missed_where_eccjump_misses(capsys) -> None:
    peers = ["numbalsoda dop853 (numba)", "pydiffsol tsit45"]
    levels = bp.ACCURACY
    ratios = {(p, lv): 3.0 for p in peers for lv in levels}
    ratios[(peers[0], levels[0])] = 2.99  # short of 3x
    ratios[(peers[1], levels[1])] = math.nan  # eccjump did not reach this level
    del ratios[(peers[1], levels[2])]  # the peer did not reach it: eccjump's
    bp.cell_table({"(40, 0.15, 0.02)": ratios}, peers)
    out = capsys.readouterr().out
    assert f"cells at >= 3x: {2 * len(levels) - 2} of {2 * len(levels)}" in out
    assert "2.99" in out and "inf" in out
