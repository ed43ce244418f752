#!/usr/bin/env bash
# Main job: installs what it needs (Debian 12, as root; idempotent), builds the
# pradis examples and simulates the default model, the two-body system of the
# PRADIS element developer's manual (section 3.6.9), writing out/two_bodies.csv
# and out/two_bodies.png.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
  apt-get update
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
    ca-certificates cmake g++ make libeigen3-dev gnuplot-nox
fi
cmake -S . -B build/example -DCMAKE_BUILD_TYPE=Release \
  -DPRADIS_BUILD_TESTS=OFF -DPRADIS_BUILD_BENCH=OFF -DPRADIS_BUILD_EXAMPLES=ON
cmake --build build/example -j"$(nproc)" --target two_bodies
./build/example/examples/two_bodies out
