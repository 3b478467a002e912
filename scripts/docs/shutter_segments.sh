#!/usr/bin/env bash
# docs/img/design_shutter_segments.png: how `segments: auto` cuts a shutter [0, 1], for a hand-written
# case: the camera turns 30 degrees (2 segments of 15 degrees each, shutterSegments), and the
# hidden-surface probe (hidesSomethingAtBothEnds: probe times 1/2, 1/4, 3/4 into a segment, stopping at
# the first that finds a point hidden at both ends) finds one in [0, 1/2] at its middle, none in either
# half of it, and none in [1/2, 1]. splitWhereHidden bisects [0, 1/2]: the segments are [0, 1/4],
# [1/4, 1/2], [1/2, 1] with weights 1/4, 1/4, 1/2, and the four fragment sets are built at 0, 1/4, 1/2, 1
# (neighbours share the set where they meet).
set -euo pipefail
source "$(dirname "$0")/terminal.sh"
gnuplot <<GP
set terminal $(png_terminal 680 280)
set output "$out/design_shutter_segments.png"
set title "segments: auto; the camera turns 30 degrees while two objects cross"
\$rotation << END
0 3 0.5
0.5 3 0.5
END
\$probe_hit << END
0.25 2
END
\$probe_clear << END
0.125 1
0.0625 1
0.1875 1
0.375 1
0.3125 1
0.4375 1
0.75 2
0.625 2
0.875 2
END
\$sets << END
0 0
0.25 0
0.5 0
1 0
END
set xrange [-0.02:1.02]
set yrange [-0.6:3.6]
set xtics ("open 0" 0, "1/4" 0.25, "1/2" 0.5, "close 1" 1)
set ytics ("fragment sets" 0, "probe, 2nd pass" 1, "probe, 1st pass" 2, "15 deg turn rule" 3) nomirror
set grid xtics
set key outside bottom center horizontal maxrows 1 width 1
# Segments per row: rotation rule, then after the probe.
set object 1 rect from 0,2.8 to 0.5,3.2 fs solid 0.25 border lc rgb "#3a74c4" fc rgb "#3a74c4"
set object 2 rect from 0.5,2.8 to 1,3.2 fs solid 0.25 border lc rgb "#3a74c4" fc rgb "#3a74c4"
set object 3 rect from 0,0.8 to 0.25,1.2 fs solid 0.25 border lc rgb "#3a74c4" fc rgb "#3a74c4"
set object 4 rect from 0.25,0.8 to 0.5,1.2 fs solid 0.25 border lc rgb "#3a74c4" fc rgb "#3a74c4"
set object 5 rect from 0.5,1.8 to 1,2.2 fs solid 0.25 border lc rgb "#3a74c4" fc rgb "#3a74c4"
set object 6 rect from 0,1.8 to 0.5,2.2 fs solid 0.08 border lc rgb "#b03030" fc rgb "#b03030"
set label 1 "weight 1/4" at 0.125,0.55 center
set label 2 "weight 1/4" at 0.375,0.55 center
set label 3 "weight 1/2" at 0.75,1.55 center
set label 4 "hidden at both ends: bisect" at 0.25,2.42 center tc rgb "#b03030"
plot \$probe_hit with points pt 2 ps 2 lw 2 lc rgb "#b03030" title "probe: hidden at both ends", \
     \$probe_clear with points pt 6 ps 1.2 lc rgb "#2f7d32" title "probe: nothing hidden", \
     \$sets with points pt 5 ps 1.3 lc rgb "black" title "fragment set"
GP
