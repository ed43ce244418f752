#!/bin/sh
# Fuzzes pradis with libFuzzer for a given time. Two targets:
#   parser  the model-language parser and builder (fuzz/fuzz_parser.cpp), from the
#           committed corpus fuzz/corpus/; crashes go to fuzz/regressions/;
#   run     model files built and run, under a CPU budget per input
#           (fuzz/fuzz_run.cpp), from the example models examples/models/*.prd;
#           crashes go to fuzz/regressions-run/.
#
#   scripts/fuzz.sh [SECONDS] [BUILD_DIR] [TARGET]
#   (defaults: 60 s, /tmp/pradis-fuzz or for run /tmp/pradis-fuzz-run, parser)
#
# Needs clang with libFuzzer and Eigen 3.4; installs the Debian packages clang and
# libeigen3-dev itself when they are missing.
# New interesting inputs are kept in BUILD_DIR/corpus (copy the good ones to
# fuzz/corpus/ by hand). A crash is written to the target's regressions folder.
# parser: commit it; tests/lang/test_fuzz_regressions.cpp replays every file in
# fuzz/regressions/. run: replay it with `BUILD_DIR/fuzz_run FILE`, fix the
# cause and add the model, cut down, to the tests of what it broke.
# Exit status: 0 if no crash was found.
set -eu
seconds=${1:-60}
target=${3:-parser}
if [ "$target" = run ]; then build=${2:-/tmp/pradis-fuzz-run}; else build=${2:-/tmp/pradis-fuzz}; fi
root=$(cd "$(dirname "$0")/.." && pwd)
cxx=${CXX_FUZZ:-clang++}
eigen=${EIGEN_INCLUDE:-/usr/include/eigen3}
if ! command -v "$cxx" >/dev/null 2>&1 || [ ! -d "$eigen" ]; then
  echo "fuzz.sh: installing clang and Eigen (Debian packages)"
  apt-get update && apt-get install -y clang libeigen3-dev
fi
case "$target" in
  parser) source=fuzz_parser.cpp regressions=regressions seeds="$root/fuzz/corpus" ;;
  run) source=fuzz_run.cpp regressions=regressions-run seeds="$root/examples/models" ;;
  *) echo "fuzz.sh: unknown target '$target' (parser or run)" >&2; exit 2 ;;
esac
mkdir -p "$build/corpus" "$root/fuzz/$regressions"
binary="$build/${source%.cpp}"
echo "fuzz.sh: building $binary with $cxx"
"$cxx" -std=c++20 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
  -I"$root/include" -I"$eigen" "$root/fuzz/$source" -o "$binary"
echo "fuzz.sh: fuzzing $target for $seconds s"
"$binary" -max_total_time="$seconds" -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
  -artifact_prefix="$root/fuzz/$regressions/" -print_final_stats=1 \
  "$build/corpus" "$seeds"
