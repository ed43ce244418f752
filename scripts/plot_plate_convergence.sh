#!/usr/bin/env bash
# Plots the mesh convergence of TRIPL on the square plate (docs/plates.md) with gnuplot:
# |relative error| of the centre deflection and of the first frequency against the
# number of cells per side, log-log, with a slope -2 (O(h^2)) guide.
#   scripts/plot_plate_convergence.sh [CSV] [PNG]
# defaults: docs/data/plate_convergence.csv docs/plate_convergence.png
set -euo pipefail
csv=${1:-docs/data/plate_convergence.csv}
png=${2:-docs/plate_convergence.png}
command -v gnuplot >/dev/null || { echo "gnuplot not found" >&2; exit 1; }
[ -r "$csv" ] || { echo "cannot read $csv" >&2; exit 1; }
gnuplot <<GP
set terminal pngcairo size 800,560 font ",11"
set output "$png"
set datafile separator ","
set datafile commentschars "#n"
set logscale xy
set xtics (4, 8, 16, 32)
set xlabel "cells per side n"
set ylabel "|relative error|"
set title "TRIPL, square plate: convergence with mesh refinement"
set key bottom left
set grid
plot "$csv" using 1:(abs(\$2)) with linespoints lw 2 title "deflection, simply supported", \
     "$csv" using 1:(abs(\$3)) with linespoints lw 2 title "deflection, clamped", \
     "$csv" using 1:(abs(\$4)) with linespoints lw 2 title "first frequency, simply supported", \
     "$csv" using 1:(abs(\$5)) with linespoints lw 2 title "first frequency, clamped", \
     2.0*(4.0/x)**2 with lines dt 2 lc "black" title "slope -2 (O(h^2))"
GP
echo "wrote $png"
