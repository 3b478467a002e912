#!/usr/bin/env python3
"""Issue 20, item 2: which RMS error is visually converged? Per bench scene, clipped renders at several
settings against a reference converged in time and in re-clips, judged twice:

  rmse      linear RMS over R, G, B (white = 1): what render.error_target aims for;
  display   both images as an 8-bit sRGB display shows them (oiiotool --colorconvert linear sRGB,
            uint8): the largest difference in code values, and the share of pixels more than one code
            value off. One code value is what quantisation to the display already does to the reference,
            so a render no pixel of which is more than one code value off shows no strobing or stepping
            that the display could show.

Settings: the default render (nothing set), the default with render.sweep_spacing S (--spacings: under
time_integration auto it places point subframes too), render.error_target T (--targets), and, for context, the
strongest peer's stochastic ray casting at --peer-spp samples. The reference is sweep integration at
--reference-spacing px with automatic re-clips spaced 1 / --refine px (--refine x a default render's
in every tile and shutter segment).

    scripts/bench/visual_threshold.py --width 320 --height 180 --targets 1e-2,3e-3,1e-3,3e-4
"""

import argparse
import csv
import re
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import benchlib  # noqa: E402
from error_estimate import scene_configs  # noqa: E402

CODE = 1.0 / 255.0


def display_image(exr):
    """The image as an 8-bit sRGB display shows it, beside the EXR."""
    png = exr.with_suffix(".display.png")
    subprocess.run(["oiiotool", str(exr), "--ch", "R,G,B", "--colorconvert", "linear", "sRGB", "-d", "uint8",
                    "-o", str(png)], check=True, capture_output=True)
    return png


def display_difference(reference, image):
    """Largest difference in code values and the share of pixels more than one code value off. oiiotool
    prints figures only for a comparison that fails, hence one threshold for each figure."""
    a, b = str(display_image(reference)), str(display_image(image))

    def diff(fail):
        out = subprocess.run(["oiiotool", a, b, "--fail", f"{fail:g}", "--warn", "1e30", "--diff"],
                             capture_output=True, text=True)
        return out.stdout + out.stderr

    peak = re.search(r"Max error\s*=\s*([0-9.eE+-]+)", diff(0.0))
    # Lines "N pixels (P%) over T" for the warn threshold (1e30) and the fail one; keep the fail one's.
    over = [float(p) for p, t in re.findall(r"\d+ pixels \(([0-9.eE+-]+)%\) over (\S+)", diff(1.5 * CODE))
            if float(t) < 1e29]
    return {"max_codes": round(float(peak.group(1)) / CODE) if peak else 0,
            "over_one_percent": over[0] if over else 0.0}


def parse_setting(text):
    """'label:key=value,key=value' as (label, overrides); values stay text (benchlib passes --set)."""
    label, _, pairs = text.partition(":")
    pairs = [p for p in pairs.split(",") if p]
    if not label or not pairs or not all("=" in p for p in pairs):
        raise SystemExit(f"--settings: '{text}' is not label:key=value[,key=value...]")
    return label, dict(p.split("=", 1) for p in pairs)


def run_scene(clipblur, name, config, args, folder):
    base = benchlib.base_overrides(args.width, args.height)
    stem = folder / name.replace("/", "_")

    def clipped(tag, overrides):
        image = stem / f"{tag}.exr"
        stats = benchlib.render(clipblur, config, dict(base, **{"render.method": "clipped"}, **overrides), image,
                                args.threads)
        return image, stats

    earlier = benchlib.earlier_references(args.references_from, stem.name, "reference.exr")
    if earlier:
        reference = earlier[0]
    else:
        # Automatic re-clips --refine x as dense as a default render's in every tile of every shutter
        # segment (a fixed count would be shared out over the segments), uncapped.
        reference, _ = clipped("reference", {"render.time_integration": "sweep",
                                             "render.sweep_spacing": args.reference_spacing,
                                             "render.reclip_spacing": 1.0 / args.refine,
                                             "render.max_subframes": 4096})
    settings = ([("default", {})] + [(f"spacing {s:g}", {"render.sweep_spacing": s}) for s in args.spacings] +
                [(f"target {t:g}", {"render.error_target": t}) for t in args.targets] + args.settings)
    rows = []
    for label, overrides in settings:
        image, stats = clipped(label.replace(" ", "_"), overrides)
        rows.append({"scene": name, "setting": label, "seconds": stats["process_wall_seconds"],
                     "rmse": benchlib.image_error(reference, image)["rmse"], **display_difference(reference, image)})
    if args.peer_spp:
        image = stem / f"stochastic_{args.peer_spp}.exr"
        stats = benchlib.render(clipblur, config, dict(base, **{"render.method": "stochastic",
                                                               "render.samples": args.peer_spp}), image, args.threads)
        rows.append({"scene": name, "setting": f"stochastic {args.peer_spp} spp",
                     "seconds": stats["process_wall_seconds"],
                     "rmse": benchlib.image_error(reference, image)["rmse"], **display_difference(reference, image)})
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", help="comma-separated names (bench stems, many/<stem>); default: all but "
                                     "dense_mesh and near_plane")
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=180)
    ap.add_argument("--targets", default="1e-2,3e-3,1e-3,3e-4")
    ap.add_argument("--spacings", default="", help="comma-separated render.sweep_spacing values (px) to "
                                                   "render beside the default")
    ap.add_argument("--settings", default="", help="more settings to judge, ';'-separated, each "
                    "label:key=value[,key=value...], e.g. 'exact:render.sweep_time=exact'")
    ap.add_argument("--peer-spp", type=int, default=256, help="stochastic samples for context (0: none)")
    ap.add_argument("--reference-spacing", type=float, default=0.05, help="px")
    ap.add_argument("--refine", type=int, default=4, help="the reference's re-clips over the auto ones")
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--out", default=str(benchlib.REPO / "build" / "bench" / "visual_threshold"))
    ap.add_argument("--references-from", help="reuse the references of an earlier --out at the same size "
                                               "(another binary's renders against the same references)")
    ap.add_argument("--clipblur", help="path of the clipblur binary (default build/clipblur or $CLIPBLUR)")
    args = ap.parse_args()
    args.targets = [float(t) for t in args.targets.split(",") if t]
    args.spacings = [float(s) for s in args.spacings.split(",") if s]
    args.settings = [parse_setting(s) for s in args.settings.split(";") if s]
    clipblur = benchlib.find_clipblur(args.clipblur)
    scenes = scene_configs(args.scenes)
    if not args.scenes:
        scenes = {n: c for n, c in scenes.items() if n.split("/")[0] not in ("dense_mesh", "near_plane", "table1")}
    folder = Path(args.out)
    rows = []
    for name, config in scenes.items():
        try:
            rows += run_scene(clipblur, name, config, args, folder / "renders")
        except benchlib.BenchError as e:
            print(f"{name}: {e}", file=sys.stderr)
    folder.mkdir(parents=True, exist_ok=True)
    with open(folder / "results.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["scene", "setting", "seconds", "rmse", "max_codes", "over_one_percent"])
        w.writeheader()
        w.writerows(rows)
    print(f"{args.width}x{args.height}; reference: sweep {args.reference_spacing:g} px, re-clips "
          f"{1.0 / args.refine:g} px\n")
    print("| scene | setting | RMSE (linear) | max difference (8-bit sRGB codes) | pixels > 1 code | seconds |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['scene']} | {r['setting']} | {r['rmse']:.2e} | {r['max_codes']} | "
              f"{r['over_one_percent']:.3f} % | {r['seconds']:.2f} |")


if __name__ == "__main__":
    main()
