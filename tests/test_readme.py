"""Every example in README.md runs, and prints what the README says it prints.

- the first command's command-line part runs and writes its file and figure;
- each ``console`` block: every ``$ command`` is run and its output compared line by line
  (the wall-time line of ``eccjump map`` excepted);
- each ``python`` block runs; a ``print(...)  # expected`` comment that starts like a value
  is checked token by token (each expected token a prefix of the printed one).
"""

from __future__ import annotations

import contextlib
import io
import re
import shlex
import subprocess
from pathlib import Path

import pytest

README = Path(__file__).resolve().parent.parent / "README.md"
BLOCKS = re.findall(r"```(\w+)\n(.*?)```", README.read_text(), re.S)
TIMING = re.compile(r"^time\s+[\d.]+ s, ")


def blocks(lang: str) -> list[str]:
    return [body for kind, body in BLOCKS if kind == lang]


def run_cli(command: str, cwd: Path) -> str:
    args = shlex.split(command)
    assert args[0] == "eccjump", command
    p = subprocess.run(args, cwd=cwd, capture_output=True, text=True, timeout=300, check=False)
    assert p.returncode == 0, p.stderr
    return p.stdout


def test_the_two_commands_come_first():
    first, second = blocks("bash")[:2]
    assert first.startswith("pip install") and "eccjump map" in first
    assert "pytest" in second and "cargo test" in second
    assert (README.parent / ".ci" / "run").read_text().strip().endswith(second.strip())


def test_first_command_writes_a_map_and_a_figure(tmp_path):
    command = blocks("bash")[0].split("&&", 1)[1].strip()
    out = run_cli(command, tmp_path)
    assert "complete" in out
    assert (tmp_path / "region.nc").stat().st_size > 0
    assert (tmp_path / "region.png").stat().st_size > 10_000


@pytest.mark.parametrize("block", blocks("console"), ids=lambda b: b.split("\n")[0][2:40])
def test_console_examples(block, tmp_path):
    chunks = re.split(r"^\$ ", block, flags=re.M)[1:]
    for chunk in chunks:
        command, _, expected = chunk.partition("\n")
        got = run_cli(command, tmp_path).splitlines()
        want = expected.rstrip("\n").splitlines()
        assert len(got) == len(want), "\n".join(got)
        for g, w in zip(got, want, strict=True):
            if TIMING.match(w):
                assert TIMING.match(g), g
            else:
                assert g.rstrip() == w.rstrip()


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


@pytest.mark.parametrize("code", blocks("python"), ids=lambda c: c.split("\n")[1][:40])
def test_python_examples(code, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        exec(compile(code, str(README), "exec"), {"__name__": "__readme__"})
    printed = buf.getvalue().splitlines()
    expected = _expected_prints(code)
    assert len(printed) == len(expected)
    for got, want in zip(printed, expected, strict=True):
        if want is None:
            continue
        gt, wt = _tokens(got), _tokens(want)
        assert len(gt) == len(wt), (got, want)
        for g, w in zip(gt, wt, strict=True):
            assert g.startswith(w), (got, want)
