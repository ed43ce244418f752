#!/usr/bin/env bash
# Work-precision plots: one log-log PNG of error against CPU time per problem,
# one line per solver/method, from the CSV written by bench/work_precision.
# Usage: scripts/plot_work_precision.sh [CSV] [OUTDIR]
#   defaults: docs/data/work_precision.csv -> docs/work_precision_<problem>.png
# Needs gnuplot (Debian: gnuplot-nox).
set -euo pipefail
cd "$(dirname "$0")/.."
csv="${1:-docs/data/work_precision.csv}"
outdir="${2:-docs}"
[ -f "$csv" ] || { echo "no $csv: run the work_precision benchmark first" >&2; exit 1; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
# Split into one data file per problem and series (solver method), in
# sweep order; failed or useless points (error >= 1e300 or not positive) are dropped.
awk -F, -v dir="$tmp" 'NR > 1 && $5 > 0 && $5 < 1e300 && $6 > 0 {
  series = $2 "_" $3; gsub(/[^A-Za-z0-9._-]/, "_", series)
  f = dir "/" $1 "__" series ".dat"
  print $6, $5 > f
}' "$csv"
palette=('#1f77b4' '#ff7f0e' '#2ca02c' '#d62728' '#9467bd' '#e377c2' '#7f7f7f' '#bcbd22' '#17becf'
  '#000000' '#aec7e8' '#ffbb78' '#98df8a' '#ff9896' '#c5b0d5' '#f7b6d2' '#c49c94' '#dbdb8d' '#9edae5' '#393b79')
for problem in $(awk -F, 'NR > 1 { print $1 }' "$csv" | sort -u); do
  plots=()
  n=0
  for f in "$tmp/$problem"__*.dat; do
    [ -e "$f" ] || continue
    # points stay in sweep order (loosest setting first), so a line follows its sweep
    label="$(basename "$f" .dat)"; label="${label#${problem}__}"; label="${label//_/ }"
    # one colour per series of a plot (gnuplot's own cycle has 8, topx has 17 series)
    colour="${palette[$((n % ${#palette[@]}))]}"; n=$((n + 1))
    case "$label" in
      "pradis BDF") style="lw 3 lc rgb '#8c564b'";;
      pradis*) style="lw 2 lc rgb '$colour'";;
      *) style="lw 1 dt 2 lc rgb '$colour'";;
    esac
    plots+=("'$f' using 1:2 with linespoints $style pt 7 ps 0.6 title '$label'")
  done
  [ ${#plots[@]} -gt 0 ] || continue
  joined="$(printf '%s, ' "${plots[@]}")"; joined="${joined%, }"
  gnuplot <<GP
set terminal pngcairo size 900,650 enhanced font ',10'
set output '$outdir/work_precision_$problem.png'
set logscale xy
set format x '10^{%T}'
set format y '10^{%T}'
set xlabel 'CPU time [s] (min of 3 after warm-up)'
set ylabel 'relative error at the final time'
set title 'Work-precision: $problem'
set key outside right top box
set grid
plot $joined
GP
  echo "wrote $outdir/work_precision_$problem.png"
done
