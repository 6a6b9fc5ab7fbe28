#!/usr/bin/env bash
# Builds the Python package as a wheel that installs without a Rust toolchain (issue 32):
# stable ABI (abi3, one wheel for every CPython >= 3.9), manylinux_2_28 (glibc 2.28 and
# later: RHEL 8, Debian 10, Ubuntu 18.10 and newer), debug info stripped. Zig (the PyPI
# package `ziglang`) links against glibc 2.28's symbols, so no manylinux container is needed.
#
#   bash python/build-wheel.sh [OUT]          # OUT: default target/wheels
#   pip install target/wheels/curvenet-*-cp39-abi3-manylinux_2_28_x86_64.whl
#
# Another architecture: add `--target aarch64-unknown-linux-gnu` below (after
# `rustup target add aarch64-unknown-linux-gnu`). macOS and Windows: `maturin build --release
# --strip -m python/Cargo.toml` on that system gives its abi3 wheel (no zig needed).
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-target/wheels}"
python3 -m pip install --quiet --disable-pip-version-check "maturin>=1.9,<2" "ziglang>=0.13"
python3 -m maturin build --release --strip --zig --compatibility manylinux_2_28 \
    -m python/Cargo.toml -o "$out"
