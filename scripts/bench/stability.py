#!/usr/bin/env python3
"""Failure-mode sweeps: error against a converged stochastic reference as one stress grows, for the
clipped method and the baselines. Writes stability.csv and stability.md (the measured tables that
docs/stability.md quotes) and one chart per sweep.

    scripts/bench/stability.py            # 160x90, reference 1024 spp, every sweep
    scripts/bench/stability.py --sweeps ode_steps,coincident --width 64 --height 36 --reference-spp 256
    scripts/bench/stability.py --width 320 --height 180 --reference-spp 4096
"""

import argparse
import csv
import io
import math
import re
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
    # propeller.yaml: both bars turn by theta over three keys, theta/2 per key interval. Slerp takes the
    # short arc, so a key interval must stay below 180 degrees; 350 (175 per interval) and 358 (179) probe
    # the limit where the interpolation between two keys approaches the ambiguous half turn.
    for theta in (20, 90, 180, 300, 350, 358):
        o = {}
        for obj, start in ((1, 0), (2, 90)):
            for k, frac in enumerate((0, 0.5, 1)):
                o[f"objects.{obj}.transform.{k}.rotate.angle_deg"] = start + theta * frac
        yield f"theta={theta}", theta, o


def near_plane():
    # near_plane.yaml: the camera dollies D units; posts at z = 2, 4, 8 cross its plane when D passes them.
    for d in (1, 3, 5, 9):
        yield f"D={d}", d, {"camera.keys.1.position": f"[0, 0, {d}]"}


RENDER_SWEEPS = {"motion_length": ("fast_motion", motion_length, "ball travel (units at range 8)"),
                 "rotation_angle": ("propeller", rotation_angle, "propeller turn in the shutter (degrees)"),
                 "near_plane": ("near_plane", near_plane, "camera dolly (units; posts at 2, 4, 8)")}
SWEEPS = list(RENDER_SWEEPS) + ["ode_steps", "coincident"]


def render_sweep(clipblur, args, base, name, out, rows, md):
    scene, points, xlabel = RENDER_SWEEPS[name]
    config = BENCH / f"{scene}.yaml"
    md += [f"### {name} ({scene}.yaml, {args.width}x{args.height}, RMSE / max abs error vs stochastic "
           f"{args.reference_spp} spp)", "",
           "| " + " | ".join([xlabel] + [label(m, o) for m, o in METHODS]) + " | clipped auto subframes (max/tile, capped tiles) |",
           "|" + "---|" * (len(METHODS) + 2)]
    series = {label(m, o): [] for m, o in METHODS}
    for tag, x, sweep_o in points():
        print(f"{name} {tag}", flush=True)
        job = dict(base, **sweep_o)
        ref = benchlib.reference_image(clipblur, config, job, args.reference_spp, args.cache, args.threads)
        cells, auto_sub = [str(x)], ""
        for method, o in METHODS:
            image = out / "renders" / name / f"{tag}_{method}_{next(iter(o.values()))}.exr"
            stats = benchlib.render(clipblur, config, dict(job, **{"render.method": method}, **o), image, args.threads)
            err = benchlib.image_error(ref, image)
            counts = stats.get("counts", {})
            if method == "clipped" and o["render.subframes"] == "auto":
                auto_sub = f"{counts.get('subframes_max_per_tile', '')}, {counts.get('capped_tiles', '')}"
            rows.append({"sweep": name, "x": x, "method": label(method, o), "seconds": stats["seconds"]["total"],
                         "rmse": err["rmse"], "max_abs": err["max_abs"],
                         "near_clipped": counts.get("open_near_clipped", 0) + counts.get("close_near_clipped", 0)
                         + counts.get("reclip_near_clipped", 0),
                         "max_time_steps": counts.get("max_time_steps", ""), "mixed": "", "overlap_stddev": ""})
            cells.append(f"{err['rmse']:.4f} / {err['max_abs']:.3f}")
            series[label(method, o)].append((x, err["rmse"], ""))
        md.append("| " + " | ".join(cells + [auto_sub]) + " |")
    md.append("")
    benchlib.gnuplot_chart(out / "charts" / name, f"{name}: error vs stress", list(series.items()), xlabel,
                           "RMSE vs reference", logx=False, logy=True)


def observed_order(points):
    """Convergence order from the last doubling whose errors both stand clear of round-off (1e-11)."""
    order = None
    for (s0, e0), (s1, e1) in zip(points, points[1:]):
        if e0 > 1e-11 and e1 > 1e-11 and math.isfinite(e0) and math.isfinite(e1):
            order = math.log(e0 / e1) / math.log(s1 / s0)
    return order


def ode_sweep(clipblur, out, rows, md):
    """Paper eq. 11-12 integrated with Euler and RK4 against the exact projection, from
    `clipblur paths --convergence` (largest image-plane error at f = 1 over the Table 1 vertex grid)."""
    print("ode_steps", flush=True)
    cmd = [clipblur, "paths", "--convergence"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise benchlib.BenchError(f"{' '.join(cmd)} failed ({r.returncode}): {r.stderr.strip()}")
    series = {}
    for row in csv.DictReader(io.StringIO(r.stdout)):
        series.setdefault((row["case"], row["method"]), []).append((int(row["steps"]), float(row["error"])))
    shown = (1, 4, 16, 64, 256, 4096)
    md += ["### ode_steps (`clipblur paths --convergence`: largest image-plane error at f = 1, Table 1 grid)", "",
           "| case | method | " + " | ".join(f"{s} steps" for s in shown) + " | observed order |",
           "|" + "---|" * (len(shown) + 3)]
    for (case, method), pts in series.items():
        errors = dict(pts)
        order = observed_order(pts)
        md.append(f"| {case} | {method} | " + " | ".join(f"{errors.get(s, float('nan')):.2e}" for s in shown)
                  + f" | {'-' if order is None else f'{order:.2f}'} |")
        for s, e in pts:
            rows.append({"sweep": "ode_steps", "x": s, "method": f"{case} {method}", "seconds": "", "rmse": e,
                         "max_abs": e, "near_clipped": "", "max_time_steps": "", "mixed": "", "overlap_stddev": ""})
    md.append("")
    benchlib.gnuplot_chart(out / "charts" / "ode_steps", "ODE (eq. 11-12) error at f = 1 vs steps",
                           [(f"{c} {m}", [(s, e, "") for s, e in pts]) for (c, m), pts in series.items()],
                           "steps over the frame", "max image-plane error", logx=True, logy=True)


def overlap_window(width, height):
    """Pixels that coincident.yaml's two quads overlap during the whole shutter: x in [-0.5, 0.5] and
    y in [-2, 2] at range 10 (red spans [-3.5, 0.5] + t, green [-1.5, 2.5] + t), shrunk by 30 % in x and
    10 % in y to keep clear of the edges' blur. Returns oiiotool geometry WxH+X+Y."""
    px_per_unit = 0.5 * height / math.tan(math.radians(20.0)) / 10.0
    half_w = max(1, int(0.35 * px_per_unit))
    half_h = max(1, int(1.8 * px_per_unit))
    return f"{2 * half_w}x{2 * half_h}+{width // 2 - half_w}+{height // 2 - half_h}"


def window_stddev(image, geom):
    """Largest per-channel (R, G, B) standard deviation of the pixels in `geom`: zero when one rule decides
    the tie the same way everywhere, positive for noise or for a winner that changes across the window
    (per pixel: speckle; along a line: Embree's BVH order deciding ties differently in two regions)."""
    cmd = ["oiiotool", str(image), "--ch", "R,G,B", "--cut", geom, "--printstats"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    m = re.search(r"Stats StdDev:\s*([-0-9.eE+naif ]+)", r.stdout)
    if r.returncode != 0 or not m:
        raise benchlib.BenchError(f"{' '.join(cmd)}: no statistics ({r.stderr.strip()})")
    return max(float(v) for v in m.group(1).split())


def window_mean(image, geom):
    cmd = ["oiiotool", str(image), "--ch", "R,G,B", "--cut", geom, "--printstats"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    m = re.search(r"Stats Avg:\s*([-0-9.eE+naif ]+)", r.stdout)
    if r.returncode != 0 or not m:
        raise benchlib.BenchError(f"{' '.join(cmd)}: no statistics ({r.stderr.strip()})")
    return [float(v) for v in m.group(1).split()[:3]]


def coincident_sweep(clipblur, args, base, out, rows, md):
    """Two coplanar quads overlapping at one range: each method's error, and the spread of pixel values
    inside the always-overlapping window (speckle), with the clipped renderer's mixed-fragment counts."""
    print("coincident", flush=True)
    config = BENCH / "coincident.yaml"
    geom = overlap_window(args.width, args.height)
    ref = benchlib.reference_image(clipblur, config, base, args.reference_spp, args.cache, args.threads)
    ref_mean = window_mean(ref, geom)
    md += [f"### coincident (coincident.yaml, {args.width}x{args.height}; overlap window {geom})", "",
           f"Reference (stochastic {args.reference_spp} spp) in the window: mean RGB "
           f"{', '.join(f'{v:.3f}' for v in ref_mean)}, std dev {window_stddev(ref, geom):.4f}.", "",
           "| method | RMSE / max abs vs reference | window mean RGB | window std dev (mixed winners) "
           "| reclip_mixed_fragments | seconds |", "|---|---|---|---|---|---|"]
    bars = []
    for method, o in METHODS:
        image = out / "renders" / "coincident" / f"{method}_{next(iter(o.values()))}.exr"
        stats = benchlib.render(clipblur, config, dict(base, **{"render.method": method}, **o), image, args.threads)
        err = benchlib.image_error(ref, image)
        counts = stats.get("counts", {})
        mixed = counts.get("reclip_mixed_fragments", "")
        sd = window_stddev(image, geom)
        mean = window_mean(image, geom)
        rows.append({"sweep": "coincident", "x": "", "method": label(method, o), "seconds": stats["seconds"]["total"],
                     "rmse": err["rmse"], "max_abs": err["max_abs"], "near_clipped": "", "max_time_steps": "",
                     "mixed": mixed, "overlap_stddev": sd})
        md.append(f"| {label(method, o)} | {err['rmse']:.4f} / {err['max_abs']:.3f} | "
                  f"{', '.join(f'{v:.3f}' for v in mean)} | {sd:.4f} | {mixed} | {stats['seconds']['total']:.2f} |")
        bars.append((label(method, o), (sd, mean[1] / max(sum(mean[:2]), 1e-12))))
    md.append("")
    bar_chart(out / "charts" / "coincident", "coincident quads, pixels where they tie (window of the whole shutter)",
              bars, ["std dev of R,G,B (0: one winner everywhere)", "green share of the window mean"])


def bar_chart(path_stem, title, bars, columns):
    """Grouped bars, one group per label: bars is [(label, (value per column))]. PNG and SVG."""
    stem = Path(path_stem)
    stem.parent.mkdir(parents=True, exist_ok=True)
    dat = stem.with_suffix(".dat")
    with open(dat, "w") as f:
        for name, values in bars:
            f.write(f'"{name}" ' + " ".join(f"{v:.6g}" for v in values) + "\n")
    plots = [f"'{dat}' using {i + 2}:xtic(1) title '{c}'" for i, c in enumerate(columns)]
    script = "\n".join(["set termoption noenhanced", f"set title '{title}'", "set style data histograms",
                        "set style fill solid 0.8 border -1", "set yrange [0:1]", "set grid ytics",
                        "set xtics rotate by -30", "set key top left", "plot " + ", ".join(plots)]) + "\n"
    for term, ext in (("pngcairo size 800,450", ".png"), ("svg size 800,450", ".svg")):
        full = f"set terminal {term}\nset output '{stem.with_suffix(ext)}'\n" + script
        r = subprocess.run(["gnuplot"], input=full, capture_output=True, text=True)
        if r.returncode != 0:
            raise benchlib.BenchError(f"gnuplot failed for {stem.with_suffix(ext)}: {r.stderr.strip()}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--width", type=int, default=160)
    ap.add_argument("--height", type=int, default=90)
    ap.add_argument("--reference-spp", type=int, default=1024)
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--sweeps", default=",".join(SWEEPS), help=f"comma-separated subset of {','.join(SWEEPS)}")
    ap.add_argument("--out", default=str(benchlib.REPO / "build" / "bench" / "stability"))
    ap.add_argument("--cache", default=str(benchlib.REPO / "build" / "bench" / "reference_cache"))
    ap.add_argument("--clipblur")
    args = ap.parse_args()
    out = Path(args.out)
    rows, md = [], []
    try:
        clipblur = benchlib.find_clipblur(args.clipblur)
        benchlib.require_tool("oiiotool")
        benchlib.require_tool("gnuplot")
        base = {"film.width": args.width, "film.height": args.height, "output.half": "false"}
        for name in args.sweeps.split(","):
            if name in RENDER_SWEEPS:
                render_sweep(clipblur, args, base, name, out, rows, md)
            elif name == "ode_steps":
                ode_sweep(clipblur, out, rows, md)
            elif name == "coincident":
                coincident_sweep(clipblur, args, base, out, rows, md)
            else:
                raise benchlib.BenchError(f"unknown sweep '{name}' (known: {', '.join(SWEEPS)})")

        topo = BENCH / "refused" / "topology_change.yaml"
        r = subprocess.run([clipblur, "validate", str(topo)], capture_output=True, text=True)
        md += ["### topology change between deformation keys", "",
               f"`clipblur validate configs/bench/refused/topology_change.yaml` exit {r.returncode}:", "",
               "    " + (r.stderr.strip() or r.stdout.strip()).replace("\n", "\n    "), ""]
        md = [f"git {benchlib.git_hash()[:12]}, {benchlib.machine_description()}", ""] + md
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
