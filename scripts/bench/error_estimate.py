#!/usr/bin/env python3
"""Issue 20, item 2: does a clipped render's own `estimated_error` (stats `values.estimated_error`,
renderer/clipped/time_error.h) match its measured error?

Per bench scene (default: configs/bench/*.yaml, configs/bench/many/*.yaml, configs/table1/*.yaml) at a
small size, and per setting:

  sweep, spacing S      time_integration sweep, auto re-clips, sweep_spacing S (--spacings);
  subframes, N          point subframes, render.subframes N (--subframes);

the render's estimated_error beside two measured errors (RMS over R, G, B, oiiotool --diff):

  e_time   against the same re-clips with the time sampling the estimate covers made --refine times
           finer (sweep: spacing S / refine, the render's re-clip count fixed, as auto re-clips follow
           the spacing; subframes: N x refine subframes).
           This is what the estimate claims to estimate;
  e_total  (sweep only, --total) against a clipped render fine in everything: sweep with --refine x
           the auto re-clips (render.subframes) and spacing S / refine. The difference to e_time is what
           re-clips add (occlusion order between re-clips), which the estimate does not cover.

The ratio estimate / measured is the figure of merit (issue 20 asks for 0.5 .. 1.5 of the target).

With --targets T1,T2,..: instead, per scene and target, a sweep render with render.error_target T
(renderer/clipped/error_target.h) and its measured e_total against a sweep at --reference-spacing, whose
auto re-clips follow that spacing as its positions do (fine in everything), as a ratio to T. Beside it,
per scene, `ref_check`: the reference's difference from the same render at twice its spacing, which
bounds the reference's own error where it converges (both errors fall with the spacing).

With --targets and --search-only: no references, only what each search chose (spacing, the re-clip
check's re-clip spacing and measured order, renders): which rows a change to the search moves.

Writes a markdown table to stdout and results.csv under --out.

    scripts/bench/error_estimate.py                       # every bench scene at 160x90
    scripts/bench/error_estimate.py --scenes table1_pan,propeller --spacings 4,1 --subframes 27
    scripts/bench/error_estimate.py --targets 1e-2,1e-3,1e-4 --refine 4
    scripts/bench/error_estimate.py --targets 1e-2,1e-3 --random-seeds 1,2,3   # seeded random scenes
"""

import argparse
import csv
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import benchlib  # noqa: E402
from random_scenes import write_scenes  # noqa: E402


def scene_configs(names):
    repo = benchlib.REPO
    found = sorted((repo / "configs" / "bench").glob("*.yaml")) + sorted((repo / "configs" / "bench" / "many").glob("*.yaml"))
    found += sorted((repo / "configs" / "table1").glob("*.yaml"))
    configs = {}
    for path in found:
        name = path.stem if path.parent.name == "bench" else f"{path.parent.name}/{path.stem}"
        configs[name] = path
    if names:
        wanted = names.split(",")
        missing = [n for n in wanted if n not in configs]
        if missing:
            raise SystemExit(f"unknown scenes: {', '.join(missing)} (known: {', '.join(configs)})")
        return {n: configs[n] for n in wanted}
    return configs


def chosen_configs(args, folder):
    """The named bench scenes and the seeded random ones (--random-seeds: only those unless --scenes)."""
    seeds = [int(s) for s in args.random_seeds.split(",")] if args.random_seeds else []
    configs = scene_configs(args.scenes) if args.scenes or not seeds else {}
    configs.update(write_scenes(seeds, folder / "random"))
    return configs


def ratio(a, b):
    return a / b if b > 0 else math.nan


def run_scene(clipblur, name, config, args, folder):
    base = benchlib.base_overrides(args.width, args.height)
    base["render.method"] = "clipped"
    rows = []
    stem = name.replace("/", "_")

    def render(tag, overrides):
        image = folder / stem / f"{tag}.exr"
        stats = benchlib.render(clipblur, config, dict(base, **overrides), image, args.threads)
        return image, stats

    for spacing in args.spacings:
        o = {"render.time_integration": "sweep", "render.sweep_spacing": spacing}
        image, stats = render(f"sweep_{spacing:g}", o)
        reclips = stats["counts"].get("subframes_max_per_tile", 0)
        # Positions are capped at max_subframes: the reference lifts the cap. Auto re-clips follow the
        # spacing, so the reference fixes the render's count (the same intervals where there is one shutter
        # segment; a fixed count is shared out over several, which same_reclips then shows).
        fine_o = {"render.sweep_spacing": spacing / args.refine, "render.max_subframes": 4096}
        if reclips > 0:
            fine_o["render.subframes"] = reclips
        fine, fine_stats = render(f"sweep_{spacing:g}_fine", dict(o, **fine_o))
        row = {"scene": name, "setting": f"sweep {spacing:g} px", "reclips": reclips,
               "positions": stats["counts"].get("sweep_positions", 0),
               "seconds": stats["seconds"]["total"],
               "estimated": stats["values"]["estimated_error"],
               "e_time": benchlib.image_error(fine, image)["rmse"],
               # per moving tile (a fixed count re-clips still tiles too, so totals differ)
               "same_reclips": fine_stats["counts"].get("subframes_max_per_tile") == reclips}
        if args.total and reclips > 0:
            total, _ = render(f"sweep_{spacing:g}_total",
                              dict(o, **{"render.sweep_spacing": spacing / args.refine,
                                         "render.subframes": max(1, reclips) * args.refine,
                                         "render.max_subframes": max(256, max(1, reclips) * args.refine)}))
            row["e_total"] = benchlib.image_error(total, image)["rmse"]
        rows.append(row)
    for n in args.subframes:
        o = {"render.time_integration": "subframes", "render.subframes": n, "render.max_subframes": max(256, n * args.refine)}
        image, stats = render(f"subframes_{n}", o)
        fine, _ = render(f"subframes_{n}_fine", dict(o, **{"render.subframes": n * args.refine}))
        rows.append({"scene": name, "setting": f"subframes {n}", "reclips": n, "positions": 0,
                     "seconds": stats["seconds"]["total"],
                     "estimated": stats["values"]["estimated_error"],
                     "e_time": benchlib.image_error(fine, image)["rmse"], "same_reclips": True})
    return rows


def run_targets(clipblur, name, config, args, folder):
    base = benchlib.base_overrides(args.width, args.height)
    base.update({"render.method": "clipped", "render.time_integration": "sweep"})
    stem = name.replace("/", "_")
    fine = {"render.sweep_spacing": args.reference_spacing, "render.max_subframes": 4096}
    # References are plain renders (no target): another run's at the same size may serve (--references-from).
    names = ("target_reference.exr", "target_reference_check.exr")
    earlier = None if args.search_only else benchlib.earlier_references(args.references_from, stem, *names)
    reference, check = earlier or (folder / stem / n for n in names)
    if not args.search_only and not earlier:
        benchlib.render(clipblur, config, dict(base, **fine), reference, args.threads)
        benchlib.render(clipblur, config, {**base, **fine, "render.sweep_spacing": 2 * args.reference_spacing},
                        check, args.threads)
    ref_check = math.nan if args.search_only else benchlib.image_error(reference, check)["rmse"]
    rows = []
    for target in args.targets:
        image = folder / stem / f"target_{target:g}.exr"
        stats = benchlib.render(clipblur, config, dict(base, **{"render.error_target": target}), image, args.threads)
        values, counts = stats["values"], stats.get("counts", {})
        rows.append({"scene": name, "target": target, "spacing": values.get("target_sweep_spacing", math.nan),
                     "estimated": values["estimated_error"], "seconds": stats["seconds"]["total"],
                     "e_total": math.nan if args.search_only else benchlib.image_error(reference, image)["rmse"],
                     "ref_check": ref_check, "reclip_spacing": values.get("target_reclip_spacing", math.nan),
                     "reclip_order": values.get("target_reclip_order", math.nan),
                     "renders": counts.get("target_renders"), "bisections": counts.get("target_bisections"),
                     "pilot_kept": counts.get("target_pilot_kept")})
        r = rows[-1]  # as it comes: a long run shows its rows before the table
        print(f"{name} {target:g}: e_total / target {r['e_total'] / target:.2f}, {r['seconds']:.2f} s", file=sys.stderr,
              flush=True)
    return rows


def print_targets(rows, args):
    if args.search_only:
        print(f"{args.width}x{args.height}, the searches alone (no references)\n")
        print("| scene | target | chosen spacing (px) | re-clip spacing (px) | re-clip order | renders | seconds |")
        print("|---|---|---|---|---|---|---|")
        for r in rows:
            print(f"| {r['scene']} | {r['target']:g} | {r['spacing']:.4g} | {r['reclip_spacing']:.4g} | "
                  f"{r['reclip_order']:.3g} | {r['renders']} | {r['seconds']:.2f} |")
        return
    print(f"{args.width}x{args.height}, references at {args.reference_spacing:g} px (re-clips following)\n")
    print("| scene | target | chosen spacing (px) | estimated / target | e_total / target | ref_check / target | seconds |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        t = r["target"]
        print(f"| {r['scene']} | {t:g} | {r['spacing']:.3g} | {r['estimated'] / t:.2f} | {r['e_total'] / t:.2f} | "
              f"{r['ref_check'] / t:.2f} | {r['seconds']:.2f} |")


def fmt(x):
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.2e}"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", help="comma-separated names (bench stems, many/<stem>, table1/<stem>)")
    ap.add_argument("--width", type=int, default=160)
    ap.add_argument("--height", type=int, default=90)
    ap.add_argument("--spacings", default="4,1,0.25", help="sweep_spacing values (px)")
    ap.add_argument("--subframes", default="9", help="point subframe counts ('' for none)")
    ap.add_argument("--refine", type=int, default=16, help="how much finer the references are")
    ap.add_argument("--total", action=argparse.BooleanOptionalAction, default=True,
                    help="also measure against references with --refine x the re-clips")
    ap.add_argument("--targets", help="render.error_target values: measure the target mode instead")
    ap.add_argument("--reference-spacing", type=float, default=0.05, help="px, for --targets")
    ap.add_argument("--random-seeds", help="comma-separated seeds: also (or, without --scenes, only) the "
                    "scenes scripts/bench/random_scenes.py writes for them, under <out>/random")
    ap.add_argument("--references-from", help="with --targets: reuse the references of an earlier --out at the "
                    "same size and reference spacing instead of rendering them")
    ap.add_argument("--search-only", action="store_true", help="with --targets: no references, only what each "
                    "search chose (the re-clip check's spacing and order among it)")
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--out", default=str(benchlib.REPO / "build" / "bench" / "error_estimate"))
    ap.add_argument("--clipblur", help="path of the clipblur binary (default build/clipblur or $CLIPBLUR)")
    args = ap.parse_args()
    args.spacings = [float(s) for s in args.spacings.split(",") if s]
    args.subframes = [int(s) for s in args.subframes.split(",") if s]
    clipblur = benchlib.find_clipblur(args.clipblur)
    folder = Path(args.out)
    folder.mkdir(parents=True, exist_ok=True)
    rows = []
    if args.targets:
        args.targets = [float(t) for t in args.targets.split(",")]
        for name, config in chosen_configs(args, folder).items():
            try:
                rows += run_targets(clipblur, name, config, args, folder / "renders")
            except benchlib.BenchError as e:
                print(f"{name}: {e}", file=sys.stderr)
        with open(folder / "targets.csv", "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0].keys()) if rows else ["scene"])
            w.writeheader()
            w.writerows(rows)
        print_targets(rows, args)
        return
    for name, config in chosen_configs(args, folder).items():
        try:
            rows += run_scene(clipblur, name, config, args, folder / "renders")
        except benchlib.BenchError as e:
            print(f"{name}: {e}", file=sys.stderr)
    keys = ["scene", "setting", "reclips", "positions", "seconds", "estimated", "e_time",
            "e_total", "same_reclips"]
    with open(folder / "results.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        for r in rows:
            w.writerow({k: r.get(k) for k in keys})
    print(f"{args.width}x{args.height}, references {args.refine}x finer\n")
    print("| scene | setting | re-clips | estimated | e_time | est / e_time | e_total | est / e_total |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        same = "" if r["same_reclips"] else " (re-clips differ)"
        print(f"| {r['scene']} | {r['setting']} | {r['reclips']} | {fmt(r['estimated'])} | "
              f"{fmt(r['e_time'])}{same} | {ratio(r['estimated'], r['e_time']):.2f} | {fmt(r.get('e_total'))} | "
              f"{ratio(r['estimated'], r.get('e_total', math.nan)):.2f} |")


if __name__ == "__main__":
    main()
