#!/usr/bin/env bash
# Plots the sparse ordering benchmark (bench/sparse/sparse_orderings.cpp) with gnuplot:
# factor nonzeros and refactorisation time against n, log-log, one column per matrix family
# (2D grids, 3D grids, truss girders), one line per solver/ordering. Also prints the fitted
# growth exponents (least squares of log y on log n) of every contender on the truss family.
#   scripts/plot_sparse.sh [CSV] [PNG]
# defaults: docs/data/sparse_orderings.csv docs/sparse_orderings.png
set -euo pipefail
csv=${1:-docs/data/sparse_orderings.csv}
png=${2:-docs/sparse_orderings.png}
command -v gnuplot >/dev/null || { echo "gnuplot not found" >&2; exit 1; }
[ -r "$csv" ] || { echo "cannot read $csv" >&2; exit 1; }

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# One data file per family and contender: n nnz_factor refactor_s
awk -F, -v dir="$tmp" 'NR > 1 {
  fam = $1; sub(/_.*/, "", fam)
  key = $4 "-" $5
  f = dir "/" fam "__" key ".dat"
  print $2, $6, ($9 == "" ? "NaN" : $9) >> f
  seen[fam "__" key] = 1
}' "$csv"

echo "Fitted exponents on the truss family (y ~ n^p):"
for f in "$tmp"/truss__*.dat; do
  [ -e "$f" ] || continue
  name=$(basename "$f" .dat); name=${name#truss__}
  awk -v name="$name" '
    function fit(col,   i, sx, sy, sxx, sxy, k) {
      k = 0; sx = sy = sxx = sxy = 0
      for (i = 1; i <= m; ++i) if (v[i, col] != "NaN" && v[i, col] > 0) {
        x = log(v[i, 1]); y = log(v[i, col]); ++k; sx += x; sy += y; sxx += x * x; sxy += x * y }
      if (k < 2) return "n/a"
      return sprintf("%.2f", (k * sxy - sx * sy) / (k * sxx - sx * sx))
    }
    { ++m; v[m, 1] = $1; v[m, 2] = $2; v[m, 3] = $3 }
    END { printf "  %-28s fill exponent %s, refactor exponent %s (%d sizes)\n", name, fit(2), fit(3), m }' "$f"
done

plot_cmds() {  # $1 family, $2 column (2 fill, 3 refactor)
  local first=1 f name
  for f in "$tmp"/"$1"__*.dat; do
    [ -e "$f" ] || continue
    name=$(basename "$f" .dat); name=${name#"$1"__}
    sort -n -o "$f" "$f"
    if [ $first -eq 1 ]; then printf 'plot '; first=0; else printf ', '; fi
    printf "'%s' using 1:%s with linespoints title '%s'" "$f" "$2" "$name"
  done
  echo
}

{
  echo "set terminal pngcairo size 1800,1000 font ',10' noenhanced"
  echo "set output '$png'"
  echo "set logscale xy"
  echo "set grid"
  echo "set key top left font ',8'"
  echo "set multiplot layout 2,3 title 'pradis sparse LU: orderings vs AMD / KLU / Eigen SparseLU'"
  for fam in grid2d grid3d truss; do
    echo "set title '$fam: factor nonzeros'"
    echo "set xlabel 'n'"; echo "set ylabel 'nnz(L+U)'"
    plot_cmds "$fam" 2
  done
  for fam in grid2d grid3d truss; do
    echo "set title '$fam: refactorisation time'"
    echo "set xlabel 'n'"; echo "set ylabel 'CPU s'"
    plot_cmds "$fam" 3
  done
  echo "unset multiplot"
} > "$tmp/plot.gp"
gnuplot "$tmp/plot.gp"
echo "wrote $png"
