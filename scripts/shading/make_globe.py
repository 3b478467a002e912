#!/usr/bin/env python3
"""Writes configs/shading/globe.obj and globe.mtl: a UV sphere of radius 1 with per-vertex normals (`vn`)
and texture coordinates (`vt`, longitude right, latitude up), faces outward, material `globe` with
map_Kd globe.png (made by: oiiotool --pattern checker:width=4:height=4:color1=0.95,0.6,0.15:color2=0.1,0.3,0.75
256x128 3 --pattern fill:left=1,1,1:right=0.35,0.35,0.35 256x128 3 --mul -d uint8 -o globe.png).

    scripts/shading/make_globe.py [--lon 32 --lat 16]
"""

import argparse
import math
from pathlib import Path

OUT = Path(__file__).resolve().parents[2] / "configs" / "shading"


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--lon", type=int, default=32)
    parser.add_argument("--lat", type=int, default=16)
    args = parser.parse_args()
    rows, cols = args.lat, args.lon
    lines = ["# UV sphere, radius 1: scripts/shading/make_globe.py", "mtllib globe.mtl", "usemtl globe"]
    index = {}
    for i in range(rows + 1):
        theta = math.pi * i / rows
        for j in range(cols + 1):
            phi = 2.0 * math.pi * j / cols
            p = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            index[(i, j)] = len(index) + 1
            lines.append("v %.6f %.6f %.6f" % p)
            lines.append("vn %.6f %.6f %.6f" % p)
            lines.append("vt %.6f %.6f" % (j / cols, 1.0 - i / rows))
    for i in range(rows):
        for j in range(cols):
            a, b, c, d = index[(i, j)], index[(i + 1, j)], index[(i + 1, j + 1)], index[(i, j + 1)]
            corners = [a, b, c, d]
            if i == 0:
                corners = [a, b, c]  # a and d are both the north pole
            elif i == rows - 1:
                corners = [a, b, d]  # b and c are both the south pole
            lines.append("f " + " ".join("%d/%d/%d" % (k, k, k) for k in corners))
    (OUT / "globe.obj").write_text("\n".join(lines) + "\n")
    (OUT / "globe.mtl").write_text("# scripts/shading/make_globe.py\nnewmtl globe\nKd 1 1 1\nmap_Kd globe.png\n")


if __name__ == "__main__":
    main()
