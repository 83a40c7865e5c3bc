#!/usr/bin/env bash
# The declared minimum versions are tested ones: the lowest versions of the direct dependencies
# of every extra (pyproject.toml: [all] and [test]) that have wheels for this Python, resolved by
# `uv pip install --resolution lowest-direct` (their own dependencies at their newest, as a
# user gets them), the package installed over them, and `pytest -m "not slow"` run against it.
#   1. the tools (uv) in a venv;
#   2. a fresh venv with the lowest direct dependencies, wheels only; the versions are printed;
#   3. the package: the wheel ECCJUMP_WHEEL if set, else built here (the core compiles in
#      about two minutes), installed without touching those versions; `uv pip check`;
#   4. `pytest -m "not slow" -n auto` from the checkout's tests against the installed package.
# Every step fails the script. Everything it makes goes in one temporary directory, removed at
# exit, but uv's download cache (set CARGO_TARGET_DIR to keep compiled crates between runs).
# Run it with the oldest supported Python (PYTHON, default python3; requires-python says 3.11):
# a newer Python has no wheels of some minimums, and uv then takes the lowest that have them.
# Needs a Rust toolchain (>= 1.83) unless ECCJUMP_WHEEL is given, and network for the index.
set -euo pipefail
unset PYTHONPATH # the venv runs what it installed, never a checkout

repo=$(cd "$(dirname "$0")/.." && pwd)
python=${PYTHON:-python3}
work=$(mktemp -d "${TMPDIR:-/tmp}/eccjump-minimums.XXXXXX")
trap 'rm -rf "$work"' EXIT
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-$work/target}
venv=$work/lowest

step() { printf '\n== %s (at %d s)\n' "$*" "$SECONDS"; }
fail() {
    echo "check_minimums: $*" >&2
    exit 1
}

step "tools (uv) in a venv"
"$python" -m venv "$work/tools"
"$work/tools/bin/pip" install -q uv
uv=$work/tools/bin/uv

step "the lowest versions of the direct dependencies, wheels only"
"$uv" venv -q --python "$python" "$venv"
(cd "$repo" && VIRTUAL_ENV=$venv "$uv" pip install -q --only-binary :all: \
    --resolution lowest-direct -r pyproject.toml --extra all --extra test)
VIRTUAL_ENV=$venv "$uv" pip freeze

step "the package over them"
if [[ -n ${ECCJUMP_WHEEL:-} ]]; then
    VIRTUAL_ENV=$venv "$uv" pip install -q --no-deps "$ECCJUMP_WHEEL"
else
    VIRTUAL_ENV=$venv "$uv" pip install -q --no-deps "$repo"
fi
VIRTUAL_ENV=$venv "$uv" pip check
where=$(cd "$work" && "$venv/bin/python" -c "import eccjump; print(eccjump.__file__)")
[[ $where == "$venv"/* ]] || fail "eccjump is imported from $where, not from the venv"

step "pytest -m 'not slow' against the lowest versions"
# PATH: the tests that run the `eccjump` command run the venv's.
(cd "$repo" && PATH="$venv/bin:$PATH" "$venv/bin/python" -m pytest -m "not slow" -n auto \
    -p no:cacheprovider -q)

step "done: the tests pass with the lowest versions"
