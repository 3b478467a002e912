#!/usr/bin/env bash
# docs/img/design_tiles_spills.png: what one moving tile re-clips and where its swept fragments land,
# for hand-written numbers put through sweepInterval (renderer/clipped/clipped_renderer.cpp). Film 24x16
# px, tile_size 8 (3x2 tiles); the tile [8,16)x[0,8) lies on the film's top edge; its plan has
# max_sweep_pixels / n = 3 px, so reach = 2 * 3 + 1 = 7 and apron = ceil(7 / 2) + 1 = 5 px. Its resolve
# box is the tile grown past the film's top edge by the apron, [8,16)x[-5,8) (surfaces above the film
# sweep in), and the pixels its sweep can reach are resolve grown by the apron, [3,21)x[-10,13). Two
# fragments, hand-placed: A at [14.3,15.6]x[3.2,4.5] moving 3 px right, whose footprint covers pixels
# x 14-18, y 3-4 (x >= 16: spills, the next tile's pixels, added after all tiles in tile order); B above
# the film at [10.2,11.5]x[-3.4,-2.1] moving 3 px down, into the tile's own pixels at y 0.
set -euo pipefail
source "$(dirname "$0")/terminal.sh"
gnuplot <<GP
set terminal $(png_terminal 560 620)
set output "$out/design_tiles_spills.png"
set title "One moving tile of a 24x16 film (8 px tiles)"
set size ratio -1
set xrange [-1:25]
set yrange [17:-11]
set xtics 8
set ytics 8
set mxtics 8
set mytics 8
set grid mxtics mytics lc rgb "#e4e4e4" lw 0.5, lc rgb "#e4e4e4" lw 0.5
set key outside bottom center vertical Left reverse box spacing 1.1
# Film and tiles (the grid's major lines are the tile borders).
set object 1 rect from 0,0 to 24,16 fs empty border lc rgb "black" lw 2 back
set arrow 10 from 8,0 to 8,16 nohead lc rgb "#555555" lw 1 back
set arrow 11 from 16,0 to 16,16 nohead lc rgb "#555555" lw 1 back
set arrow 12 from 0,8 to 24,8 nohead lc rgb "#555555" lw 1 back
# The tile's reach box, resolve box and the tile itself.
set object 2 rect from 3,-10 to 21,13 fs transparent solid 0.10 border lc rgb "#7a7a00" lw 1.5 back
set object 3 rect from 8,-5 to 16,8 fs transparent solid 0.18 border lc rgb "#3a74c4" lw 1.5 back
set object 4 rect from 8,0 to 16,8 fs transparent solid 0.30 noborder fc rgb "#3a74c4" back
# Fragment A's footprint: its own pixels and the spilled ones.
set object 5 rect from 14,3 to 16,5 fs solid 0.6 noborder fc rgb "#3a74c4" front
set object 6 rect from 16,3 to 19,5 fs pattern 4 border lc rgb "#b03030" fc rgb "#b03030" front
# Fragment B sweeping in across the film's top edge.
set object 7 rect from 10,0 to 12,1 fs solid 0.6 noborder fc rgb "#3a74c4" front
set object 8 rect from 14.3,3.2 to 15.6,4.5 fs empty border lc rgb "black" lw 1.5 front
set object 9 rect from 10.2,-3.4 to 11.5,-2.1 fs empty border lc rgb "black" lw 1.5 front
set arrow 1 from 15.6,3.85 to 18.6,3.85 lw 1.5 front
set arrow 2 from 10.85,-2.1 to 10.85,0.9 lw 1.5 front
set label 1 "film" at 0.3,15.3 front
set label 2 "A" at 13.2,3.6 front
set label 3 "B" at 9.2,-2.7 front
plot NaN with boxes fs solid 0.3 lc rgb "#3a74c4" title "the tile's own pixels", \
     NaN with boxes fs transparent solid 0.18 lc rgb "#3a74c4" title "resolve: re-clipped (grown past the film edge)", \
     NaN with boxes fs transparent solid 0.10 lc rgb "#7a7a00" title "box: what its sweep can reach", \
     NaN with boxes fs pattern 4 lc rgb "#b03030" title "spilled pixels (another tile's)", \
     NaN with lines lw 1.5 lc rgb "black" title "fragment and its motion"
GP
