#!/bin/sh
# Fuzzes the model-language parser and builder (fuzz/fuzz_parser.cpp) with
# libFuzzer for a given time, starting from the committed corpus fuzz/corpus/.
#
#   scripts/fuzz.sh [SECONDS] [BUILD_DIR]      (default 60 s, /tmp/pradis-fuzz)
#
# Needs clang with libFuzzer and Eigen 3.4; installs the Debian packages clang and
# libeigen3-dev itself when they are missing.
# New interesting inputs are kept in BUILD_DIR/corpus (copy the good ones to
# fuzz/corpus/ by hand). A crash is written to fuzz/regressions/crash-<hash>;
# commit it: tests/lang/test_fuzz_regressions.cpp replays every file there.
# Exit status: 0 if no crash was found.
set -eu
seconds=${1:-60}
build=${2:-/tmp/pradis-fuzz}
root=$(cd "$(dirname "$0")/.." && pwd)
cxx=${CXX_FUZZ:-clang++}
eigen=${EIGEN_INCLUDE:-/usr/include/eigen3}
if ! command -v "$cxx" >/dev/null 2>&1 || [ ! -d "$eigen" ]; then
  echo "fuzz.sh: installing clang and Eigen (Debian packages)"
  apt-get update && apt-get install -y clang libeigen3-dev
fi
mkdir -p "$build/corpus" "$root/fuzz/regressions"
echo "fuzz.sh: building $build/fuzz_parser with $cxx"
"$cxx" -std=c++20 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
  -I"$root/include" -I"$eigen" "$root/fuzz/fuzz_parser.cpp" -o "$build/fuzz_parser"
echo "fuzz.sh: fuzzing for $seconds s"
"$build/fuzz_parser" -max_total_time="$seconds" -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
  -artifact_prefix="$root/fuzz/regressions/" -print_final_stats=1 \
  "$build/corpus" "$root/fuzz/corpus"
