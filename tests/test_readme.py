"""Every example in README.md runs, and prints what the README says it prints.

- the first command's command-line part runs and writes its file and figure;
- each ``console`` block: every ``$ command`` is run with this interpreter
  (``python -m eccjump.cli``, so the virtual environment's bin need not be on PATH) and its
  output compared line by line (the wall-time line of ``eccjump map`` excepted): the text
  between numbers exactly, the numbers within the tolerances below;
- each ``python`` block runs; a ``print(...)  # expected`` comment that starts like a value
  is checked token by token: words exactly, numbers within the tolerances below.

Tolerances. The README's numbers come from one machine; float64 results move with the
platform's libm (sin, cos) and CPU by ulps, which can flip a printed last digit, a step-size
decision or a grid point on a region boundary. So a printed number must agree to
- one unit in its last printed digit (the value straddled a rounding boundary), plus
- REL of itself: roots and extrema of float64 functions of sin/cos move by ~1e-15 relative
  for a 1-ulp change of libm, integrated values by far less than their rtol 1e-10 error;
- counts of floating-point decisions get a slack in counts (COUNT_SLACK, FLIPS).
"""

from __future__ import annotations

import math
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

README = Path(__file__).resolve().parent.parent / "README.md"
BLOCKS = re.findall(r"```(\w+)\n(.*?)```", README.read_text(), re.S)
TIMING = re.compile(r"^time\s+[\d.]+ s, ")
NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:e[-+]?\d+)?")

# ~1000x the ~1e-15 relative change a 1-ulp libm difference makes to our closed-form roots.
REL = 1e-12
# Integers on these lines count accept/reject decisions of the step-size controller: one
# error norm within rounding of 1 (at rtol 1e-10 rounding is ~1e-6 of the error estimate)
# may go the other way, changing the accepted steps by 1 and the evaluations by 6.
COUNT_SLACK = {
    "steps": (2, 12),
    # The energy ledger closes to ~1e-9 at rtol 1e-10 (docs/motion.md): a step taken
    # differently on another platform moves the energies and the balance at that level.
    "energy": (0, 1e-8, 1e-8),
    "dissipated": (1e-8, 1e-8, 0, 1e-8),
}
# Grid points that may change sides of a region boundary on another platform. Nudging every
# axis of the README's two grids by one ulp flips none of their points (measured), so 2 is a
# margin over none seen, small against the 1733 and 3561 JARM points counted.
FLIPS = 2
# Map summary lines: a fraction of the grid's points and their count, in parentheses.
MAP_COUNT_LINE = re.compile(r"^(JARM\s|  n [=>] )")
# Printed grid fractions in the python blocks: expected text -> number of grid points.
FRACTION_PRINTS = {"(90, 50, 50) 0.0077022": 90 * 50 * 50}


def blocks(lang: str) -> list[str]:
    return [body for kind, body in BLOCKS if kind == lang]


def run_cli(command: str, cwd: Path) -> str:
    args = shlex.split(command)
    assert args[0] == "eccjump", command
    cmd = [sys.executable, "-m", "eccjump.cli", *args[1:]]
    p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=300, check=False)
    assert p.returncode == 0, p.stderr
    return p.stdout


def _unit(token: str) -> float:
    """One unit in the last printed digit of a number token."""
    mantissa, _, exponent = token.lower().partition("e")
    decimals = len(mantissa.partition(".")[2])
    return 10.0 ** (int(exponent or 0) - decimals)


def _is_int(token: str) -> bool:
    return re.fullmatch(r"[-+]?\d+", token) is not None


def number_close(got: str, want: str, slack: float = 0.0) -> bool:
    """got agrees with the printed want: integers within slack counts, other numbers within
    one unit in want's last digit + REL * |want| + slack."""
    if _is_int(want):
        return _is_int(got) and abs(int(got) - int(want)) <= slack
    g, w = float(got), float(want)
    return math.isfinite(g) and abs(g - w) <= _unit(want) + REL * abs(w) + slack


def compare_line(got: str, want: str, points: int | None) -> None:
    """Text between numbers exactly, numbers with the tolerances of the module docstring;
    `points` is the grid size behind a map summary line."""
    g_text, w_text = NUMBER.split(got.rstrip()), NUMBER.split(want.rstrip())
    g_nums, w_nums = NUMBER.findall(got), NUMBER.findall(want)
    assert g_text == w_text, (got, want)
    slack = [0.0] * len(w_nums)
    label = want.split()[0] if want.split() else ""
    if label in COUNT_SLACK:
        slack = [float(x) for x in COUNT_SLACK[label]]
        assert len(slack) == len(w_nums), want
    elif MAP_COUNT_LINE.match(want):
        assert points, "no grid line before the summary"
        # the fraction (then the count) are the last two numbers of the line
        slack[-2:] = [FLIPS / points, FLIPS]
    for g, w, s in zip(g_nums, w_nums, slack, strict=True):
        assert number_close(g, w, s), (got, want)


def test_the_two_commands_come_first():
    first, second = blocks("bash")[:2]
    assert first.startswith("pip install") and "eccjump map" in first
    assert "pytest" in second and "cargo test" in second
    # CI runs it verbatim, on a line of its own (then the documentation's: tests/test_docs.py)
    assert second.strip() in (README.parent / ".ci" / "run").read_text().splitlines()


def collected(*args: str) -> str:
    """The test ids ``pytest --collect-only`` lists with ``args``, from the checkout."""
    cmd = [sys.executable, "-m", "pytest", "--collect-only", "-q", "-p", "no:cacheprovider"]
    p = subprocess.run(
        [*cmd, *args], cwd=README.parent, capture_output=True, text=True, timeout=120, check=False
    )
    assert p.returncode == 0, p.stdout[-2000:] + p.stderr[-2000:]
    return p.stdout


@pytest.mark.slow
def test_the_quick_check_leaves_out_the_campaigns():
    """`pytest -m "not slow"`, the README's quick check, runs no campaign (minutes each),
    though a -m of the command line replaces the one of addopts; `-m campaign` runs them."""
    verdict = "tests/test_analysis_verdict.py"
    quick = collected("-m", "not slow", verdict)
    assert "::test_a_slip_the_data_ask_for_is_never_jarm" in quick
    assert "::test_never_confidently_wrong" not in quick
    assert "::test_never_confidently_wrong" in collected("-m", "campaign", verdict)


@pytest.mark.slow
def test_first_command_writes_a_map_and_a_figure(tmp_path):
    command = blocks("bash")[0].split("&&", 1)[1].strip()
    out = run_cli(command, tmp_path)
    assert "complete" in out
    assert (tmp_path / "region.nc").stat().st_size > 0
    assert (tmp_path / "region.png").stat().st_size > 10_000


@pytest.mark.slow
@pytest.mark.parametrize("block", blocks("console"), ids=lambda b: b.split("\n")[0][2:40])
def test_console_examples(block, tmp_path):
    chunks = re.split(r"^\$ ", block, flags=re.M)[1:]
    for chunk in chunks:
        command, _, expected = chunk.partition("\n")
        got = run_cli(command, tmp_path).splitlines()
        want = expected.rstrip("\n").splitlines()
        assert len(got) == len(want), "\n".join(got)
        points = None
        for g, w in zip(got, want, strict=True):
            if TIMING.match(w):
                assert TIMING.match(g), g
                continue
            if m := re.match(r"grid .* = (\d+) points", w):
                points = int(m[1])
            compare_line(g, w, points)


def _expected_prints(code: str) -> list[str | None]:
    out = []
    for line in code.splitlines():
        m = re.match(r"\s*print\(.*\)\s+#\s*(.*)$", line)
        if m:
            text = m.group(1).split("  (")[0].strip()
            out.append(text if re.match(r"[\d\[(\-'\"]", text) else None)
        elif re.match(r"\s*print\(", line):
            out.append(None)
    return out


def _tokens(text: str) -> list[str]:
    return re.findall(r"[-+]?[\d.]+(?:e[-+]?\d+)?|'[^']*'|\w+", text)


def test_fraction_prints_are_in_the_readme():
    expected = [e for code in blocks("python") for e in _expected_prints(code)]
    for text in FRACTION_PRINTS:
        assert text in expected, text


@pytest.mark.slow
@pytest.mark.parametrize("code", blocks("python"), ids=lambda c: c.split("\n")[1][:40])
def test_python_examples(code, tmp_path):
    # Each example as a user runs it: saved as a script and run by Python (a Dask cluster
    # of processes needs the script's __main__ guard; run inline it did not).
    script = tmp_path / "example.py"
    script.write_text(code)
    p = subprocess.run(
        [sys.executable, str(script)], cwd=tmp_path, capture_output=True, text=True, timeout=300
    )
    assert p.returncode == 0, p.stderr[-3000:]
    printed = p.stdout.splitlines()
    expected = _expected_prints(code)
    assert len(printed) == len(expected)
    for got, want in zip(printed, expected, strict=True):
        if want is None:
            continue
        gt, wt = _tokens(got), _tokens(want)
        assert len(gt) == len(wt), (got, want)
        slack = [0.0] * len(wt)
        if want in FRACTION_PRINTS:
            slack[-1] = FLIPS / FRACTION_PRINTS[want]  # the fraction is the last number
        for g, w, s in zip(gt, wt, slack, strict=True):
            if NUMBER.fullmatch(w):
                assert number_close(g, w, s), (got, want)
            else:
                assert g == w, (got, want)


def test_ci_stops_at_a_failed_command_inside_a_readme_line():
    """``set -e`` ignores a failure inside ``a && b && c`` but for its last command, so a
    failed ``cargo test`` in the README's test line went on to the next step and the run
    could end 0: each such line of .ci/run is followed by ``check $?``, which stops it."""
    run = (README.parent / ".ci" / "run").read_text()
    lines = run.splitlines()
    commands = [x for x in lines if x and not x[0].isspace() and not x.startswith(("#", "if "))]
    chained = [i for i, x in enumerate(lines) if x in commands and "&&" in x]
    assert chained and all(lines[i + 1] == "check $?" for i in chained)
    define = next(line for line in lines if line.startswith("check()"))
    script = f"set -euo pipefail\n{define}\ntrue && false && true\ncheck $?\necho reached\n"
    done = subprocess.run(["bash", "-c", script], capture_output=True, text=True, timeout=10)
    assert done.returncode != 0 and "reached" not in done.stdout
