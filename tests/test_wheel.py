"""Wheels anyone can install.

- No CPU-specific code at compile time: no rustflags, target-cpu or target-feature in the cargo
  configuration, no `cfg(target_feature)` switch, and every function compiled for a CPU feature
  (`#[target_feature(enable = "X")]`) is called only behind `is_x86_feature_detected!("X")`.
- The compiled core agrees: its AVX (VEX-encoded) instructions are all inside those functions
  (or in libm's `fma`, which dispatches at run time itself).
- `scripts/check_wheel.sh` passes: the sdist and the README's manylinux2014 wheel build,
  install in fresh venvs and run (the wheel without Rust). It compiles the core twice (about
  4 minutes of CPU time, 9-10 minutes on 2 shared cores), so it runs only with
  ECCJUMP_TEST_WHEEL=1.
- The declared minimum versions are tested: every dependency has one, CI runs
  `scripts/check_minimums.sh` after the wheel check, and it passes (`pytest -m "not slow"`
  against the lowest versions; it compiles the core once, so it runs only with
  ECCJUMP_TEST_MINIMUMS=1).
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from eccjump import _core

ROOT = Path(__file__).resolve().parent.parent
RUST_SOURCES = sorted((ROOT / "rust").rglob("*.rs"))
CARGO_FILES = [ROOT / "Cargo.toml", *sorted((ROOT / "rust").glob("*/Cargo.toml"))]
FEATURE_FN = re.compile(r'#\[target_feature\(enable\s*=\s*"([^"]+)"\)\][^{;]*?\bfn\s+(\w+)', re.S)
# How far above a call its runtime check may stand (the `if` and a SAFETY comment).
CHECK_REACH = 4
# libm (a dependency) picks its fma instruction at run time through cpuid.
DISPATCHED_BY_LIBM = {"fma_with_fma", "fma_with_fma4", "fmaf_with_fma", "fmaf_with_fma4"}


def feature_functions() -> dict[str, str]:
    """Function name -> the CPU feature it is compiled for, over the Rust sources."""
    return {
        name: feature
        for path in RUST_SOURCES
        for feature, name in FEATURE_FN.findall(path.read_text())
    }


def test_no_cpu_flags_in_the_cargo_configuration():
    configs = [*ROOT.glob(".cargo/config*"), *ROOT.glob("rust/*/.cargo/config*")]
    assert not configs, configs
    for path in [*CARGO_FILES, ROOT / "pyproject.toml"]:
        text = path.read_text()
        for flag in ("rustflags", "target-cpu", "target-feature"):
            assert flag not in text, f"{path.name} sets {flag}"


def test_no_compile_time_feature_switch():
    for path in RUST_SOURCES:
        assert "target_feature =" not in path.read_text(), path


def test_feature_functions_are_called_only_behind_a_runtime_check():
    functions = feature_functions()
    assert functions == {"lanes_avx2": "avx2"}  # the 8-lane integrator; a new one: check it
    for name, feature in functions.items():
        check = f'is_x86_feature_detected!("{feature}")'
        calls = 0
        for path in RUST_SOURCES:
            lines = path.read_text().splitlines()
            for i, line in enumerate(lines):
                if re.search(rf"\b{name}\s*(::<|\()", line) and not re.search(r"\bfn\s", line):
                    calls += 1
                    above = "\n".join(lines[max(0, i - CHECK_REACH) : i])
                    assert check in above, f"{path.name}:{i + 1} calls {name} unchecked"
        assert calls > 0, name


def avx_functions(library: Path) -> set[str]:
    """Names of the functions of `library` with a VEX-encoded (AVX) instruction."""
    listing = subprocess.run(
        ["objdump", "-d", "--no-show-raw-insn", "-C", str(library)],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    found, current = set(), ""
    for line in listing.splitlines():
        if label := re.match(r"^[0-9a-f]+ <(.*)>:$", line):
            current = label[1].rsplit("::", 1)[-1]
        elif re.search(r"\tv\w+\s.*%[xyz]mm", line):
            found.add(current)
    return found


@pytest.mark.slow
@pytest.mark.skipif(not shutil.which("objdump"), reason="needs objdump (binutils)")
def test_avx_instructions_only_where_dispatched_at_run_time():
    library = Path(_core.__file__)
    symbols = subprocess.run(["nm", str(library)], capture_output=True, text=True).stdout
    if not symbols.strip():
        pytest.skip(f"{library.name} is stripped: no function names to check")
    found = avx_functions(library)
    assert "lanes_avx2" in found  # the check sees AVX where it is
    assert found <= set(feature_functions()) | DISPATCHED_BY_LIBM, found


@pytest.mark.slow
@pytest.mark.skipif(
    os.environ.get("ECCJUMP_TEST_WHEEL") != "1",
    reason="set ECCJUMP_TEST_WHEEL=1: builds and installs the sdist and the wheel (minutes)",
)
def test_sdist_and_portable_wheel_install_and_run():
    script = ROOT / "scripts" / "check_wheel.sh"
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}  # not the checkout's
    env["PYTHON"] = sys.executable
    p = subprocess.run(["bash", str(script)], env=env, capture_output=True, text=True, timeout=1800)
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
    assert "done: sdist and wheel install and run" in p.stdout


def test_every_dependency_has_a_minimum():
    """`--resolution lowest-direct` tests the declared minimums; one not declared would be
    resolved to the oldest release on the index."""
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    extras = project["optional-dependencies"]
    for req in [*project["dependencies"], *(r for name in extras for r in extras[name])]:
        if not req.startswith("eccjump["):
            assert ">=" in req, f"{req} declares no minimum version"


def test_ci_checks_the_minimums_after_the_wheel():
    lines = (ROOT / ".ci" / "run").read_text().strip().splitlines()
    wheel = lines.index("bash scripts/check_wheel.sh")
    assert lines.index("bash scripts/check_minimums.sh") > wheel


@pytest.mark.slow
@pytest.mark.skipif(
    os.environ.get("ECCJUMP_TEST_MINIMUMS") != "1",
    reason="set ECCJUMP_TEST_MINIMUMS=1: installs the lowest versions and runs the tests (minutes)",
)
def test_the_lowest_versions_pass_the_tests():
    script = ROOT / "scripts" / "check_minimums.sh"
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}  # not the checkout's
    env["PYTHON"] = sys.executable
    p = subprocess.run(["bash", str(script)], env=env, capture_output=True, text=True, timeout=3600)
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
    assert "done: the tests pass with the lowest versions" in p.stdout
