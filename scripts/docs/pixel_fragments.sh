#!/usr/bin/env bash
# docs/img/design_pixel_fragments.png: one pixel's clipped fragment set at shutter open (f = 0), at
# shutter close (f = 1) and re-clipped at f = 1/2, for hand-written data: a still wall behind the whole
# pixel and a front triangle (-0.5,-0.5) (1.5,-0.5) (-0.5,1.5) that slides 0.6 px right over the shutter.
# Raster coordinates, pixel [0,1)^2, y down. The pieces below are that geometry clipped by hand; areas:
# open front 0.5, wall 0.5; close front 0.82, wall 0.1 + 0.08. The third panel shows regions, not pieces:
# at f = 1/2 both sets' fragments (with those of neighbouring pixels, which move in) are propagated and
# re-clipped; the front (x + y < 1.3) is covered by both frames' copies (mixed 1 - f, f), the wall's
# visible corner by the open set's wall (x + y >= 1) everywhere and by the close set's (x + y >= 1.6)
# only in its tip; the resolver cuts these regions further along the fragments' edges.
set -euo pipefail
source "$(dirname "$0")/terminal.sh"
gnuplot <<GP
set terminal $(png_terminal 840 330)
set output "$out/design_pixel_fragments.png"
\$tri0 << END
-0.5 -0.5
1.5 -0.5
-0.5 1.5
-0.5 -0.5
END
\$tri1 << END
0.1 -0.5
2.1 -0.5
0.1 1.5
0.1 -0.5
END
\$trih << END
-0.2 -0.5
1.8 -0.5
-0.2 1.5
-0.2 -0.5
END
\$open_front << END
0 0
1 0
0 1
END
\$open_wall << END
1 0
1 1
0 1
END
\$close_front << END
0.1 0
1 0
1 0.6
0.6 1
0.1 1
END
\$close_wall << END
0 0
0.1 0
0.1 1
0 1


1 0.6
1 1
0.6 1
END
\$mid_front << END
0 0
1 0
1 0.3
0.3 1
0 1
END
\$mid_wall_open_only << END
1 0.3
1 0.6
0.6 1
0.3 1
END
\$mid_wall_both << END
1 0.6
1 1
0.6 1
END
\$pixel << END
0 0
1 0
1 1
0 1
0 0
END
set size ratio -1
set xrange [-0.3:1.3]
set yrange [1.3:-0.3]
unset key
set xtics 0.5
set ytics 0.5
set grid front
set style fill solid 0.55 border lc rgb "black"
set multiplot layout 1,3
set title "shutter open (f = 0): 2 pieces"
set label 1 "front 0.5" at 0.12,0.3 front
set label 2 "wall 0.5" at 0.55,0.8 front
plot \$open_front with filledcurves closed lc rgb "#3a74c4", \
     \$open_wall with filledcurves closed lc rgb "#c8a46a", \
     \$tri0 with lines dt 2 lc rgb "#3a74c4", \$pixel with lines lw 2 lc rgb "black"
set title "shutter close (f = 1): 3 pieces"
set label 1 "front 0.82" at 0.3,0.4 front
set label 2 "wall" at -0.25,1.2 front
set arrow 1 from -0.1,1.13 to 0.05,0.9 lw 1 front
set label 3 "wall" at 1.02,1.2 front
set arrow 2 from 1.08,1.12 to 0.92,0.9 lw 1 front
plot \$close_front with filledcurves closed lc rgb "#3a74c4", \
     \$close_wall with filledcurves closed lc rgb "#c8a46a", \
     \$tri1 with lines dt 2 lc rgb "#3a74c4", \$pixel with lines lw 2 lc rgb "black"
set title "re-clip at f = 1/2: who covers what"
unset arrow
set label 1 "front: open and\\nclose copies mixed" at 0.05,0.3 front
set label 2 "wall: open set only" at -0.25,1.22 front
set arrow 1 from 0.3,1.14 to 0.6,0.85 lw 1 front
set label 3 "wall: both" at 0.95,-0.12 front
set arrow 2 from 1.1,-0.05 to 0.92,0.9 lw 1 front
plot \$mid_front with filledcurves closed lc rgb "#3a74c4", \
     \$mid_wall_open_only with filledcurves closed lc rgb "#e3cfa8", \
     \$mid_wall_both with filledcurves closed lc rgb "#c8a46a", \
     \$trih with lines dt 2 lc rgb "#3a74c4", \$pixel with lines lw 2 lc rgb "black"
unset multiplot
GP
