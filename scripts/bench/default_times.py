#!/usr/bin/env python3
"""Default clipped renders of bench scenes by several binaries, taken in turns (binary A, B, A, B, ...) so
that the machine's drift falls on all of them alike: the median whole-process wall clock of --repeat
renders per binary, and the noise-free counts of the last (re-clips or point subframes summed over tiles,
sweep positions, and segments by sweep / by point subframes).

    scripts/bench/default_times.py --clipblur /tmp/before/clipblur,build/clipblur --scenes coincident,many/street
"""

import argparse
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import benchlib  # noqa: E402
from error_estimate import scene_configs  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--clipblur", required=True, help="comma-separated binaries, compared in this order")
    ap.add_argument("--scenes", help="comma-separated names (bench stems, many/<stem>); default: all")
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=180)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--out", default=str(benchlib.REPO / "build" / "bench" / "default_times"))
    args = ap.parse_args()
    binaries = [benchlib.find_clipblur(b) for b in args.clipblur.split(",")]
    overrides = dict(benchlib.base_overrides(args.width, args.height), **{"render.method": "clipped"})
    print(f"{args.width}x{args.height}, {args.threads} threads, median of {args.repeat} in turns\n")
    print("| scene | " + " | ".join(f"binary {i + 1}: s, re-clips, positions, sweep/points segments"
                                    for i in range(len(binaries))) + " |")
    print("|---|" + "---|" * len(binaries))
    for name, config in scene_configs(args.scenes).items():
        seconds = [[] for _ in binaries]
        counts = [None] * len(binaries)
        for _ in range(args.repeat):
            for i, binary in enumerate(binaries):
                image = Path(args.out) / f"{name.replace('/', '_')}_{i + 1}.exr"
                stats = benchlib.render(binary, config, overrides, image, args.threads)
                seconds[i].append(stats["process_wall_seconds"])
                c = stats["counts"]
                counts[i] = (c["subframes_total"], c.get("sweep_positions", 0), c.get("segments_sweep", 0),
                             c.get("segments_points", 0))
        cells = [f"{statistics.median(s):.2f}, {n[0]}, {n[1]}, {n[2]}/{n[3]}" for s, n in zip(seconds, counts)]
        print(f"| {name} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
