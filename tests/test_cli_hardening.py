"""Regression tests of the second hardening round (issue 35): the command line and the input
checks. Every bad input is one short line naming the option (exit status != 0, no traceback),
every output path is checked before the work and written through a temporary sibling, every
numeric option reads negative numbers, every printed number has a bounded length."""

from __future__ import annotations

import argparse
import errno
import math
import os
import re

import numpy as np
import pytest
from fuzz_cases import MAX_MESSAGE, run_cli_inprocess
from reference_points import JARM_ARGS, JARM_BODY, SLIP_FIRST_ARGS

import eccjump
from eccjump import plot
from eccjump.cli import build_parser, main
from eccjump.cli import simulate as cli_simulate
from eccjump.cli._args import NEGATIVE_NUMBER, RAMP_RADIANS, Degrees, Parser
from eccjump.cli._output import bounded, figure_suffixes
from eccjump.motion import fields as motion_fields

SIMULATE = ["simulate", *SLIP_FIRST_ARGS, "--mu-s", "1"]
ROLL = ["roll", *SLIP_FIRST_ARGS]


def failure(argv: list[str], code: int | None = None) -> str:
    """Run ``argv`` in-process; it must fail with a one-line message and no traceback.
    Returns the message (the last line of stderr)."""
    got, _, err = run_cli_inprocess(argv)
    assert "Traceback" not in err, err[-500:]
    assert got != 0, f"exit status 0 for {argv}"
    if code is not None:
        assert got == code, (got, err[-300:])
    last = err.strip().splitlines()[-1]
    assert len(last) <= MAX_MESSAGE, last
    assert last.startswith("eccjump"), last
    return last


def files(directory) -> list[str]:
    return sorted(os.listdir(directory))


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    import matplotlib.pyplot as plt

    plt.close("all")


@pytest.fixture
def no_simulation(monkeypatch):
    """A simulate that fails the test if it is reached: the path check comes first."""

    def refuse(*args, **kwargs):
        raise AssertionError("the run started before the output path was checked")

    monkeypatch.setattr(cli_simulate, "simulate", refuse)


# --- 1. writer faults of --figure, --animate and figures -o ---------------------------------


def _bad_paths(tmp_path):
    """Paths no figure can be written to, each with what the message must say."""
    (tmp_path / "file").write_text("x")
    (tmp_path / "dir.png").mkdir()
    return {
        "missing directory": (tmp_path / "no" / "such" / "x.png", "no such directory"),
        "parent is a file": (tmp_path / "file" / "x.png", "not a directory"),
        "a directory at the path": (tmp_path / "dir.png", "is a directory"),
        "too long a name": (tmp_path / ("x" * 250 + ".png"), "longer than"),
        "unknown suffix": (tmp_path / "x.xyz", "suffix '.xyz' is not one of"),
        "no suffix": (tmp_path / "x", "no suffix: one of"),
        "empty": ("", "give a file name"),
    }


@pytest.mark.parametrize(
    "fault",
    [
        "missing directory",
        "parent is a file",
        "a directory at the path",
        "too long a name",
        "unknown suffix",
        "no suffix",
        "empty",
    ],
)
@pytest.mark.parametrize("option", ["--figure", "--animate"])
def test_simulate_refuses_a_bad_output_before_the_run(tmp_path, fault, option, no_simulation):
    path, says = _bad_paths(tmp_path)[fault]
    if option == "--animate" and fault == "a directory at the path":
        (tmp_path / "dir.gif").mkdir()
        path = tmp_path / "dir.gif"
    if option == "--animate" and str(path).endswith(".png"):
        path = str(path)[:-4] + ".gif"
    before = files(tmp_path)
    message = failure([*SIMULATE, option, str(path)], code=2)
    assert option in message and says in message, message
    assert files(tmp_path) == before


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into a read-only directory")
def test_simulate_refuses_an_unwritable_directory(tmp_path, no_simulation):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o500)
    try:
        message = failure([*SIMULATE, "--figure", str(ro / "x.png")], code=2)
    finally:
        ro.chmod(0o700)
    assert "--figure" in message and "not writable" in message


def test_a_real_write_failure_is_one_line():
    """/proc takes no new files, even from root: the OSError of the write is the message."""
    message = failure([*SIMULATE, "--t-max", "1", "--figure", "/proc/eccjump-x.png"])
    assert "--figure" in message and "/proc/eccjump-x.png" in message


def test_a_failed_write_leaves_no_partial_file(tmp_path, monkeypatch):
    from matplotlib.figure import Figure

    def half_written(self, fname, **kwargs):
        with open(fname, "wb") as fh:
            fh.write(b"\x89PNG half")
        raise OSError(errno.ENOSPC, "No space left on device", str(fname))

    monkeypatch.setattr(Figure, "savefig", half_written)
    target = tmp_path / "x.png"
    message = failure([*SIMULATE, "--t-max", "1", "--figure", str(target)], code=1)
    assert "--figure" in message and "No space left on device" in message
    assert files(tmp_path) == []


def test_ctrl_c_while_writing_leaves_no_partial_file(tmp_path, monkeypatch):
    from matplotlib.figure import Figure

    def interrupted(self, fname, **kwargs):
        with open(fname, "wb") as fh:
            fh.write(b"\x89PNG half")
        raise KeyboardInterrupt

    monkeypatch.setattr(Figure, "savefig", interrupted)
    code, _, err = run_cli_inprocess(
        [*SIMULATE, "--t-max", "1", "--figure", str(tmp_path / "x.png")]
    )
    assert code == 130 and err.strip() == "eccjump: aborted"
    assert files(tmp_path) == []


def test_an_existing_figure_is_replaced_only_when_the_new_one_is_complete(tmp_path):
    target = tmp_path / "x.png"
    target.write_bytes(b"old")
    code, _, err = run_cli_inprocess([*SIMULATE, "--t-max", "1", "--figure", str(target)])
    assert code == 0, err
    assert target.read_bytes()[:4] == b"\x89PNG" and files(tmp_path) == ["x.png"]


@pytest.mark.slow
def test_the_animation_is_written_through_a_temporary_sibling(tmp_path):
    target = tmp_path / "a.gif"
    code, out, err = run_cli_inprocess([*SIMULATE, "--t-max", "1", "--animate", str(target)])
    assert code == 0, err
    assert target.read_bytes()[:6] == b"GIF89a" and files(tmp_path) == ["a.gif"]
    assert f"animation: {target}" in out


def test_the_figure_suffixes_are_those_matplotlib_writes():
    suffixes = figure_suffixes()
    assert {".png", ".pdf", ".svg"} <= suffixes and ".pgf" not in suffixes


def _figures_faults(tmp_path):
    (tmp_path / "file").write_text("x")
    (tmp_path / "taken").mkdir()
    (tmp_path / "taken" / "fig3b.png").mkdir()
    return {
        "outdir is a file": (tmp_path / "file", "cannot make it"),
        "outdir under a file": (tmp_path / "file" / "sub", "cannot make it"),
        "a missing parent": (tmp_path / "no" / "such", "cannot make it"),
        "a deep path": (tmp_path / ("a/" * 1500), "cannot make it"),  # was a RecursionError
        "too long a name": (tmp_path / ("d" * 300), "cannot make it"),
        "a directory at a figure's path": (tmp_path / "taken", "is a directory"),
        "a read-only file system": ("/proc/eccjump-figures", "cannot make it"),
    }


@pytest.mark.parametrize(
    "fault",
    [
        "outdir is a file",
        "outdir under a file",
        "a missing parent",
        "a deep path",
        "too long a name",
        "a directory at a figure's path",
        "a read-only file system",
    ],
)
def test_figures_refuses_a_bad_outdir_before_the_work(tmp_path, fault, monkeypatch):
    path, says = _figures_faults(tmp_path)[fault]

    def refuse(*args, **kwargs):
        raise AssertionError("a figure was computed before the paths were checked")

    monkeypatch.setattr(plot, "fig3b", refuse)
    message = failure(["figures", "--only", "fig3b", "-o", str(path)], code=2)
    assert "--outdir" in message and says in message, message


@pytest.mark.parametrize("command", ["figures", "starts"])
def test_an_empty_outdir_is_no_directory(command):
    """``Path("")`` is the current directory: an empty -o used to write there."""
    message = failure([command, "-o", " "], code=2)
    assert "--outdir" in message and "names no directory" in message


def test_figures_turns_a_write_error_into_one_line(tmp_path, monkeypatch):
    from matplotlib.figure import Figure

    def full(self, fname, **kwargs):
        raise OSError(errno.EDQUOT, "Disk quota exceeded", str(fname))

    monkeypatch.setattr(Figure, "savefig", full)
    message = failure(["figures", "--only", "fig3b", "-o", str(tmp_path), "--dpi", "20"], code=1)
    assert "--outdir" in message and "fig3b.png" in message and "quota" in message
    assert files(tmp_path) == []


def test_figures_writes_through_the_checked_path(tmp_path):
    out = tmp_path / "new"
    code, stdout, err = run_cli_inprocess(["figures", "--only", "fig3b", "-o", str(out)])
    assert code == 0, err
    assert files(out) == ["fig3b.png"] and str(out / "fig3b.png") in stdout


def test_starts_checks_its_figure_paths_before_the_work(tmp_path):
    (tmp_path / "starts_region_rest_mu0p3.png").mkdir()
    argv = ["starts", "--mu-s", "0.3", "--grid", "2", "--lattice", "2", "2", "--no-map", "-q"]
    message = failure([*argv, "-o", str(tmp_path)], code=2)
    assert "--outdir" in message and "is a directory" in message
    message = failure([*argv, "-o", str(tmp_path / "missing")], code=2)
    assert "--outdir" in message and "not a directory" in message


# --- 2. size and resolution options are bounded ----------------------------------------------


@pytest.mark.parametrize(
    "argv, option, allowed",
    [
        (["figures", "--dpi", "20000"], "--dpi", "[20, 600]"),
        (["figures", "--dpi", "19"], "--dpi", "[20, 600]"),
        (["figures", "--slice-resolution", "100000"], "--slice-resolution", "[2, 10000]"),
        (["figures", "--resolution", "201"], "--resolution", "[2, 200]"),
        (["figures", "--n-scan", "1000000"], "--n-scan", "[2, 100000]"),
        (["figures", "--dpi", "1" + "0" * 400], "--dpi", "[20, 600]"),
        (["starts", "--dpi", "20000"], "--dpi", "[20, 600]"),
        (["starts", "--threads", "100000"], "--threads", "[0, 256]"),
        (["starts", "--grid", "65"], "--grid", "[2, 64]"),
        (["starts", "--map-grid", "129"], "--map-grid", "[2, 128]"),
        (["starts", "--lattice", "2", "1001"], "--lattice", "[2, 1000]"),
        (["starts", "--map-size", "2", "10**9"], "--map-size", "[2, 5000]"),
    ],
)
def test_size_options_are_bounded(argv, option, allowed):
    message = failure(argv, code=2)
    assert option in message and allowed in message, message


def test_the_map_of_starts_is_bounded_before_the_search():
    message = failure(["starts", "--map-size", "200", "200", "-q"], code=2)
    assert "--map-size" in message and "10000" in message


def test_the_figure_functions_bound_their_resolution():
    with pytest.raises(ValueError, match=r"resolution .* \[2, 10000\]"):
        plot.fig4_slices(1.0, resolution=10**5)
    with pytest.raises(ValueError, match=r"resolution .* \[2, 200\]"):
        plot.jarm_surfaces(1.0, 1, resolution=10**4)
    with pytest.raises(ValueError, match=r"resolution .* \[2, 200\]"):
        plot.fig4(1.0, resolution=201)


# --- 3. negative numbers are values -----------------------------------------------------------


@pytest.mark.parametrize(
    "args, dest, value",
    [
        (["--omega0", "-1e-3"], "omega0", -1e-3),
        (["--omega0=-1e-3"], "omega0", -1e-3),
        (["--theta0", "-0.5"], "theta0", -0.5),
        (["--theta0", "-1E+2"], "theta0", -100.0),
        (["--slip0", "-1"], "slip0", -1.0),
        (["--slip0", "-.5e-1"], "slip0", -0.05),
        (["--l-max", "-inf"], "l_max", -math.inf),
    ],
)
def test_negative_numbers_parse(args, dest, value):
    ns = build_parser().parse_args([*SIMULATE, *args])
    assert getattr(ns, dest) == value


def test_negative_omega0_runs():
    code, _, err = run_cli_inprocess([*ROLL, "--omega0", "-1e-3", "--json"])
    assert code == 0, err


#: A valid value of each required option, to parse one option at a time.
REQUIRED = {
    "--alpha": ["30"],
    "--chi": ["0.5"],
    "--km": ["0.4"],
    "--mu-s": ["1"],
    "--alpha-range": ["10", "50"],
    "--output": ["x.npz"],
}


def _subcommands() -> dict[str, Parser]:
    parser = build_parser()
    (sub,) = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    return dict(sub.choices)


def _numeric_options(p: Parser):
    for action in p._actions:
        if action.option_strings and action.type not in (None, str) and action.nargs != 0:
            if action.choices is None and getattr(action.type, "__name__", "") != "Path":
                yield action


@pytest.mark.parametrize("command", sorted(_subcommands()))
def test_every_numeric_option_reads_a_negative_number(command, capsys):
    """-1e-3 reaches the option's type (which may refuse it by its range), never "expected
    one argument"."""
    p = _subcommands()[command]
    required = [a for a in p._actions if a.required and a.option_strings]
    base = [command]
    for a in required:
        base += [a.option_strings[-1], *REQUIRED[a.option_strings[-1]]]
    options = list(_numeric_options(p))
    assert options, command
    for action in options:
        count = action.nargs if isinstance(action.nargs, int) else 1
        argv = [*base, action.option_strings[-1], *["-1e-3"] * count]
        try:
            build_parser().parse_args(argv)
        except SystemExit:
            err = capsys.readouterr().err
            assert "expected" not in err and "unrecognized" not in err, (argv, err)


def test_the_negative_number_pattern():
    for text in ("-1", "-1.5", "-.5", "-1e-3", "-1E+3", "-1_000", "-inf", "-Infinity", "-nan"):
        assert NEGATIVE_NUMBER.match(text), text
        float(text)
    for text in ("-o", "--mu-s", "-q", "-e", "-x1", "-1x", "--1"):
        assert not NEGATIVE_NUMBER.match(text), text


# --- 4. printed numbers have a bounded length --------------------------------------------------


def test_starts_prints_no_quotient_of_a_zero_fraction():
    argv = ["starts", "--mu-s", "0.3", "--grid", "2", "--lattice", "2", "2", "--no-map", "-q"]
    code, out, err = run_cli_inprocess(argv)
    assert code == 0, err
    assert "no JARM from rest" in out
    assert not re.search(r"\d{20}", out) and max(map(len, out.splitlines())) < MAX_MESSAGE


def test_fixed_point_formats_are_bounded():
    assert bounded(1.5, "14.8f") == "    1.50000000"
    assert len(bounded(1e300, "14.8f")) < 20 and bounded(-1e300, ".1f") == "-1.0e+300"
    assert bounded(math.inf, ".3f") == "inf" and bounded(1e300, ".6g") == "1e+300"


def test_roll_prints_bounded_numbers():
    code, out, err = run_cli_inprocess([*ROLL, "--t-max", "1e6", "--mu-s", "1"])
    assert code == 0, err
    assert not re.search(r"\d{20}", out)


# --- 5. times are not numbers; arrays where a scalar is due -------------------------------------

BODY = eccjump.Cylinder(*JARM_BODY)
#: numpy makes a timedelta64 an integer (np.signedinteger): it used to pass as one.
TIME = np.timedelta64(1)


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: eccjump.roll(BODY, TIME, mu_s=1), "alpha"),
        (lambda: eccjump.roll(BODY, 0.5, mu_s=TIME), "mu_s"),
        (lambda: eccjump.roll(BODY, 0.5, max_steps=TIME), "max_steps"),
        (lambda: eccjump.Cylinder(np.datetime64("2020-01-01"), 0.1), "chi"),
        (lambda: eccjump.jarm(TIME, 0.2, 0.1, 1.0), "alpha"),
        (lambda: eccjump.jarm([TIME], 0.2, 0.1, 1.0), "alpha"),
        (lambda: eccjump.Units(g=TIME), "g"),
        (
            lambda: eccjump.region(mu_s=1.0, alpha=[0.5], chi=[0.2], km_frac=[0.1], n_threads=TIME),
            "n_threads",
        ),
    ],
)
def test_times_are_refused_naming_the_parameter(call, name):
    with pytest.raises(TypeError, match=rf"^{name} must"):
        call()


def test_motion_map_refuses_an_array_tolerance_naming_it():
    with pytest.raises((TypeError, ValueError), match="rtol"):
        eccjump.motion_map(alpha=[0.5], chi=[0.2], km_frac=[0.1], mu_s=1.0, rtol=np.array([1e-8]))


def test_real_names_the_parameter_of_an_array():
    from eccjump._base.checks import real

    with pytest.raises(TypeError, match=r"^rtol must be a real number, not an array"):
        real("rtol", np.array([1e-8]))


# --- 6. sequence_name takes a code of the table ------------------------------------------------


@pytest.mark.parametrize(
    "code, error",
    [
        (-1, ValueError),
        (4**motion_fields.SEQUENCE_LEN, ValueError),
        (10**400, ValueError),
        (4, ValueError),  # a gap: no sequence_code makes it
        ("13", TypeError),
        (13.0, TypeError),
        (True, TypeError),
        (None, TypeError),
        (np.timedelta64(13), TypeError),
    ],
)
def test_sequence_name_refuses_what_is_no_code(code, error):
    with pytest.raises(error, match=r"^code "):
        motion_fields.sequence_name(code)


def test_sequence_name_names_every_code_of_the_table():
    modes = ["ROLL", "SLIP", "FLIGHT", "ROLL", "SLIP", "FLIGHT", "ROLL", "SLIP"]
    code = motion_fields.sequence_code(modes)
    assert motion_fields.sequence_name(code) == "→".join(modes)
    assert motion_fields.sequence_name(np.uint16(13)) == "ROLL→FLIGHT"
    assert motion_fields.sequence_name(np.array(13)) == "ROLL→FLIGHT"
    assert motion_fields.sequence_name(0) == ""


# --- 7. SI scales within a range that keeps the derived units finite and normal ------------------


@pytest.mark.parametrize(
    "scales, name",
    [
        ({"g": 1e200, "R": 1e200}, "g"),  # energies M g R = 1e400: inf
        ({"g": 1e-200, "R": 1e-150, "M": 1e-100}, "g"),  # M g R = 1e-450: 0.0
        ({"R": 1e-150}, "R"),
        ({"M": 1e51}, "M"),
        ({"M": math.nan}, "M"),
    ],
)
def test_to_si_refuses_scales_outside_their_range(scales, name):
    r = eccjump.roll(eccjump.Cylinder(*JARM_BODY), 0.7, mu_s=1.0)
    allowed = r"outside the allowed range \[1e-50, 1e\+50\]"
    with pytest.raises(ValueError, match=rf"^{name} = .* {allowed}"):
        r.to_si(**scales)


def test_to_si_at_the_ends_of_the_range_is_finite_and_normal():
    r = eccjump.simulate(eccjump.Cylinder(*JARM_BODY), 0.7, mu_s=1.0, t_max=2.0)

    for g, R, M in ((1e50, 1e50, 1e50), (1e-50, 1e-50, 1e-50), (1e50, 1e-50, 1e50)):
        si = r.to_si(g=g, R=R, M=M)
        for name in ("t", "omega", "l", "ldot", "Fx", "Fy", "energy"):
            before, after = getattr(r, name), getattr(si, name)
            assert np.array_equal(np.isfinite(before), np.isfinite(after)), name
            assert np.array_equal(before == 0, after == 0), name


# --- 8. a misspelt option is named with its close spelling ---------------------------------------


@pytest.mark.parametrize("command", sorted(_subcommands()))
def test_a_misspelt_option_gets_a_suggestion(command):
    p = _subcommands()[command]
    option = next(o for a in p._actions for o in a.option_strings if o.count("-") >= 3)
    misspelt = "--" + option[2:].replace("-", "_")
    message = failure([command, misspelt, "1"], code=2)
    assert message.startswith(f"eccjump {command}: error:"), message
    assert f"did you mean {option}?" in message, message


@pytest.mark.parametrize(
    "argv, hint",
    [
        ([*ROLL, "--mu_s", "1"], "--mu-s"),
        ([*ROLL, "--omgea0", "1"], "--omega0"),
        ([*SIMULATE[:7], "--mu_s", "1"], "--mu-s"),  # before "required: --mu-s"
        (["map", "--mu_s", "1", "-o", "x.npz"], "--mu-s"),
        (["design", "--alpha_range", "10", "50", "--mu-s", "1"], "--alpha-range"),
    ],
)
def test_misspellings_are_suggested(argv, hint):
    message = failure(argv, code=2)
    assert f"did you mean {hint}?" in message, message


def test_unknown_arguments_are_reported_by_the_subcommand():
    message = failure([*ROLL, "stray"], code=2)
    assert message.startswith("eccjump roll: error: unrecognized arguments: stray")
    message = failure([*ROLL, "--bogus"], code=2)
    assert message == "eccjump roll: error: unrecognized options: --bogus"


def test_an_unknown_option_before_the_subcommand_is_named():
    message = failure(["--bogus", *ROLL], code=2)
    assert message == "eccjump: error: unrecognized options: --bogus"


def test_long_values_are_cut_in_messages():
    message = failure([*ROLL, "--rule", "x" * 5000], code=2)
    assert "--rule" in message and "paper" in message
    message = failure([*ROLL, "--chi", "y" * 5000], code=2)
    assert "--chi" in message


def test_abbreviations_still_work():
    ns = build_parser().parse_args([*ROLL, "--mu", "1", "--omega", "-2"])
    assert ns.mu_s == 1.0 and ns.omega0 == -2.0


def test_main_returns_the_status_of_a_parse_error():
    with pytest.raises(SystemExit) as exc:
        main([*ROLL, "--mu_s", "1"])
    assert exc.value.code == 2


# --- issue 46, items 12, 14, 15: writes, overwrites and the options of each --kind --------

UNCERTAINTY = ["uncertainty", *JARM_ARGS, "--mu-s", "1",
               "--sd", "chi", "0.01", "-n", "64", "-q"]  # fmt: skip


@pytest.fixture
def small_tmpfs(tmp_path):
    """A 64 KiB tmpfs (root only): a disk that fills up for real."""
    mount = tmp_path / "full"
    mount.mkdir()
    if os.geteuid() != 0 or os.system(f"mount -t tmpfs -o size=64k tmpfs {mount} 2>/dev/null"):
        pytest.skip("needs root to mount a small tmpfs")
    yield mount
    os.system(f"umount {mount}")


@pytest.mark.parametrize("suffix", [".nc", ".csv"])
def test_uncertainty_on_a_full_disk_is_one_line(small_tmpfs, suffix):
    # -o u.nc on a full disk was a traceback (RuntimeError: NetCDF: HDF error).
    if suffix == ".nc":
        pytest.importorskip("xarray")
    target = small_tmpfs / f"u{suffix}"
    message = failure([*UNCERTAINTY, "-n", "20000", "-o", str(target)], code=1)
    assert "--output" in message and "full/u" in message, message
    assert files(small_tmpfs) == []


def test_a_failed_netcdf_write_is_one_line(tmp_path, monkeypatch):
    # The same without root: the netCDF writer raises what it raises on a full disk.
    xr = pytest.importorskip("xarray")

    def full(self, *args, **kwargs):
        raise RuntimeError("NetCDF: HDF error")

    monkeypatch.setattr(xr.Dataset, "to_netcdf", full)
    message = failure([*UNCERTAINTY, "-o", str(tmp_path / "u.nc")], code=1)
    assert "--output" in message and "HDF error" in message, message
    assert files(tmp_path) == []


def test_a_write_without_space_is_one_line(tmp_path, monkeypatch):
    def no_space(*args, **kwargs):
        raise OSError(errno.ENOSPC, "No space left on device", "somewhere")

    monkeypatch.setattr(np, "savetxt", no_space)
    message = failure([*UNCERTAINTY, "-o", str(tmp_path / "u.csv")], code=1)
    assert "--output" in message and "No space left" in message and "u.csv" in message
    assert files(tmp_path) == []


def test_uncertainty_refuses_an_existing_output_unless_overwrite(tmp_path):
    target = tmp_path / "u.csv"
    target.write_text("mine")
    message = failure([*UNCERTAINTY, "-o", str(target)], code=2)
    assert "--output" in message and "--overwrite" in message
    assert target.read_text() == "mine"
    code, _, err = run_cli_inprocess([*UNCERTAINTY, "-o", str(target), "--overwrite"])
    assert code == 0, err
    assert eccjump.Uncertainty.load(target).n == 64


def test_starts_with_a_name_too_long_is_one_line(tmp_path):
    # -o <300 characters> was a traceback (OSError: File name too long).
    message = failure(["starts", "--no-map", "-o", str(tmp_path / ("x" * 300))], code=2)
    assert "--outdir" in message and "too long" in message


def test_any_other_oserror_is_one_line_naming_the_option(tmp_path, monkeypatch):
    # The fallback of every subcommand: an OSError outside the writes names its option.
    from eccjump.cli import starts as cli_starts

    target = tmp_path / "figs"
    target.mkdir()

    def broken(*args, **kwargs):
        raise OSError(errno.EIO, "Input/output error", str(target / "starts_mu1.png"))

    monkeypatch.setattr(cli_starts, "check_outputs", broken)
    message = failure(["starts", "--no-map", "--mu-s", "1", "-o", str(target)], code=1)
    assert message.startswith("eccjump: error: --outdir") and "Input/output error" in message


MAP = ["map", "--mu-s", "1", "--grid", "2"]


@pytest.mark.parametrize(
    ("kind", "option", "value", "owner"),
    [
        ("motion", "--max-turns", "5", "jarm"),
        ("motion", "--n", "2", "jarm"),
        ("motion", "--route", "ode", "jarm"),
        ("motion", "--stop-at-slip", None, "jarm"),
        ("jarm", "--mu-k", "0.5", "motion"),
        ("jarm", "--restitution", "0.5", "motion"),
        ("jarm", "--t-max", "5", "motion"),
        ("jarm", "--max-transitions", "5", "motion"),
    ],
)
def test_map_refuses_the_options_of_the_other_kind(tmp_path, kind, option, value, owner):
    # --max-turns 4294967296 with --kind motion exited 0, while --n was refused.
    given = [option] if value is None else [option, value]
    argv = [*MAP, "--kind", kind, *given, "-o", str(tmp_path / "m.npz")]
    message = failure(argv, code=2)
    assert f"{option} is an option of --kind {owner}" in message
    assert files(tmp_path) == []


@pytest.mark.parametrize("kind", ["jarm", "motion"])
def test_map_checks_the_range_of_max_turns(tmp_path, kind):
    argv = [*MAP, "--kind", kind, "--max-turns", "4294967296", "-o", str(tmp_path / "m.npz")]
    message = failure(argv, code=2)
    assert "--max-turns" in message and "1000000" in message


def _angle_options() -> list[tuple[str, argparse.Action]]:
    """(subcommand, action) of every option of the command line."""
    sub = next(a for a in build_parser()._actions if isinstance(a, argparse._SubParsersAction))
    return [(name, a) for name, p in sub.choices.items() for a in p._actions if a.option_strings]


def test_every_option_in_degrees_is_a_degrees_action():
    """One mechanism for the note on a degree value that looks like radians: an option whose
    help says [deg] that is not a Degrees action would forget it. (The tolerances --sd
    alpha SD say "in degrees": a spread's size cannot tell its unit, so they get no note.)"""
    for command, action in _angle_options():
        in_degrees = "[deg]" in (action.help or "")
        assert in_degrees == isinstance(action, Degrees), (command, action.option_strings)
    degrees = {(c, a.option_strings[0]) for c, a in _angle_options() if isinstance(a, Degrees)}
    # roll, simulate, map, design, uncertainty, track, analyze: every subcommand with angles
    assert {c for c, _ in degrees} == {
        "roll", "simulate", "map", "design", "uncertainty", "track", "analyze"
    }  # fmt: skip


@pytest.mark.parametrize(
    "command, option",
    sorted((c, a.option_strings[0]) for c, a in _angle_options() if isinstance(a, Degrees)),
)
def test_each_degree_option_notes_a_value_that_looks_like_radians(command, option, capsys):
    action = next(a for c, a in _angle_options() if c == command and a.option_strings[0] == option)
    ramp = action.radians_up_to == RAMP_RADIANS  # type: ignore[attr-defined]
    n = action.nargs if isinstance(action.nargs, int) else 1

    def given(text: str) -> str:
        value = [action.type(text)] * n if action.nargs else action.type(text)  # type: ignore[misc]
        action(argparse.ArgumentParser(), argparse.Namespace(), value, option)
        return capsys.readouterr().err

    note = given("0.698")
    assert note.startswith(f"note: {option} is in degrees: 0.698") and "39.9925" in note, note
    assert given("40" if ramp else "200") == ""  # degrees by the look of them
    assert given("0") == ""  # 0 is 0 in either unit
    if ramp:
        assert given("1.6") == ""  # above pi/2: no radian ramp


def test_roll_notes_an_alpha_in_radians():
    """The issue's reproducer: ``eccjump roll --alpha 0.698`` ran at 0.698 deg without a
    word."""
    code, _, err = run_cli_inprocess(
        ["roll", "--alpha", "0.698", "--chi", "0.15", "--km", "0.02", "--mu-s", "1"]
    )
    assert code == 0
    assert "note: --alpha is in degrees: 0.698 deg; for 0.698 rad write --alpha 39.9925" in err


def test_uncertainty_notes_bounds_of_an_angle_in_radians():
    argv = ["uncertainty", "--alpha", "40", "--chi", "0.15", "--km", "0.02", "--mu-s", "1",
            "--bounds", "alpha", "0.6", "0.8", "-n", "16", "-q"]  # fmt: skip
    code, _, err = run_cli_inprocess(argv)
    assert code == 0 and "note: --bounds alpha is in degrees: 0.6 0.8 deg" in err, err
