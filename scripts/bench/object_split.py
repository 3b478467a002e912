#!/usr/bin/env python3
"""Issue 20's table: the cost of a frame must follow what moves, not how the scene was cut into objects.

The paper's spin/pan camera move (Table 1, case 4) over a still black and white board of 24 x 16 unit
cells ten units away (configs/bench/peers/spin_pan_checker.yaml's scene), modelled three ways:

  1 object   the board as one grid with a checker texture (the peer scene itself);
  2 objects  the white cells and the black cells, flat colours (OBJ files written here);
  N objects  one object per cell, flat colours.

Each is rendered with sweep integration and automatic re-clips and positions, and the table gives
the re-clips per tile (`subframes_max_per_tile`), sweep positions, the render's seconds (`seconds.total`),
the process's wall clock, and the RMSE and max error against the 1-object image (or against a stochastic
reference with --reference-spp N).

    scripts/bench/object_split.py [--width 640 --height 360] [--reference-spp 0] [--repeats 3]
"""

import argparse
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import benchlib  # noqa: E402

COLUMNS, ROWS = 24, 16
DEPTH = 10.0


def cell_quads(colour=None):
    """The board's cells as quads (4 corners each), optionally only those of one colour (0 white, 1 black).
    Cell (i, j) spans x in [j - 12, j - 11], y in [i - 8, i - 7] at z = DEPTH, wound to face -z."""
    for i in range(ROWS):
        for j in range(COLUMNS):
            c = (i + j) % 2
            if colour is not None and c != colour:
                continue
            x0, y0 = j - COLUMNS / 2, i - ROWS / 2
            yield c, [(x0, y0), (x0, y0 + 1), (x0 + 1, y0 + 1), (x0 + 1, y0)]


def write_obj(path, quads):
    with open(path, "w") as f:
        for k, corners in enumerate(quads):
            for x, y in corners:
                f.write(f"v {x:g} {y:g} {DEPTH:g}\n")
            b = 4 * k
            f.write(f"f {b + 1} {b + 2} {b + 3}\nf {b + 1} {b + 3} {b + 4}\n")


def job_text(objects):
    """A job with the peer scene's camera, film and light, and the given (name, obj, material) objects."""
    lines = ["version: 1", "film: {width: 640, height: 360, background: 0.0}",
             "camera:", "  vfov: 40", "  keys:",
             "    - {time: 0, position: [0, 0, 0], view: [0, 0, 1], up: [0, 1, 0]}",
             "    - {time: 1, position: [0, 0, 0], view: [0, 0.1, 1], up: [0.1, 1, 0]}",
             "materials:", "  - {name: white, color: 1.0}", "  - {name: black, color: 0.0}",
             "ambient: 1.0", "objects:"]
    lines += [f"  - {{name: {name}, material: {material}, obj: {obj}}}" for name, obj, material in objects]
    lines += ["render: {method: clipped, time_integration: sweep, subframes: auto, samples: 256, seed: 1}",
              "output: {path: split.exr, png_preview: false, half: false}"]
    return "\n".join(lines) + "\n"


def make_jobs(folder):
    """The 2-object and the N-object jobs (with their OBJ files) in `folder`."""
    quads = list(cell_quads())
    write_obj(folder / "white.obj", [q for c, q in quads if c == 0])
    write_obj(folder / "black.obj", [q for c, q in quads if c == 1])
    (folder / "two.yaml").write_text(job_text([("white", "white.obj", "white"), ("black", "black.obj", "black")]))
    cells = []
    for k, (c, q) in enumerate(quads):
        write_obj(folder / f"cell{k}.obj", [q])
        cells.append((f"cell{k}", f"cell{k}.obj", "black" if c else "white"))
    (folder / "cells.yaml").write_text(job_text(cells))
    return {"1 object (checker texture)": benchlib.REPO / "configs/bench/peers/spin_pan_checker.yaml",
            "2 objects": folder / "two.yaml", f"{len(cells)} objects (one per cell)": folder / "cells.yaml"}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--width", type=int, default=640)
    ap.add_argument("--height", type=int, default=360)
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--repeats", type=int, default=3, help="renders per variant, alternating; the fastest counts")
    ap.add_argument("--reference-spp", type=int, default=0,
                    help="compare against a stochastic render at this many spp instead of the 1-object image")
    ap.add_argument("--clipblur", help="path of the clipblur binary (default build/clipblur or $CLIPBLUR)")
    args = ap.parse_args()
    try:
        clipblur = benchlib.find_clipblur(args.clipblur)
        benchlib.require_tool("oiiotool")
        with tempfile.TemporaryDirectory() as tmp:
            folder = Path(tmp)
            jobs = make_jobs(folder)
            film = dict(benchlib.base_overrides(args.width, args.height), **{"render.time_integration": "sweep"})
            best = {}
            for r in range(args.repeats):
                for name, config in jobs.items():
                    image = folder / f"variant{list(jobs).index(name)}_{r}.exr"
                    start = time.perf_counter()
                    stats = benchlib.render(clipblur, config, film, image, args.threads)
                    wall = time.perf_counter() - start
                    if name not in best or wall < best[name]["wall"]:
                        best[name] = {"stats": stats, "wall": wall, "image": image}
            names = list(jobs)
            reference = best[names[0]]["image"]
            label = "the 1-object image"
            if args.reference_spp:
                reference = folder / "reference.exr"
                benchlib.render(clipblur, jobs[names[0]], dict(film, **{"render.method": "stochastic",
                                                                     "render.samples": args.reference_spp}),
                                reference, args.threads)
                label = f"stochastic {args.reference_spp} spp"
            print(f"{args.width}x{args.height}, git {benchlib.git_hash()[:12]}, fastest of {args.repeats}; errors against {label}\n")
            print("| the board modelled as | re-clips per tile | sweep positions | seconds (stats total) | wall clock s | RMSE | max error |")
            print("|---|---|---|---|---|---|---|")
            for name in names:
                b = best[name]
                counts, seconds = b["stats"]["counts"], b["stats"]["seconds"]
                e = benchlib.image_error(reference, b["image"])
                print(f"| {name} | {counts.get('subframes_max_per_tile', '-')} | {counts.get('sweep_positions', '-')} | "
                      f"{seconds['total']:.3f} | {b['wall']:.3f} | {e['rmse']:.3g} | {e['max_abs']:.3g} |")
    except (benchlib.BenchError, subprocess.CalledProcessError) as e:
        print(f"object_split: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
