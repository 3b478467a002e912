#!/usr/bin/env python3
"""Speed-accuracy sweep: renders every bench scene with each method over a quality ladder, measures
wall time (stats seconds.total) and error against a converged stochastic reference, and writes
results.csv, one error-vs-time chart per scene (PNG and SVG) and summary.md with time-to-equal-error
ratios: each baseline at clipped `auto`'s error, and clipped at the error stochastic reaches with 256
samples per pixel (scripts/bench/equal_error.py measures the latter without a reference).

    scripts/bench/speed_accuracy.py                 # full sweep, 320x180, reference 4096 spp
    scripts/bench/speed_accuracy.py --quick         # about 2 minutes: 160x90, fewer scenes and rungs
    scripts/bench/speed_accuracy.py --scenes propeller,sweep --width 640 --height 360
"""

import argparse
import csv
import datetime
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import benchlib  # noqa: E402

ALL_SCENES = ["table1_spin", "table1_pan", "table1_spin_pan", "table1_recede", "table1_recede_spin_pan",
              "propeller", "sweep", "dense_mesh", "fast_motion", "near_plane", "rotate90"]
QUICK_SCENES = ["table1_spin_pan", "sweep", "fast_motion", "near_plane", "rotate90"]

FULL = {"width": 320, "height": 180, "reference_spp": 4096, "clipped": "1,2,4,8,16,32,64,128,auto",
        "stochastic": "1,4,16,64,256,1024", "accumulation": "1,2,4,8,16,32,64"}
QUICK = {"width": 96, "height": 54, "reference_spp": 1024, "clipped": "1,4,auto",
         "stochastic": "1,4,16,64,256", "accumulation": "1,4,16"}

# Issue 5's yardstick: clipped is compared at the error stochastic reaches with this many samples.
EQUAL_ERROR_SPP = 256

CSV_FIELDS = ["scene", "method", "param", "seconds", "rmse", "max_abs", "mean_abs", "subframes_total",
              "subframes_max_per_tile", "rays", "fragments", "width", "height", "threads", "image"]


def parse_ladder(text):
    rungs = []
    for item in text.split(","):
        item = item.strip()
        if item:
            rungs.append(item if item == "auto" else int(item))
    return rungs


def row_from(scene, method, rung, stats, err, args, image):
    counts = stats.get("counts", {})
    fragments = sum(v for k, v in counts.items() if k.endswith("_fragments") and k.count("_") == 1)
    return {"scene": scene, "method": method, "param": rung, "seconds": stats["seconds"]["total"],
            "rmse": err["rmse"], "max_abs": err["max_abs"], "mean_abs": err["mean_abs"],
            "subframes_total": counts.get("subframes_total", ""),
            "subframes_max_per_tile": counts.get("subframes_max_per_tile", ""),
            "rays": counts.get("rays", counts.get("open_rays", "")), "fragments": fragments,
            "width": args.width, "height": args.height, "threads": stats.get("threads", ""), "image": str(image)}


def summarise(rows):
    """For every scene: clipped auto's error and time, and how long each baseline needs to reach the
    same error (log-log interpolation along its ladder)."""
    lines = ["| scene | clipped auto: subframes | time s | RMSE | stochastic time at that RMSE | ratio |"
             " accumulation time at that RMSE | ratio | frame0_only RMSE |",
             "|---|---|---|---|---|---|---|---|---|"]
    scenes = sorted({r["scene"] for r in rows}, key=lambda s: ALL_SCENES.index(s) if s in ALL_SCENES else 99)
    for scene in scenes:
        mine = [r for r in rows if r["scene"] == scene]
        auto = [r for r in mine if r["method"] == "clipped" and r["param"] == "auto"]
        if not auto:
            continue
        a = auto[0]
        cells = [scene, str(a["subframes_max_per_tile"]), f"{a['seconds']:.3f}", f"{a['rmse']:.4g}"]
        for method in ("stochastic", "accumulation"):
            pts = [(r["seconds"], r["rmse"]) for r in mine if r["method"] == method]
            if not pts:
                cells += ["-", "-"]
                continue
            t = benchlib.time_to_reach(pts, a["rmse"])
            if t is None:
                longest = max(p[0] for p in pts)
                cells += [f"not reached (> {longest:.3f})", f"> {longest / a['seconds']:.3g}"]
            else:
                cells += [f"{t:.3f}", f"{t / a['seconds']:.3g}"]
        f0 = [r for r in mine if r["method"] == "frame0_only"]
        cells.append(f"{f0[0]['rmse']:.4g}" if f0 else "-")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def summarise_equal_error(rows, spp=EQUAL_ERROR_SPP):
    """Issue 5's comparison: the error stochastic reaches with `spp` samples per pixel, and the time
    clipped needs for it, interpolated in log-log along every clipped rung (not only `auto`)."""
    lines = [f"| scene | stochastic {spp} spp: time s | RMSE | clipped time at that RMSE | ratio |",
             "|---|---|---|---|---|"]
    scenes = sorted({r["scene"] for r in rows}, key=lambda s: ALL_SCENES.index(s) if s in ALL_SCENES else 99)
    for scene in scenes:
        mine = [r for r in rows if r["scene"] == scene]
        target = [r for r in mine if r["method"] == "stochastic" and str(r["param"]) == str(spp)]
        clipped = [(r["seconds"], r["rmse"]) for r in mine if r["method"] == "clipped"]
        if not target or not clipped:
            continue
        s = target[0]
        cells = [scene, f"{s['seconds']:.3f}", f"{s['rmse']:.4g}"]
        t = benchlib.time_to_reach(clipped, s["rmse"])
        if t is None:
            best = min(e for _, e in clipped)
            cells += [f"not reached (best RMSE {best:.4g})", "-"]
        else:
            cells += [f"{t:.3f}", f"{s['seconds'] / t:.3g}"]
        lines.append("| " + " | ".join(cells) + " |")
    if len(lines) == 2:
        return f"(no stochastic {spp} spp rung or no clipped rung: equal-error table left out)\n"
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--quick", action="store_true", help="small film, few scenes and rungs (~2 min)")
    ap.add_argument("--scenes", help="comma-separated scene names from configs/bench (default: all, or the quick set)")
    ap.add_argument("--width", type=int)
    ap.add_argument("--height", type=int)
    ap.add_argument("--reference-spp", type=int)
    ap.add_argument("--clipped", help="subframe ladder, e.g. 1,2,4,auto")
    ap.add_argument("--stochastic", help="samples-per-pixel ladder")
    ap.add_argument("--accumulation", help="renders-per-frame ladder")
    ap.add_argument("--threads", type=int, default=0, help="render threads (0: all cores)")
    ap.add_argument("--out", default=str(benchlib.REPO / "build" / "bench" / "speed_accuracy"))
    ap.add_argument("--cache", default=str(benchlib.REPO / "build" / "bench" / "reference_cache"))
    ap.add_argument("--refresh-reference", action="store_true", help="re-render cached references")
    ap.add_argument("--clipblur", help="path of the clipblur binary (default build/clipblur or $CLIPBLUR)")
    args = ap.parse_args()

    preset = QUICK if args.quick else FULL
    for key in ("width", "height", "reference_spp", "clipped", "stochastic", "accumulation"):
        if getattr(args, key) is None:
            setattr(args, key, preset[key])
    scenes = args.scenes.split(",") if args.scenes else (QUICK_SCENES if args.quick else ALL_SCENES)

    try:
        clipblur = benchlib.find_clipblur(args.clipblur)
        benchlib.require_tool("oiiotool")
        benchlib.require_tool("gnuplot")
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        ladders = {m: parse_ladder(getattr(args, m)) for m in ("clipped", "stochastic", "accumulation")}
        rows = []
        for scene in scenes:
            config = benchlib.REPO / "configs" / "bench" / f"{scene}.yaml"
            if not config.is_file():
                raise benchlib.BenchError(f"no bench scene {config}")
            print(f"{scene}:", flush=True)
            base = benchlib.base_overrides(args.width, args.height)
            ref = benchlib.reference_image(clipblur, config, base, args.reference_spp, args.cache, args.threads,
                                           args.refresh_reference)
            runs = [(m, r) for m in ("clipped", "stochastic", "accumulation") for r in ladders[m]]
            runs.append(("frame0_only", "-"))
            for method, rung in runs:
                o = dict(base)
                o.update(benchlib.ladder_overrides(method, rung) if method != "frame0_only" else {"render.method": method})
                image = out / "renders" / scene / f"{method}_{rung}.exr"
                stats = benchlib.render(clipblur, config, o, image, args.threads)
                err = benchlib.image_error(ref, image)
                row = row_from(scene, method, rung, stats, err, args, image)
                rows.append(row)
                print(f"  {method:12s} {str(rung):>5s}  {row['seconds']:8.3f} s  rmse {row['rmse']:.4g}  "
                      f"max {row['max_abs']:.4g}", flush=True)

            series = []
            for method in ("clipped", "stochastic", "accumulation", "frame0_only"):
                pts = [(r["seconds"], r["rmse"], "" if r["param"] == "-" else r["param"]) for r in rows if r["scene"] == scene and r["method"] == method]
                if pts:
                    series.append((method, sorted(pts, key=lambda p: p[0])))
            benchlib.gnuplot_chart(out / "charts" / scene, f"{scene} ({args.width}x{args.height}, reference "
                                   f"{args.reference_spp} spp)", series, "render time (s)", "RMSE vs reference")

        with open(out / "results.csv", "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=CSV_FIELDS)
            w.writeheader()
            w.writerows(rows)
        summary = (summarise(rows) + f"\nClipped at the error stochastic reaches with {EQUAL_ERROR_SPP} spp (ratio: "
                   f"stochastic time / clipped time):\n\n" + summarise_equal_error(rows))
        meta = {"date": datetime.datetime.now().isoformat(timespec="seconds"), "git": benchlib.git_hash(),
                "machine": benchlib.machine_description(), "argv": sys.argv[1:], "width": args.width,
                "height": args.height, "reference_spp": args.reference_spp, "ladders": ladders}
        with open(out / "summary.md", "w") as f:
            f.write(f"Speed-accuracy sweep, {meta['date']}, git {meta['git'][:12]}, "
                    f"{meta['machine']['nproc']} x {meta['machine']['cpu_model']}\n\n{summary}")
        with open(out / "run.json", "w") as f:
            json.dump(meta, f, indent=2)
        print("\n" + summary)
        print(f"wrote {out / 'results.csv'}, {out / 'summary.md'}, charts in {out / 'charts'}")
    except benchlib.BenchError as e:
        print(f"speed_accuracy: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
