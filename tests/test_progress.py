"""``progress=`` of the long calls (issue 49 item 3): off by default, a tqdm bar for True, a
callable called as (done, total); the same bits with and without it; a wrong value a
TypeError naming ``progress`` before any work. One mechanism, ``eccjump._base.progress``,
which the command line's bars use too."""

from __future__ import annotations

import contextlib
import io
import math
import re

import numpy as np
import pytest
from fuzz_cases import run_cli_inprocess
from hypothesis import given, settings
from hypothesis import strategies as st

import eccjump
from eccjump._base import progress as prog
from eccjump._base.arrays import fields_equal

A = np.radians([20.0, 35.0, 50.0])
C = np.array([0.15, 0.5])
F = np.array([0.1, 0.6])
CALLS = {
    "region": lambda **kw: eccjump.region(A, C, F, 1.0, **kw),
    "motion_map": lambda **kw: eccjump.motion_map(A, C, F, 1.0, t_max=5.0, **kw),
    "motion_points": lambda **kw: eccjump.motion_points(A, 0.15, 0.02, 1.0, t_max=5.0, **kw),
    "start_map": lambda **kw: eccjump.start_map(1.0, [0.0, 2.0], [0.0, 1.0], grid=4, **kw),
    "optimal_start": lambda **kw: eccjump.optimal_start(
        1.0, grid=4, lattice=(4, 3), n_starts=1, **kw
    ),
    "design": lambda **kw: eccjump.design(
        [math.radians(10), math.radians(40)], 0.6, 0.1, grid=6, **kw
    ),
    "uncertainty": lambda **kw: eccjump.uncertainty(
        eccjump.Cylinder(0.15, 0.02), math.radians(40), 1.0, sd={"chi": 0.01}, n=64, **kw
    ),
}


def same(x: object, y: object) -> bool:
    """Results equal field by field, arrays by their bits (NaN equal to NaN)."""
    return type(x) is type(y) and fields_equal(x, y)


@pytest.mark.parametrize("name", sorted(CALLS))
def test_progress_reports_and_changes_no_bit(name, capsys):
    seen: list[tuple[int, int]] = []
    plain = CALLS[name]()
    reported = CALLS[name](progress=lambda done, total: seen.append((done, total)))
    assert same(plain, reported)
    assert seen, "the callable was never called"
    assert all(type(d) is int and type(t) is int and 0 <= d <= t for d, t in seen), seen
    assert [d for d, _ in seen] == sorted(d for d, _ in seen)  # done never goes back
    assert seen[-1][0] == seen[-1][1]  # it ends done
    capsys.readouterr()
    with_bar = CALLS[name](progress=True)
    assert same(plain, with_bar)
    assert "100%" in capsys.readouterr().err  # the bar, on stderr


@pytest.mark.parametrize("name", sorted(CALLS))
@pytest.mark.parametrize("bad", [1, "bar", 2.5, object()])
def test_a_wrong_progress_is_a_type_error_naming_it(name, bad):
    with pytest.raises(TypeError, match="progress"):
        CALLS[name](progress=bad)


@pytest.mark.parametrize("name", ["region", "motion_map"])
def test_progress_is_refused_for_a_lazy_map(name):
    pytest.importorskip("dask")
    with pytest.raises(ValueError, match="progress"):
        CALLS[name](progress=True, chunks=2)


def test_off_by_default_and_false_or_none_draw_nothing(capsys):
    for value in (None, False, np.bool_(False)):
        CALLS["region"](progress=value)
    CALLS["region"]()
    assert capsys.readouterr().err == ""


@settings(max_examples=60, deadline=None)
@given(
    sizes=st.lists(st.integers(0, 7), min_size=1, max_size=4),
    tail=st.sampled_from([(), (3,)]),
    min_points=st.integers(1, 20),
)
def test_a_grid_in_parts_is_the_grid_in_one_call(sizes, tail, min_points):
    """The invariant that makes progress free of any bit: a grid computed in parts along an
    axis, joined, is the grid of one call (fields flat in C order, with trailing axes)."""
    axes = [np.arange(n, dtype=np.float64) * 10.0**i for i, n in enumerate(sizes)]

    def compute(ax: int, part: slice) -> dict[str, np.ndarray]:
        grid = np.meshgrid(*prog.cut(axes, ax, part), indexing="ij")
        value = sum(grid) if grid else np.zeros(())
        flat = np.asarray(value, dtype=np.float64).ravel()
        return {"v": np.repeat(flat, math.prod(tail)).reshape(flat.size, *tail)}

    whole = compute(0, slice(None))["v"]
    seen: list[tuple[int, int]] = []
    old = prog.MIN_PART_POINTS
    prog.MIN_PART_POINTS = min_points  # small parts: many joins
    try:
        parts = prog.grid_in_parts(compute, sizes, lambda d, t: seen.append((d, t)))["v"]
    finally:
        prog.MIN_PART_POINTS = old
    assert parts.shape == whole.shape and np.array_equal(parts, whole)
    if math.prod(sizes):
        assert seen[0] == (0, whole.shape[0]) and seen[-1] == (whole.shape[0],) * 2


def test_the_cli_starts_reports_with_the_shared_bar_not_by_hand():
    """``eccjump starts`` printed "map: k/n starts" lines by hand; it now draws the bars of
    ``progress=True`` (on a terminal only, as every subcommand)."""
    argv = ["starts", "--mu-s", "0.3", "--grid", "2", "--lattice", "2", "2",
            "--map-size", "2", "2", "--map-grid", "2"]  # fmt: skip
    code, _, err = run_cli_inprocess(argv)  # stderr is no terminal here: no bar
    assert code == 0 and not re.search(r"map: \d+/\d+ starts", err), err

    class Terminal(io.StringIO):
        def isatty(self) -> bool:
            return True

    from eccjump.cli import main

    tty = Terminal()
    with contextlib.redirect_stderr(tty), contextlib.redirect_stdout(io.StringIO()):
        assert main(argv) == 0
    assert "4/4" in tty.getvalue() and "start/s" in tty.getvalue(), tty.getvalue()
