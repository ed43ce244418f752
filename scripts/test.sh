#!/usr/bin/env bash
# Builds everything (library tests, examples, benchmarks) and runs the whole
# test suite with CTest. Installs what it needs (Debian 12, as root; idempotent).
# Usage: scripts/test.sh [preset]   (preset: dev (default) or asan-ubsan)
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-dev}"
if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
  apt-get update
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
    ca-certificates cmake g++ clang make libeigen3-dev doctest-dev libbenchmark-dev gnuplot-nox \
    libsuitesparse-dev libsundials-dev libboost-dev libsimbody-dev
fi
cmake --preset "$preset"
cmake --build --preset "$preset" -j"$(nproc)"
ctest --preset "$preset"
