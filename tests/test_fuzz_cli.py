"""Fuzzing of the command line: generated argument lists for every subcommand of ``eccjump``
(read from the parser, so a new subcommand without a generator fails here), valid and
invalid: negative, NaN, infinite, huge, empty and non-numeric values, unknown and misspelt
options, output paths that cannot be written.

The contract (``fuzz_cases.check_cli``): exit status 0 with output and no traceback, or a
non-zero status with a last line of at most MAX_MESSAGE characters that names an option, and
no traceback; besides, no partial file is left next to an output. The commands run in-process
(``fuzz_cases.run_cli_inprocess``) on tiny grids; a few in a subprocess. About 30 s in all.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import re
import subprocess
import sys
import warnings
from collections.abc import Callable
from pathlib import Path
from unittest import mock

import fuzz_cases
import pytest
from fuzz_cases import (
    Case,
    Drawer,
    HypothesisDrawer,
    alarm,
    check_cli,
    cli_design_argv,
    cli_integrator,
    cli_map_argv,
    cli_number,
    cli_roll_argv,
    cli_starts_argv,
    run_cli_inprocess,
    tmpdir,
)
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from eccjump.cli import build_parser
from eccjump.explorer import server as explorer_server

pytest.importorskip("matplotlib")


def _subcommands() -> dict[str, argparse.ArgumentParser]:
    (sub,) = [a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction)]
    return dict(sub.choices)


#: Every option string of every subcommand, with and without its dashes: what a message of
#: the command line may name (fuzz_cases.CLI_PARAMS holds those of roll, map, starts, design).
OPTIONS = tuple(
    sorted(
        {
            name
            for p in _subcommands().values()
            for a in p._actions
            for o in a.option_strings
            for name in (o, o.lstrip("-"), o.lstrip("-").replace("-", "_"))
        }
    )
)

#: Output paths that cannot be written, by what is wrong (made on demand in :func:`outdir`).
BAD_FILES = (
    "no/such/x.png",
    "file/x.png",  # under a file
    "adir.png",  # a directory
    "x.xyz",
    "x",
    "x" * 300 + ".png",
    "",
    "/proc/eccjump-fuzz.png",
)


def outdir() -> Path:
    """The fuzzing's directory, with a file and a directory to collide with."""
    root = tmpdir() / "cli"
    if not root.exists():
        root.mkdir()
        (root / "file").write_text("x")
        (root / "adir.png").mkdir()
    return root


def output_file(d: Drawer, suffix: str) -> str:
    """A good path (half the time) or one of :data:`BAD_FILES`."""
    if d.integer(0, 1):
        return str(outdir() / f"out{d.integer(0, 2)}{suffix}")
    bad = d.choice(BAD_FILES)
    return bad if bad.startswith("/") or not bad else str(outdir() / bad)


# --- argument lists of the subcommands fuzz_cases does not draw ---------------------------------


def cli_simulate_argv(d: Drawer) -> list[str]:
    """A short run (t_max <= 5, few transitions); sometimes a figure, an animation only to a
    path that fails before the run (a GIF takes seconds)."""
    argv = ["simulate", "--alpha", cli_number(d, 0, 90), "--chi", cli_number(d, 0, 1)]
    argv += ["--km", cli_number(d, 0, 0.5), "--mu-s", cli_number(d, 0, 2)]
    argv += ["--t-max", cli_number(d, 0, 5), "--max-transitions", d.choice(("3", "0", "x"))]
    for opt, lo, hi in (
        ("--mu-k", 0, 2),
        ("--restitution", 0, 1),
        ("--theta0", -360, 360),
        ("--omega0", -3, 3),
        ("--slip0", -2, 2),
        ("--l-max", 0, 10),
    ):
        if d.integer(0, 3) == 0:
            argv += [opt, cli_number(d, lo, hi)]
    cli_integrator(d, argv)
    if d.integer(0, 3) == 0:
        argv += ["--figure", output_file(d, d.choice((".png", ".svg", ".pdf")))]
    if d.integer(0, 5) == 0:
        argv += ["--animate", d.choice(BAD_FILES[:5]).replace(".png", ".gif")]
    if d.integer(0, 1):
        argv.append("--json")
    return argv


def cli_figures_argv(d: Drawer) -> list[str]:
    """One or two of the cheap figures, at a low resolution and dpi, into a good or a bad
    directory."""
    argv = ["figures", "--only", *sorted({d.choice(("fig3b", "trajectory", "fig4_slices"))})]
    argv += ["--dpi", d.choice(("20", "30", "19", "601", "-5", "x", "1" + "0" * 30))]
    argv += ["--slice-resolution", d.choice(("3", "4", "1", "10001"))]
    argv += ["--n-scan", d.choice(("4", "8", "1", "100001"))]
    if d.integer(0, 3) == 0:
        argv += ["--resolution", d.choice(("2", "3", "1", "201", "2.5"))]
    bad = d.choice(("file", "file/sub", "d" * 300, "/proc/eccjump-fuzz", ""))
    bad = bad if bad.startswith("/") or not bad else str(outdir() / bad)
    argv += ["-o", str(outdir() / "figs") if d.integer(0, 1) else bad]
    return argv


def cli_explore_argv(d: Drawer) -> list[str]:
    """A port that is free, taken, out of range or no number; with or without a browser."""
    argv = ["explore"]
    if d.integer(0, 3):
        argv += ["--port", d.choice(("0", "-1", "65536", "x", "", "1.5", "9" * 30, "8050"))]
    return argv + d.choice(([], ["--no-browser"]))


def cli_uncertainty_argv(d: Drawer) -> list[str]:
    """A small study (n <= 64) with tolerances good, negative, unknown or repeated; sometimes
    the motion question, a figure or a data file (good or bad paths)."""
    argv = ["uncertainty", "--alpha", cli_number(d, 0, 90), "--chi", cli_number(d, 0, 1)]
    argv += ["--km", cli_number(d, 0, 0.5), "--mu-s", cli_number(d, 0, 2)]
    argv += ["-n", d.choice(("16", "64", "0", "-3", "x", "1" + "0" * 30))]
    for _ in range(d.integer(0, 2)):
        name = d.choice(("alpha", "chi", "km", "mu_s", "theta0", "bogus", ""))
        argv += ["--sd", name, cli_number(d, 0, 2)]
    if d.integer(0, 2) == 0:
        argv += [
            "--bounds",
            d.choice(("mu_s", "chi", "x")),
            cli_number(d, 0, 1),
            cli_number(d, 0, 2),
        ]
    if d.integer(0, 2) == 0:
        argv += ["--question", d.choice(("motion", "jarm", "fly")), "--t-max", cli_number(d, 0, 5)]
    if d.integer(0, 3) == 0:
        argv += ["--sampling", d.choice(("sobol", "random", "halton"))]
    if d.integer(0, 3) == 0:
        argv += ["--figure", output_file(d, d.choice((".png", ".svg")))]
    if d.integer(0, 3) == 0:
        argv += ["-o", output_file(d, d.choice((".csv", ".nc", ".txt")))]
    if d.integer(0, 3) == 0:
        argv.append("--indices")
    return argv + d.choice(([], ["--json"], ["-q"]))


TRACK = Path(__file__).parent / "data" / "jarm_240fps.csv"
#: The stored track's setup (tests/data/jarm_240fps.csv, scripts/make_tracks.py).
TRACK_SETUP = ["--radius", "0.05", "--chi", "0.10927", "--km", "0.0777", "--scale", "1230.539145"]


def cli_analyze_argv(d: Drawer) -> list[str]:
    """The stored track, a missing, empty or foreign file, or a spoilt track (a FIFO, a
    device, a sparse 1 TB file, a row with an extra cell, pixels...: fuzz_cases's
    spoilings), with the body and setup's values good, out of range or no number, and a
    design sheet that is no file."""
    spoilt = lambda: str(fuzz_cases._bad_track_file(d, Case("cli.analyze", print)))  # noqa: E731
    video = lambda: str(d.choice(list(fuzz_cases.videos().values())))  # noqa: E731
    path = d.pick(str(TRACK), str(TRACK), str(outdir() / "none.csv"), "", str(Path(__file__)),
                  spoilt, video)  # fmt: skip
    argv = ["analyze", path] if d.integer(0, 5) else ["analyze"]
    for opt, good, bad in (
        ("--radius", "0.05", ("0", "-1", "nan", "x", "1e300", "1e-300")),
        ("--chi", "0.10927", ("1.5", "-0.1", "nan")),
        ("--km", "0.0777", ("0.95", "-1", "inf")),
        ("--alpha", "66.087", ("95", "-3", "x")),
        ("--scale", "1230.539145", ("0", "-5", "1e400", "1e-300")),
        ("--marker-radius", "0.04", ("0", "1", "nan")),
        ("--marker-angle", "34.3775", ("1e300", "inf", "361")),
        ("--g", "9.81", ("1e300", "1e-300", "0")),
        ("--mu-s", "1.2", ("0", "-1", "nan", "11")),
        ("--mu-s-err", "0.1", ("0", "inf", "x")),
        ("--design", str(TRACK), (os.devnull, str(outdir()), str(outdir() / "none.json"))),
    ):
        if d.integer(0, 4) and (opt != "--design" or d.integer(0, 3) == 0):
            argv += [opt, good if d.integer(0, 2) else d.choice(bad)]
    return argv + d.choice(([], ["--json"], ["--rule", d.choice(("normal_force", "bogus"))]))


def cli_track_argv(d: Drawer) -> list[str]:
    """The good short video, a bad one (fuzz_cases.BAD_VIDEOS), a missing path, a directory;
    an output good or bad; the options good, out of range or no number."""
    vids = fuzz_cases.videos()
    path = d.choice((str(vids["good.mp4"]),) * 3 + tuple(str(p) for p in vids.values())
                    + (str(outdir() / "none.mp4"), "", str(outdir())))  # fmt: skip
    argv = ["track", path] if d.integer(0, 5) else ["track"]
    if d.integer(0, 5):
        argv += ["-o", output_file(d, d.choice((".csv", ".csv", ".txt")))]
    for opt, good, bad in (
        ("--marker-radius", "0.035", ("0", "-1", "nan", "x", "1e300")),
        ("--scale", "1000", ("0", "-5", "1e400", "x")),
        ("--alpha", "66", ("95", "x", "nan")),
        ("--axle-color", "red", ("mauve", "#12", "grey", "", "blue")),
        ("--marker-color", "blue", ("red", "#ffffff", "1,2,3")),
        ("--start", "0", ("x", "nan", "1e300")),
        ("--end", "1", ("-1", "x", "-inf")),
    ):
        if d.integer(0, 3) == 0 or (opt == "--marker-radius" and d.integer(0, 3)):
            argv += [opt, good if d.integer(0, 2) else d.choice(bad)]
    return argv + d.choice(([], ["--json"], ["--overwrite"], ["-q"]))


# --- valid argument lists (the wild ones above rarely get past the parser) -----------------------


def value(d: Drawer, lo: float, hi: float) -> str:
    """A number in [lo, hi] written as a user might: 0.25, 2.5e-01, -.25, 1E+1."""
    x = lo + (hi - lo) * d.integer(0, 100) / 100
    text = d.choice((repr(x), f"{x:.3g}", f"{x:.2e}", f"{x:.2E}"))
    return text.replace("-0.", "-.", 1) if d.integer(0, 3) == 0 else text


def options(d: Drawer, table: dict[str, tuple[float, float]], required: int = 0) -> list[str]:
    """The first ``required`` options of ``table`` and some of the rest, with values in their
    ranges, as ``--opt value`` or ``--opt=value``."""
    argv: list[str] = []
    for k, (opt, (lo, hi)) in enumerate(table.items()):
        if k < required or d.integer(0, 2) == 0:
            v = value(d, lo, hi)
            argv += [f"{opt}={v}"] if d.integer(0, 3) == 0 else [opt, v]
    return argv


BODY = {"--alpha": (0, 90), "--chi": (0.05, 0.6), "--km": (0.01, 0.35)}


def valid_roll(d: Drawer) -> list[str]:
    table = {**BODY, "--mu-s": (0, 2), "--theta0": (-360, 360), "--omega0": (-3, 3),
             "--t-max": (0.1, 20), "--theta-max": (10, 720), "--rtol": (1e-12, 1e-4)}  # fmt: skip
    argv = ["roll", *options(d, table, required=3)]
    cli_integrator(d, argv)
    return argv + d.choice(([], ["--json"], ["--rule", "normal_force"]))


def valid_simulate(d: Drawer) -> list[str]:
    table = {**BODY, "--mu-s": (0.2, 2), "--t-max": (0.1, 3), "--restitution": (0, 1),
             "--theta0": (-360, 360), "--omega0": (-3, 3), "--slip0": (-1, 1),
             "--l-max": (0.5, 10)}  # fmt: skip
    argv = ["simulate", *options(d, table, required=5)]
    argv += ["--max-transitions", str(d.integer(1, 8))]
    if d.integer(0, 3) == 0:
        argv += ["--figure", str(outdir() / f"motion{d.choice(('.png', '.svg'))}")]
    return argv + d.choice(([], ["--json"]))


def valid_map(d: Drawer) -> list[str]:
    table = {"--mu-s": (0.2, 2), "--alpha-min": (0, 40), "--alpha-max": (50, 90),
             "--theta0": (-30, 30), "--omega0": (0, 2)}  # fmt: skip
    out = str(outdir() / f"map{d.integer(0, 1)}.npz")
    argv = ["map", *options(d, table, required=1), "--grid", str(d.integer(1, 3))]
    argv += ["-o", out, "--overwrite", "-q"]
    if d.integer(0, 2) == 0:
        argv += ["--kind", "motion", "--t-max", value(d, 0.1, 2), "--max-transitions", "3"]
    return argv


def valid_starts(d: Drawer) -> list[str]:
    argv = ["starts", "--mu-s", value(d, 0.3, 1.2), "--grid", "2", "--lattice", "2", "2", "-q"]
    argv += ["--omega-max", value(d, 0.5, 3)]
    argv += d.choice((["--no-map"], ["--map-grid", "2", "--map-size", "2", "2"]))
    if d.integer(0, 2) == 0:
        argv += ["-o", str(outdir()), "--dpi", "20"]
    return argv + d.choice(([], ["--json"]))


def valid_design(d: Drawer) -> list[str]:
    argv = ["design", "--alpha-range", value(d, 10, 40), value(d, 50, 80)]
    argv += ["--mu-s", value(d, 0.5, 1.5), "--grid", "4", "--max-turns", "2"]
    if d.integer(0, 1):
        argv += ["--chi", value(d, 0.1, 0.5), "--km", value(d, 0.01, 0.3)]
    return argv + d.choice(([], ["--json"], ["--target", "slip"]))


def valid_uncertainty(d: Drawer) -> list[str]:
    argv = ["uncertainty", *options(d, {**BODY, "--mu-s": (0.3, 1.5)}, required=4)]
    argv += ["-n", str(d.integer(1, 64)), "--seed", str(d.integer(0, 9)), "-q"]
    question = d.choice(("jarm", "motion"))
    names = ("alpha", "chi", "km", "mu_s") + (
        ("restitution", "theta0") if question == "motion" else ()
    )
    for name in sorted({d.choice(names) for _ in range(d.integer(0, 3))}):
        argv += ["--sd", name, value(d, 0, 0.05)]
    argv += ["--question", question, "--t-max", "3"]
    argv += d.choice(([], ["--sampling", "sobol"], ["--invalid", "count"], ["--indices"]))
    if d.integer(0, 3) == 0:
        argv += ["-o", str(outdir() / f"u{d.choice(('.csv', '.nc'))}")]
    if d.integer(0, 4) == 0:
        argv += ["--figure", str(outdir() / "u.png"), "--dpi", "20"]
    return argv + d.choice(([], ["--json"]))


def valid_figures(d: Drawer) -> list[str]:
    argv = ["figures", "--only", d.choice(("fig3b", "trajectory", "fig4_slices"))]
    argv += ["--dpi", "20", "--slice-resolution", str(d.integer(2, 5))]
    return [*argv, "--n-scan", str(d.integer(2, 8)), "-o", str(outdir() / "figs")]


def valid_explore(d: Drawer) -> list[str]:
    port = d.choice((["--port", "0"], ["--port=0"]))
    return ["explore", *port, *d.choice(([], ["--no-browser"]))]


def valid_analyze(d: Drawer) -> list[str]:
    alpha = ["--alpha", value(d, 64, 68)] if d.integer(0, 1) else []
    return ["analyze", str(TRACK), *TRACK_SETUP, *alpha, *d.choice(([], ["--json"]))]


def valid_track(d: Drawer) -> list[str]:
    out = str(outdir() / f"track{d.integer(0, 2)}.csv")
    extra = d.choice(([], ["--json"], ["--alpha", value(d, 60, 70)], ["--axle-color", "red"]))
    video = str(fuzz_cases.videos()["good.mp4"])
    return ["track", video, "-o", out, "--marker-radius", value(d, 0.03, 0.04), *extra]


#: Argument lists of every subcommand: mostly valid, or wild (mostly refused by the parser).
VALID: dict[str, Callable[[Drawer], list[str]]] = {
    "roll": valid_roll,
    "simulate": valid_simulate,
    "map": valid_map,
    "starts": valid_starts,
    "design": valid_design,
    "figures": valid_figures,
    "explore": valid_explore,
    "analyze": valid_analyze,
    "uncertainty": valid_uncertainty,
    "track": valid_track,
}
WILD: dict[str, Callable[[Drawer], list[str]]] = {
    "roll": cli_roll_argv,
    "simulate": cli_simulate_argv,
    "map": cli_map_argv,
    "starts": cli_starts_argv,
    "design": cli_design_argv,
    "figures": cli_figures_argv,
    "explore": cli_explore_argv,
    "analyze": cli_analyze_argv,
    "uncertainty": cli_uncertainty_argv,
    "track": cli_track_argv,
}


# --- mutations: what a user mistypes --------------------------------------------------------------


def misspell(d: Drawer, option: str) -> str:
    """``--mu-s`` as ``--mu_s``, ``--mus``, ``--mu-ss`` or ``--MU-S``."""
    how = d.integer(0, 3)
    if how == 0 and "-" in option[2:]:
        return option.replace("-", "_").replace("__", "--", 1)
    if how == 1 and len(option) > 3:
        i = d.integer(3, len(option) - 1)
        return option[:i] + option[i + 1 :]
    if how == 2:
        return option + option[-1]
    return option.upper()


def mutate(d: Drawer, argv: list[str]) -> list[str]:
    """Sometimes one mistake: a misspelt or unknown option, a negated or empty value, a huge
    integer, a stray argument, a repeated option."""
    argv = list(argv)
    options = [i for i, a in enumerate(argv) if a.startswith("--")]
    kind = d.integer(0, 9)
    if kind <= 3 or not options:
        return argv
    i = d.choice(options)
    if kind == 4:
        argv[i] = misspell(d, argv[i])
    elif kind == 5:
        argv.insert(d.integer(0, len(argv)), d.choice(("--bogus", "-x", "--", "---mu-s")))
    elif kind == 6 and i + 1 < len(argv) and not argv[i + 1].startswith("--"):
        argv[i + 1] = d.choice(("-", "-1e-3", "-0", "-inf", "-nan", "-" + argv[i + 1]))
    elif kind == 7 and i + 1 < len(argv):
        argv[i + 1] = d.choice(("", " ", "9" * 5000, "1e999999", "-" * 3))
    elif kind == 8:
        argv.append(d.choice(("stray", "1", "-1")))
    else:
        argv += argv[i : i + 2]
    return argv


def case(d: Drawer, command: str) -> Case:
    """A valid argument list, perhaps with one mistake (two in three), or a wild one."""
    make = VALID[command] if d.integer(0, 2) else WILD[command]
    argv = mutate(d, make(d))
    return Case(
        f"cli.{command}", run_cli_inprocess, args=(argv,), check=check_cli,
        info={"cmd": command, "argv": argv},
    )  # fmt: skip


def judge(res: tuple[int, str, str], c: Case) -> None:
    """``check_cli`` with every option of every subcommand (and the unknown ones drawn) as
    names a message may give; then: no temporary file left behind."""
    unknown = [a.split("=")[0] for a in c.info["argv"] if re.match(r"^--?-?[A-Za-z]", a)]
    names = (*fuzz_cases.CLI_PARAMS, *OPTIONS, *unknown)
    with mock.patch.object(fuzz_cases, "CLI_PARAMS", names):
        check_cli(res, c)
    left = [p.name for p in outdir().rglob(".*") if ".tmp-" in p.name]
    assert not left, f"partial files left: {left}"


def _run(c: Case) -> tuple[int, str, str]:
    with warnings.catch_warnings(), contextlib.ExitStack() as stack:
        warnings.simplefilter("ignore")  # overflow in casts of drawn values, matplotlib
        if c.info["cmd"] == "explore":
            # ``eccjump explore`` serves until Ctrl-C: here Ctrl-C comes as soon as it serves
            # (and no browser opens)
            stack.enter_context(mock.patch.object(
                explorer_server._Server, "serve_forever", side_effect=KeyboardInterrupt
            ))  # fmt: skip
            stack.enter_context(mock.patch("webbrowser.open"))
        return run_cli_inprocess(c.info["argv"])


# --- the tests ------------------------------------------------------------------------------------


@pytest.fixture(autouse=True)
def _in_the_fuzzing_directory(monkeypatch):
    """Relative paths drawn (" ", "file") land in the fuzzing's directory, not the checkout."""
    monkeypatch.chdir(outdir())


#: Examples per subcommand (about 30 s in all on a 2-core machine).
BUDGET = {
    "roll": 100, "simulate": 60, "map": 25, "starts": 8, "design": 5, "figures": 10, "explore": 20,
    "analyze": 6, "uncertainty": 25, "track": 15,
}  # fmt: skip


def test_every_subcommand_is_fuzzed():
    assert set(VALID) == set(WILD) == set(_subcommands()) == set(BUDGET)


@pytest.mark.parametrize("command", sorted(BUDGET))
def test_command_line_keeps_its_contract(command):
    import matplotlib

    matplotlib.use("Agg")

    @settings(
        max_examples=BUDGET[command],
        deadline=None,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
    )
    @given(st.data())
    def run(data):
        c = case(HypothesisDrawer(data), command)
        with alarm(120):  # a hang (a FIFO read) fails instead of hanging the suite
            res = _run(c)
        try:
            judge(res, c)
        except AssertionError as err:
            raise AssertionError(f"{err}\n  eccjump {' '.join(c.info['argv'])[:400]}") from None

    run()


@settings(max_examples=3, deadline=None)
@given(st.data())
def test_command_line_in_a_subprocess(data):
    """A few generated command lines through ``python -m eccjump.cli`` (the real argv, the
    real exit status)."""
    d = HypothesisDrawer(data)
    c = case(d, d.choice(("roll", "simulate", "figures")))
    proc = subprocess.run(
        [sys.executable, "-m", "eccjump.cli", *c.info["argv"]],
        capture_output=True,
        text=True,
        timeout=120,
        check=False,
        cwd=outdir(),
    )
    judge((proc.returncode, proc.stdout, proc.stderr), c)
