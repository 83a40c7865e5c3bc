#!/usr/bin/env bash
# What a user installs, installed as a user would:
#   1. the sdist: complete (LICENSE, CITATION.cff, CHANGELOG.md), no build outputs; installed in
#      a fresh venv (pip compiles the Rust core), `eccjump --version` and `eccjump roll` run;
#   2. the portable wheel of the README (abi3, manylinux2014 via zig): `auditwheel show` says
#      manylinux_2_17 or older; installed in a fresh venv without building anything and run with
#      no Rust toolchain reachable (PATH = the venv's bin only);
#   3. if qemu-x86_64 is installed: the wheel again on an emulated CPU without AVX (Nehalem).
# Every step fails the script. Everything it makes goes in one temporary directory, removed at
# exit: the tools, the venvs and the cargo target directory (set CARGO_TARGET_DIR to keep
# compiled crates between runs), so each run compiles the core twice from scratch.
# Needs python >= 3.11 (PYTHON, default python3), a Rust toolchain (>= 1.83) and network for pip.
set -euo pipefail
unset PYTHONPATH # the venvs run what they installed, never a checkout

repo=$(cd "$(dirname "$0")/.." && pwd)
python=${PYTHON:-python3}
work=$(mktemp -d "${TMPDIR:-/tmp}/eccjump-wheel.XXXXXX")
trap 'rm -rf "$work"' EXIT
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-$work/target}
roll=(roll --alpha 40 --chi 0.15 --km 0.02 --mu-s 1) # the README's JARM body: it lifts off

step() { printf '\n== %s (at %d s)\n' "$*" "$SECONDS"; }
fail() {
    echo "check_wheel: $*" >&2
    exit 1
}

# A portable wheel takes no CPU-specific flags at compile time (the core picks AVX2 at run time).
check_no_cpu_flags() {
    local var dir config
    for var in RUSTFLAGS CARGO_ENCODED_RUSTFLAGS CARGO_BUILD_RUSTFLAGS \
        CARGO_TARGET_X86_64_UNKNOWN_LINUX_GNU_RUSTFLAGS; do
        [[ -z ${!var:-} ]] || fail "$var is set ('${!var}'): a portable wheel takes no rustflags"
    done
    # cargo reads .cargo/config(.toml) in the directory it runs in and every parent, then CARGO_HOME.
    dir=$repo
    while :; do
        for config in "$dir"/.cargo/config "$dir"/.cargo/config.toml; do
            if [[ -f $config ]] && grep -qE 'rustflags|target-cpu|target-feature' "$config"; then
                fail "$config sets rustflags: a portable wheel takes none"
            fi
        done
        [[ $dir == / ]] && break
        dir=$(dirname "$dir")
    done
    for config in "${CARGO_HOME:-$HOME/.cargo}"/config{,.toml}; do
        if [[ -f $config ]] && grep -qE 'rustflags|target-cpu|target-feature' "$config"; then
            fail "$config sets rustflags: a portable wheel takes none"
        fi
    done
}

# Runs a command of venv $1 with nothing of this shell's environment: PATH is the venv's bin
# alone, so no cargo, rustc or checkout is reachable; the working directory is empty.
clean_run() {
    local venv=$1
    shift
    mkdir -p "$work/empty"
    (cd "$work/empty" && env -i PATH="$venv/bin" HOME="$work/empty" LC_ALL=C.UTF-8 "$@")
}

# `eccjump --version`, `eccjump roll` and the Python checks in venv $1.
check_installed() {
    local venv=$1 out
    out=$(clean_run "$venv" eccjump --version)
    [[ $out == "eccjump $version" ]] || fail "eccjump --version printed '$out', want 'eccjump $version'"
    out=$(clean_run "$venv" eccjump "${roll[@]}")
    grep -q "terminal event: liftoff" <<<"$out" || fail "eccjump roll: no lift-off in: $out"
    clean_run "$venv" python "$repo/scripts/wheel_smoke.py"
}

check_sdist_contents() {
    local listing name
    listing=$(tar tzf "$1" | cut -d/ -f2-)
    for name in LICENSE CITATION.cff CHANGELOG.md README.md pyproject.toml Cargo.lock; do
        grep -qx "$name" <<<"$listing" || fail "the sdist lacks $name"
    done
    if grep -E '^(target|dist|wheelhouse)/|\.(so|whl)$' <<<"$listing"; then
        fail "the sdist holds the build outputs above"
    fi
}

# auditwheel's verdict on wheel $1: manylinux_2_17 or older, tagged abi3.
check_wheel_tags() {
    local show glibc
    show=$(auditwheel show "$1")
    echo "$show"
    glibc=$(grep -oE 'manylinux_2_[0-9]+' <<<"$show" | head -n 1 | cut -d_ -f3)
    [[ -n $glibc ]] || fail "auditwheel finds no manylinux tag for $1"
    ((glibc <= 17)) || fail "the wheel needs glibc 2.$glibc, want 2.17 or older"
    [[ $(basename "$1") == eccjump-*-abi3-* ]] || fail "$1 is not tagged abi3"
    [[ $("$python" -m zipfile -l "$1") == *eccjump/_core.abi3.so* ]] || fail "$1 has no _core.abi3.so"
}

step "compile-time flags"
check_no_cpu_flags
version=$(grep -m 1 -oE '^version = "[^"]+"' "$repo/Cargo.toml" | cut -d'"' -f2)

step "build tools (maturin, ziglang, auditwheel) in a venv"
"$python" -m venv "$work/tools"
"$work/tools/bin/pip" install -q maturin ziglang auditwheel
export PATH="$work/tools/bin:$PATH" # maturin finds zig through this venv's python

step "sdist"
(cd "$repo" && maturin sdist --out "$work/sdist")
sdist=$(echo "$work"/sdist/eccjump-*.tar.gz)
check_sdist_contents "$sdist"

step "the sdist installed in a fresh venv (pip compiles the core)"
"$python" -m venv "$work/from-sdist"
"$work/from-sdist/bin/pip" install -q "$sdist"
check_installed "$work/from-sdist"

step "the README's portable wheel"
# XDG_CACHE_HOME: maturin's zig wrappers name the tools venv, so they go with it.
(cd "$repo" && XDG_CACHE_HOME="$work/cache" \
    maturin build --release --zig --compatibility manylinux2014 --out "$work/wheel")
wheel=$(echo "$work"/wheel/eccjump-*.whl)
check_wheel_tags "$wheel"

step "the wheel installed in a fresh venv, run without a Rust toolchain"
"$python" -m venv "$work/from-wheel"
"$work/from-wheel/bin/pip" install -q --only-binary=:all: "$wheel"
if clean_run "$work/from-wheel" /bin/sh -c 'command -v cargo || command -v rustc'; then
    fail "a Rust toolchain is reachable in the clean environment"
fi
check_installed "$work/from-wheel"

step "the wheel on an emulated CPU without AVX"
if command -v qemu-x86_64 >/dev/null; then
    clean_run "$work/from-wheel" "$(command -v qemu-x86_64)" -cpu Nehalem \
        "$work/from-wheel/bin/python" "$repo/scripts/wheel_smoke.py"
else
    echo "skipped: no qemu-x86_64 (apt-get install qemu-user)"
fi

step "done: sdist and wheel install and run"
