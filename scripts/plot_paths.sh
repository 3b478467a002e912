#!/usr/bin/env bash
# Draws the paper's Figures 2-6 (docs/img/paths_<case>.png: p2 horizontal, p1 vertical, one curve per grid
# vertex) and the ODE convergence chart (docs/img/convergence.png) from `clipblur paths`.
# Usage: scripts/plot_paths.sh [path/to/clipblur]   (default build/clipblur)
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-build/clipblur}
out=docs/img
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# gnuplot-nox may lack cairo; fall back to the libgd png terminal.
if gnuplot -e 'set terminal' 2>&1 | grep -q pngcairo; then term="pngcairo size 560,560 font ',10'"; else term="png size 560,560"; fi

declare -A titles=(
  [spin]="Figure 2: six degree spin of the camera"
  [pan]="Figure 3: six degree pan of the camera"
  [spin_pan]="Figure 4: six degree spin and pan"
  [recede]="Figure 5: vertex receding from range 10 to 20"
  [recede_spin_pan]="Figure 6: receding vertex, spin and pan"
)

for c in spin pan spin_pan recede recede_spin_pan; do
  # gnuplot wants one blank line between curves: break the CSV at each new (x, y) vertex.
  "$bin" paths --case "$c" --samples 20 |
    awk -F, 'NR > 1 { key = $2 "," $3; if (NR > 2 && key != prev) print ""; prev = key; print $6, $5 }' \
      > "$tmp/$c.dat"
  gnuplot <<GP
set terminal $term
set output "$out/paths_$c.png"
set title "${titles[$c]}"
set xlabel "p2 (image right)"
set ylabel "p1 (image up)"
set size ratio -1
set key off
set grid
plot "$tmp/$c.dat" using 1:2 with lines lw 1.5 lc rgb "#1f5fa8", \
     "$tmp/$c.dat" every 20 using 1:2 with points pt 7 ps 0.4 lc rgb "#b03030"
GP
done

"$bin" paths --convergence --case recede_spin_pan > "$tmp/conv.csv"
awk -F, '$2 == "euler" { print $3, $4 }' "$tmp/conv.csv" > "$tmp/euler.dat"
awk -F, '$2 == "rk4" { print $3, $4 }' "$tmp/conv.csv" > "$tmp/rk4.dat"
gnuplot <<GP
set terminal $term
set output "$out/convergence.png"
set title "Error at f = 1 vs step count (recede/spin/pan, worst grid vertex)"
set logscale xy
set format y "10^{%L}"
set xlabel "steps per frame"
set ylabel "max |p_{ODE}(1) - p_{exact}(1)|"
set grid
set key top right
plot "$tmp/euler.dat" using 1:2 with linespoints pt 7 title "explicit Euler", \
     "$tmp/rk4.dat" using 1:2 with linespoints pt 5 title "RK4", \
     [1:4096] 1.0/x with lines dt 2 lc rgb "gray" title "slope -1", \
     [1:4096] 0.03/x**4 with lines dt 3 lc rgb "gray" title "slope -4"
GP
ls -l "$out"/paths_*.png "$out"/convergence.png
