#!/usr/bin/env python3
"""The error of any clipped render against the equal-error bench's stochastic pair for its scene, as
equal_error.py measures its ladders (e_c, its standard error and whether it is within noise), so a render
made by hand can be placed on the same scale as e256.

    scripts/bench/clipped_error.py table1_recede my_render.exr [more.exr ...]

The pair is taken from --out (renders/<scene>/stochastic_256_seed*.exr, as equal_error.py left them) and
rendered there at --width x --height when missing. The renders must have the same size.
"""

import argparse
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import benchlib  # noqa: E402
import equal_error  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scene", help="a scene name from configs/bench")
    ap.add_argument("images", nargs="+", help="clipped renders of that scene")
    ap.add_argument("--width", type=int, default=1280)
    ap.add_argument("--height", type=int, default=720)
    ap.add_argument("--seeds", default=",".join(map(str, equal_error.DEFAULT_SEEDS)))
    ap.add_argument("--out", default=str(benchlib.REPO / "build" / "bench" / "equal_error"))
    ap.add_argument("--clipblur", help="path of the clipblur binary (default build/clipblur or $CLIPBLUR)")
    args = ap.parse_args()
    clipblur = benchlib.find_clipblur(args.clipblur)
    config = benchlib.REPO / "configs" / "bench" / f"{args.scene}.yaml"
    folder = Path(args.out) / "renders" / args.scene
    base = benchlib.base_overrides(args.width, args.height)
    pair = []
    for seed in (int(s) for s in args.seeds.split(",")):
        image = folder / f"stochastic_{equal_error.SPP}_seed{seed}.exr"
        if not image.is_file():
            o = dict(base, **benchlib.ladder_overrides("stochastic", equal_error.SPP), **{"render.seed": seed})
            benchlib.render(clipblur, config, o, image)
        pair.append(image)
    sbar = folder / "stochastic_mean.exr"
    r = subprocess.run(["oiiotool", "--no-autopremult"] + equal_error.rgb(pair[0]) + equal_error.rgb(pair[1])
                       + ["--add", "--mulc", "0.5", "-d", "float", "-o", str(sbar)], capture_output=True, text=True)
    if r.returncode != 0:
        raise benchlib.BenchError(f"oiiotool could not average {pair}: {r.stderr.strip()}")
    stochastic = equal_error.StochasticPair(pair[0], pair[1], sbar, args.width * args.height)
    print(f"{args.scene}: e256 {stochastic.e256:.4g}")
    for image in args.images:
        e, se, noise = stochastic.clipped_error(image)
        print(f"{image}: error {'<= ' if noise else ''}{e:.4g} (SE of e^2 {se:.2g})")


if __name__ == "__main__":
    try:
        main()
    except benchlib.BenchError as e:
        print(f"clipped_error: {e}", file=sys.stderr)
        sys.exit(1)
