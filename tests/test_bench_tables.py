"""The bookkeeping of ``benches/bench_peers.py``'s comparison at equal accuracy: which rung
a route reaches a level from, how the cells that meet issue 10's 3x are counted, and that
they reach the results file (``--json``) as plain JSON. The figures in benches/README.md rest
on them, so they are tested like library code (no peer is needed: the tables are made up)."""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benches"))
import bench_peers as bp
import results


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
    counted = bp.cell_table({"(40, 0.15, 0.02)": ratios}, peers)
    out = capsys.readouterr().out
    assert f"cells at >= 3x: {2 * len(levels) - 2} of {2 * len(levels)}" in out
    assert "2.99" in out and "inf" in out
    assert (counted["cells_met"], counted["cells_total"]) == (2 * len(levels) - 2, 2 * len(levels))
    by_key = {(c["peer"], c["level"]): c for c in counted["cells"]}
    assert not by_key[(peers[0], levels[0])]["met"]
    assert not by_key[(peers[1], levels[1])]["eccjump_reached"]
    assert (
        by_key[(peers[1], levels[2])]["met"] and not by_key[(peers[1], levels[2])]["peer_reached"]
    )


def _refuse(token: str) -> float:
    raise ValueError(f"{token} is not JSON")


def test_the_results_file_is_plain_json_with_the_shared_header(tmp_path) -> None:
    args = argparse.Namespace(number=3, json="ignored")
    cells = bp.cell_table({"case": {("p", 1e-8): math.inf, ("p", 1e-9): math.nan}}, ["p"])
    path = results.write(tmp_path / "r.json", "peers", args, accuracy=cells, n=bp.np.int64(2))
    doc = json.loads(path.read_text(), parse_constant=_refuse)  # no NaN or Infinity tokens
    assert doc["benchmark"] == "bench_peers" and doc["args"] == {"number": 3}
    assert {"date", "machine", "python", "versions", "argv"} <= doc.keys()
    assert doc["n"] == 2 and [c["ratio"] for c in doc["accuracy"]["cells"]][:2] == [None, None]


def test_every_bench_script_takes_json_and_writes_the_results_file() -> None:
    # benches/README.md promises a results file from every run of every script there.
    benches = Path(__file__).resolve().parents[1] / "benches"
    scripts = [p for p in sorted(benches.glob("*.py")) if "__main__" in p.read_text("utf-8")]
    assert len(scripts) >= 12
    for script in scripts:
        text = script.read_text("utf-8")
        assert "results.add_json_option(" in text, f"{script.name}: no --json option"
        assert "results.write(" in text, f"{script.name}: writes no results file"
