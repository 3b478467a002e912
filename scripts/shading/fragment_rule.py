#!/usr/bin/env python3
"""Error against the converged stochastic image, and cost, of the clipped method's fragment-shading rules
(render.fragment_shading: centroid, fan) on configs/shading/globe.yaml, still and spinning, beside the
stochastic method's ladder for scale. Writes docs/img/fragment_shading.{png,dat} and prints a table.

    scripts/shading/fragment_rule.py [--width 320 --height 180 --reference-spp 2048]
"""

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "bench"))
import benchlib  # noqa: E402

CONFIG = benchlib.REPO / "configs" / "shading" / "globe.yaml"
VARIANTS = {"still": {"objects.0.transform": "[]"}, "spinning": {}}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=180)
    ap.add_argument("--reference-spp", type=int, default=2048)
    ap.add_argument("--out", default=str(benchlib.REPO / "build" / "bench" / "fragment_shading"))
    ap.add_argument("--chart", default=str(benchlib.REPO / "docs" / "img" / "fragment_shading"))
    ap.add_argument("--clipblur")
    args = ap.parse_args()
    clipblur = benchlib.find_clipblur(args.clipblur)
    out = Path(args.out)
    series = []
    print("| scene | method | seconds | shading points | RMSE | max |")
    print("|---|---|---|---|---|---|")
    for name, extra in VARIANTS.items():
        base = dict(benchlib.base_overrides(args.width, args.height), **extra)
        reference = benchlib.reference_image(clipblur, CONFIG, base, args.reference_spp, out / "reference")
        runs = [(f"{name} clipped {rule}", {"render.method": "clipped", "render.fragment_shading": rule}, rule)
                for rule in ("centroid", "fan")]
        runs += [(f"{name} stochastic", {"render.method": "stochastic", "render.samples": spp}, f"{spp}spp")
                 for spp in (16, 64, 256)]
        points = {}
        for label, o, tag in runs:
            image = out / f"{name}_{tag}.exr"
            stats = benchlib.render(clipblur, CONFIG, dict(base, **o), image)
            error = benchlib.image_error(reference, image)
            seconds = stats["seconds"]["total"]
            shaded = stats.get("counts", {}).get("shaded_points", "")
            print(f"| {name} | {label.split(' ', 1)[1]} | {seconds:.2f} | {shaded} | {error['rmse']:.5f} | {error['max_abs']:.4f} |")
            points.setdefault(label if "stochastic" in label else f"{name} clipped", []).append(
                (seconds, error["rmse"], tag))
        series += list(points.items())
    benchlib.gnuplot_chart(args.chart, f"globe.yaml {args.width}x{args.height}: RMSE against "
                           f"{args.reference_spp} spp vs render seconds", series, "seconds", "RMSE")


if __name__ == "__main__":
    main()
