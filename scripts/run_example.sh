#!/usr/bin/env bash
# Main job: installs what it needs (Debian 12, as root; idempotent), builds the
# `pradis` command and runs its built-in example model, the two-body system of
# the PRADIS element developer's manual (section 3.6.9), writing out/two_bodies.csv
# and the plot out/two_bodies.*.png. Extra arguments go to `pradis run`
# (e.g. a model file: scripts/run_example.sh examples/models/simple_pendulum.prd).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
  apt-get update
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
    ca-certificates cmake g++ make libeigen3-dev gnuplot-nox
fi
cmake -S . -B build/example -DCMAKE_BUILD_TYPE=Release \
  -DPRADIS_BUILD_TESTS=OFF -DPRADIS_BUILD_BENCH=OFF -DPRADIS_BUILD_EXAMPLES=ON -DPRADIS_BUILD_APPS=ON
cmake --build build/example -j"$(nproc)" --target pradis_cli
./build/example/apps/pradis run "$@" -o out
