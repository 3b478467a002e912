#!/usr/bin/env bash
# docs/img/design_shutter_segments.png: how `segments: auto` cuts a shutter [0, 1], for a hand-written
# case: the camera turns 30 degrees (2 segments of 15 degrees each, shutterSegments), and the
# hidden-surface probe (hiddenTiles: probe times 1/2, 1/4, 3/4 into each segment) finds a surface
# point hidden at both ends of [0, 1/2] at 1/4 and nothing in [1/2, 1]. The segments stay [0, 1/2] and
# [1/2, 1] with weights 1/2; the three fragment sets are built at 0, 1/2, 1 (neighbours share the set
# where they meet), and the sets at 0 and 1/2 keep every layer in the tiles near the hidden point.
set -euo pipefail
source "$(dirname "$0")/terminal.sh"
gnuplot <<GP
set terminal $(png_terminal 680 240)
set output "$out/design_shutter_segments.png"
set title "segments: auto; the camera turns 30 degrees while two objects cross"
\$probe_hit << END
0.25 1
END
\$probe_clear << END
0.125 1
0.375 1
0.625 1
0.75 1
0.875 1
END
\$sets << END
1 0
END
\$deep_sets << END
0 0
0.5 0
END
set xrange [-0.02:1.02]
set yrange [-0.6:2.6]
set xtics ("open 0" 0, "1/4" 0.25, "1/2" 0.5, "close 1" 1)
set ytics ("fragment sets" 0, "probe" 1, "15 deg turn rule" 2) nomirror
set grid xtics
set key outside bottom center horizontal maxrows 1 width 1
set object 1 rect from 0,1.8 to 0.5,2.2 fs solid 0.25 border lc rgb "#3a74c4" fc rgb "#3a74c4"
set object 2 rect from 0.5,1.8 to 1,2.2 fs solid 0.25 border lc rgb "#3a74c4" fc rgb "#3a74c4"
set label 1 "weight 1/2" at 0.25,2.42 center
set label 2 "weight 1/2" at 0.75,2.42 center
set label 3 "hidden at both ends: both sets keep every layer near it" at 0.25,0.45 center tc rgb "#b03030"
plot \$probe_hit with points pt 2 ps 2 lw 2 lc rgb "#b03030" title "probe: hidden at both ends", \
     \$probe_clear with points pt 6 ps 1.2 lc rgb "#2f7d32" title "probe: nothing hidden", \
     \$sets with points pt 5 ps 1.3 lc rgb "black" title "fragment set", \
     \$deep_sets with points pt 5 ps 1.6 lc rgb "#b03030" title "fragment set with deep tiles"
GP
