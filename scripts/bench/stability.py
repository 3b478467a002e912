#!/usr/bin/env python3
"""Failure-mode sweeps: error against a converged stochastic reference as one stress grows, for the
clipped method and the baselines. Writes stability.csv and stability.md (the measured tables that
docs/stability.md quotes) and one chart per sweep.

    scripts/bench/stability.py            # 160x90, reference 1024 spp
    scripts/bench/stability.py --width 320 --height 180 --reference-spp 4096
"""

import argparse
import csv
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import benchlib  # noqa: E402

BENCH = benchlib.REPO / "configs" / "bench"

METHODS = [("clipped", {"render.subframes": 1}), ("clipped", {"render.subframes": 4}),
           ("clipped", {"render.subframes": "auto"}), ("accumulation", {"render.samples": 4}),
           ("accumulation", {"render.samples": 16}), ("stochastic", {"render.samples": 16}),
           ("stochastic", {"render.samples": 64})]


def label(method, o):
    return f"{method} {next(iter(o.values()))}"


def motion_length():
    # fast_motion.yaml: the ball at range 8 moves L units along x; 1 unit is height / 5.82 px there.
    for units in (0.25, 1, 2.5, 5, 10):
        yield f"L={units}", units, {"objects.1.transform.0.translate": f"[{-units / 2}, 0, 8]",
                                    "objects.1.transform.1.translate": f"[{units / 2}, 0, 8]"}


def rotation_angle():
    # propeller.yaml: both bars turn by theta over three keys (theta/2 per key interval < 180).
    for theta in (20, 90, 180, 300):
        o = {}
        for obj, start in ((1, 0), (2, 90)):
            for k, frac in enumerate((0, 0.5, 1)):
                o[f"objects.{obj}.transform.{k}.rotate.angle_deg"] = start + theta * frac
        yield f"theta={theta}", theta, o


def near_plane():
    # near_plane.yaml: the camera dollies D units; posts at z = 2, 4, 8 cross its plane when D passes them.
    for d in (1, 3, 5, 9):
        yield f"D={d}", d, {"camera.keys.1.position": f"[0, 0, {d}]"}


SWEEPS = {"motion_length": ("fast_motion", motion_length, "ball travel (units at range 8)"),
          "rotation_angle": ("propeller", rotation_angle, "propeller turn in the shutter (degrees)"),
          "near_plane": ("near_plane", near_plane, "camera dolly (units; posts at 2, 4, 8)")}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--width", type=int, default=160)
    ap.add_argument("--height", type=int, default=90)
    ap.add_argument("--reference-spp", type=int, default=1024)
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--sweeps", default=",".join(SWEEPS))
    ap.add_argument("--out", default=str(benchlib.REPO / "build" / "bench" / "stability"))
    ap.add_argument("--cache", default=str(benchlib.REPO / "build" / "bench" / "reference_cache"))
    ap.add_argument("--clipblur")
    args = ap.parse_args()
    out = Path(args.out)
    rows, md = [], []
    try:
        clipblur = benchlib.find_clipblur(args.clipblur)
        base = {"film.width": args.width, "film.height": args.height, "output.half": "false"}
        for name in args.sweeps.split(","):
            scene, points, xlabel = SWEEPS[name]
            config = BENCH / f"{scene}.yaml"
            md += [f"### {name} ({scene}.yaml, {args.width}x{args.height}, RMSE / max abs error vs stochastic "
                   f"{args.reference_spp} spp)", "",
                   "| " + " | ".join([xlabel] + [label(m, o) for m, o in METHODS]) + " | clipped auto subframes |",
                   "|" + "---|" * (len(METHODS) + 2)]
            series = {label(m, o): [] for m, o in METHODS}
            for tag, x, sweep_o in points():
                print(f"{name} {tag}", flush=True)
                job = dict(base, **sweep_o)
                ref = benchlib.reference_image(clipblur, config, job, args.reference_spp, args.cache, args.threads)
                cells, auto_sub = [str(x)], ""
                for method, o in METHODS:
                    image = out / "renders" / name / f"{tag}_{method}_{next(iter(o.values()))}.exr"
                    stats = benchlib.render(clipblur, config, dict(job, **{"render.method": method}, **o), image,
                                            args.threads)
                    err = benchlib.image_error(ref, image)
                    counts = stats.get("counts", {})
                    if method == "clipped" and o["render.subframes"] == "auto":
                        auto_sub = str(counts.get("subframes_max_per_tile", ""))
                    rows.append({"sweep": name, "x": x, "method": label(method, o), "seconds": stats["seconds"]["total"],
                                 "rmse": err["rmse"], "max_abs": err["max_abs"],
                                 "near_clipped": counts.get("open_near_clipped", 0) + counts.get("close_near_clipped", 0)
                                 + counts.get("reclip_near_clipped", 0),
                                 "max_time_steps": counts.get("max_time_steps", "")})
                    cells.append(f"{err['rmse']:.4f} / {err['max_abs']:.3f}")
                    series[label(method, o)].append((x, err["rmse"], ""))
                md.append("| " + " | ".join(cells + [auto_sub]) + " |")
            md.append("")
            benchlib.gnuplot_chart(out / "charts" / name, f"{name}: error vs stress", list(series.items()), xlabel,
                                   "RMSE vs reference", logx=False, logy=True)

        topo = BENCH / "refused" / "topology_change.yaml"
        r = subprocess.run([clipblur, "validate", str(topo)], capture_output=True, text=True)
        md += ["### topology change between deformation keys", "",
               f"`clipblur validate configs/bench/refused/topology_change.yaml` exit {r.returncode}:", "",
               "    " + (r.stderr.strip() or r.stdout.strip()).replace("\n", "\n    "), ""]
        out.mkdir(parents=True, exist_ok=True)
        with open(out / "stability.csv", "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0].keys()) if rows else ["sweep"])
            w.writeheader()
            w.writerows(rows)
        (out / "stability.md").write_text("\n".join(md) + "\n")
        print("\n".join(md))
    except benchlib.BenchError as e:
        print(f"stability: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
