#!/usr/bin/env python3
"""Error against the converged stochastic image, and cost, of the clipped method's fragment-shading rules
(render.fragment_shading: centroid, fan, integral) beside the stochastic method's ladder for scale.

`globe` (default): configs/shading/globe.yaml, still and spinning; writes docs/img/fragment_shading.{png,dat}.
`shot`: the shipped shot's frame (configs/shot.yaml) still (a zero-length shutter) and moving (its own
shutter), no chart; pass --width 160 --height 90 --reference-spp 1024 for the figures in docs/design.md.
Prints a table.

    scripts/shading/fragment_rule.py [--scene globe|shot] [--width 320 --height 180 --reference-spp 2048]
"""

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "bench"))
import benchlib  # noqa: E402

RULES = ("centroid", "fan", "integral")
SCENES = {
    "globe": (benchlib.REPO / "configs" / "shading" / "globe.yaml",
              {"still": {"objects.0.transform": "[]"}, "spinning": {}}),
    "shot": (benchlib.REPO / "configs" / "shot.yaml",
             {"still": {"shutter.open": 0, "shutter.close": 0}, "moving": {}}),
}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", choices=sorted(SCENES), default="globe")
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=180)
    ap.add_argument("--reference-spp", type=int, default=2048)
    ap.add_argument("--out", default=str(benchlib.REPO / "build" / "bench" / "fragment_shading"))
    ap.add_argument("--chart", default=str(benchlib.REPO / "docs" / "img" / "fragment_shading"))
    ap.add_argument("--clipblur")
    args = ap.parse_args()
    clipblur = benchlib.find_clipblur(args.clipblur)
    config, variants = SCENES[args.scene]
    out = Path(args.out)
    series = []
    print("| scene | method | seconds | shading points | RMSE | max |")
    print("|---|---|---|---|---|---|")
    for name, extra in variants.items():
        base = dict(benchlib.base_overrides(args.width, args.height), **extra)
        reference = benchlib.reference_image(clipblur, config, base, args.reference_spp, out / "reference")
        runs = [(f"{name} clipped {rule}", {"render.method": "clipped", "render.fragment_shading": rule}, rule)
                for rule in RULES]
        runs += [(f"{name} stochastic", {"render.method": "stochastic", "render.samples": spp}, f"{spp}spp")
                 for spp in (16, 64, 256)]
        points = {}
        for label, o, tag in runs:
            image = out / f"{args.scene}_{name}_{tag}.exr"
            stats = benchlib.render(clipblur, config, dict(base, **o), image)
            error = benchlib.image_error(reference, image)
            seconds = stats["seconds"]["total"]
            shaded = stats.get("counts", {}).get("shaded_points", "")
            print(f"| {args.scene} {name} | {label.split(' ', 1)[1]} | {seconds:.2f} | {shaded} | "
                  f"{error['rmse']:.2g} | {error['max_abs']:.2g} |")
            points.setdefault(label if "stochastic" in label else f"{name} clipped", []).append(
                (seconds, error["rmse"], tag))
        series += list(points.items())
    if args.scene == "globe":
        benchlib.gnuplot_chart(args.chart, f"globe.yaml {args.width}x{args.height}: RMSE against "
                               f"{args.reference_spp} spp vs render seconds", series, "seconds", "RMSE")


if __name__ == "__main__":
    main()
