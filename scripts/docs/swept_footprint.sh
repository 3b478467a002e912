#!/usr/bin/env bash
# docs/img/design_swept_footprint.png: one fragment swept over one interval [t - h/2, t + h/2], for
# hand-written data. The surface point under the fragment's centroid is at raster (1.2, 3.3) at the
# interval's start, (3.0, 1.9) at t and (5.4, 2.4) at its end (y down); its path is the parabola through
# those three (as SweepPath::through, here with depth constant, so homogeneous and raster agree). The
# fragment, a triangle about a pixel wide, is stretched along x from 1.0 at the start to 1.4 at the
# end (a surface turning towards the camera) and placed at positions = 5 equally spaced times, the
# midpoints of five equal parts of the interval. Each placement adds 1/5 of its exact pixel coverage.
set -euo pipefail
source "$(dirname "$0")/terminal.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# P(s) = a + b s + c s^2 through s = 0, 1/2, 1: b = 4 m - 3 p0 - p1, c = 2 (p0 + p1) - 4 m.
awk -v positions=5 'BEGIN {
  x0 = 1.2; y0 = 3.3; xm = 3.0; ym = 1.9; x1 = 5.4; y1 = 2.4
  bx = 4*xm - 3*x0 - x1; cx = 2*(x0 + x1) - 4*xm
  by = 4*ym - 3*y0 - y1; cy = 2*(y0 + y1) - 4*ym
  # The fragment relative to its centroid (it sums to zero).
  n = split("-0.45 0.5 -0.05", fx, " "); split("0.35 0.15 -0.5", fy, " ")
  for (i = 0; i <= 100; ++i) { s = i / 100; printf "%g %g\n", x0 + bx*s + cx*s*s, y0 + by*s + cy*s*s > "'"$tmp"'/path.dat" }
  printf "%g %g\n%g %g\n%g %g\n", x0, y0, xm, ym, x1, y1 > "'"$tmp"'/through.dat"
  for (k = 0; k < positions; ++k) {
    s = (k + 0.5) / positions
    cxp = x0 + bx*s + cx*s*s; cyp = y0 + by*s + cy*s*s
    stretch = 1.0 + 0.4 * s
    for (i = 1; i <= 4; ++i) { j = (i - 1) % 3 + 1; printf "%g %g\n", cxp + stretch*fx[j], cyp + fy[j] > "'"$tmp"'/positions.dat" }
    printf "\n\n" > "'"$tmp"'/positions.dat"
    printf "%g %g %d\n", cxp, cyp, k > "'"$tmp"'/centres.dat"
  }
}'
gnuplot <<GP
set terminal $(png_terminal 640 360)
set output "$out/design_swept_footprint.png"
set title "A fragment swept over one interval: 5 positions along the parabola through 3 exact points"
set size ratio -1
set xrange [0:7]
set yrange [5.2:-0.6]
set xtics 1 format ""
set xlabel "grid: pixels"
set ytics 1 format ""
set grid xtics ytics lc rgb "#999999" lt 1
set key top left box opaque
set style fill transparent solid 0.3 border lc rgb "#1f5fa8"
plot for [k=0:4] "$tmp/positions.dat" index k with filledcurves closed lc rgb "#3a74c4" notitle, \
     "$tmp/path.dat" with lines lw 1.5 lc rgb "#b03030" title "path of the centroid's surface point", \
     "$tmp/through.dat" with points pt 7 ps 1.2 lc rgb "#b03030" title "exact at start, t, end", \
     "$tmp/centres.dat" with points pt 1 ps 1 lc rgb "black" title "positions (equal times)"
GP
