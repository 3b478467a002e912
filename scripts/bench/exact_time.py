#!/usr/bin/env python3
"""Exact time integration against point positions: per bench scene, sweep renders with
render.sweep_time points and exact over a sweep_spacing ladder, each against one reference (point
positions 0.05 px apart, 4x the auto re-clips: converged in time and re-clips, and sharing no code with
the exact rule), printed as a markdown table of whole-process wall clock, RMSE and sweep positions.

    scripts/bench/exact_time.py                                   # the scenes below, 320x180, 2 threads
    scripts/bench/exact_time.py --scenes sweep,propeller --spacings 4,1
"""

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import benchlib  # noqa: E402

SCENES = ["sweep", "table1_pan", "table1_spin_pan", "table1_recede", "propeller", "many/street", "many/particles",
          "crossing"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", default=",".join(SCENES), help="bench stems, many/<stem> for configs/bench/many")
    ap.add_argument("--spacings", default="4,2,1,0.5", help="sweep_spacing ladder (px)")
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=180)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--out", default=str(benchlib.REPO / "build" / "bench" / "exact_time"))
    ap.add_argument("--clipblur", help="path of the clipblur binary (default build/clipblur or $CLIPBLUR)")
    args = ap.parse_args()
    clipblur = benchlib.find_clipblur(args.clipblur)
    base = dict(benchlib.base_overrides(args.width, args.height),
                **{"render.method": "clipped", "render.time_integration": "sweep"})
    print("| scene | sweep_time | sweep_spacing | wall s | RMSE | sweep positions |")
    print("|---|---|---|---|---|---|")
    for name in args.scenes.split(","):
        config = benchlib.REPO / "configs" / "bench" / f"{name}.yaml"
        stem = Path(args.out) / name.replace("/", "_")
        probe = benchlib.render(clipblur, config, base, stem / "probe.exr", args.threads)
        reclips = max(1, probe["counts"].get("subframes_max_per_tile", 0))
        reference = stem / "reference.exr"
        benchlib.render(clipblur, config, dict(base, **{"render.sweep_spacing": 0.05, "render.subframes": 4 * reclips,
                                                        "render.max_subframes": max(4096, 4 * reclips)}),
                        reference, args.threads)
        for mode in ("points", "exact"):
            for spacing in args.spacings.split(","):
                image = stem / f"{mode}_{spacing}.exr"
                stats = benchlib.render(clipblur, config, dict(base, **{"render.sweep_time": mode,
                                                                        "render.sweep_spacing": spacing}),
                                        image, args.threads)
                print(f"| {name} | {mode} | {spacing} | {stats['process_wall_seconds']:.2f} | "
                      f"{benchlib.image_error(reference, image)['rmse']:.2e} | "
                      f"{stats['counts'].get('sweep_positions', 0)} |", flush=True)


if __name__ == "__main__":
    main()
