#!/usr/bin/env python3
"""Issue 5's benchmark: clipped against stochastic at equal error, measured in one run, with no
converged reference. Per scene (default: the five Table 1 moves, the spinning propeller and the sweep
disocclusion scene, at 1280x720):

  1. stochastic at 256 spp twice, with seeds s1 and s2: the time, and e256, the error one such render
     has against the exact image;
  2. per clipped variant (--methods): `clipped`, the paper's point subframes on the ladder 1, 2, 4, ...
     subframes, `sweep`, sweep integration with rung r re-clips and positions 8/r px apart, and
     `sweep_spacing`, sweep integration with `auto` re-clips and positions 8/r px apart,
     `auto_spacing`, time_integration auto (per segment points or sweep) at that spacing, and
     `auto_exact`, the same with sweep_time exact (time integrated exactly between positions); each
     until its error is at most e256 (or --max-rung), and `auto`: time, subframes, fragments per
     subframe, peak memory and the error e_c of each rung. Where sweep_spacing's first rung already
     reaches e256 it also goes coarser (r = 1/2, 1/4, 1/8) until a rung does not, so that the time at
     e256 is interpolated rather than bounded by the first rung's;
  3. the strongest peer (issue 19): the plain Embree loop (scripts/bench/peers.py) at 256 spp, its
     error e_l against sbar as for a clipped render below (it is independent of s1 and s2), and its
     time scaled to e256 as t_l (e_l / e256)^2 (error ~ 1/sqrt(samples)); the peer is the faster of
     it and stochastic at e256;
  4. each variant's time at e256, interpolated in log-log along its ladder, and the ratio
     (the peer's time at e256) / (that time), beside the ratio to stochastic; the goal is at least 5;
     and the headline of issue 21: the ladders go on until they reach e1024 = e256 / 2, the error of
     1024-spp ray casting, and the whole `clipblur render` process's wall clock (start-up and image
     writing included) is interpolated to e256 and e1024 and set against the peer's time there (its
     time at e256, times 4 at e1024); the goals are 10 and 30;
  5. with --threads-check on: each variant's rung that reaches e256 (or `auto`) and stochastic 256 spp
     at 1 and at 2 threads, the clipped ones --thread-repeats times alternating (the fastest of each
     counts); the speed-up t1 / t2 (goal for clipped: at least 1.8), and whether all the images are
     bit-identical (they must be: random streams never depend on the thread count).

    scripts/bench/equal_error.py                                   # all seven scenes at 1280x720
    scripts/bench/equal_error.py --scenes table1_spin,sweep --width 160 --height 90 --threads-check off

Writes results.csv (one row per render), summary.md and run.json under --out
(build/bench/equal_error).

The statistics. Errors are RMS over the R, G and B values of all pixels (oiiotool --diff with --ch
R,G,B: the root of the mean squared difference over every channel of every pixel), as in
speed_accuracy.py. Let I be the exact motion-blurred frame and i run over the N values of the image.

  Stochastic: s_k = I + n_k (k = 1, 2), with E[n_k] = 0 (the estimator is unbiased), Var(n_k,i) =
  sigma_i^2 for both seeds, and n_1, n_2 independent (different seeds give independent streams). The
  error of one 256 spp render is E256^2 = E[mean_i (s_k,i - I_i)^2] = mean_i sigma_i^2.
  With d = s1 - s2 = n_1 - n_2: E[d_i^2] = 2 sigma_i^2, so
      e256^2 = mean(d^2) / 2 = rmse(s1, s2)^2 / 2
  estimates E256^2 without bias, and needs no reference.

  Clipped: c = I + b is deterministic (b its bias: subframe sampling, coverage), independent of n_k.
  Against the mean of the two stochastic renders, sbar = I + (n_1 + n_2) / 2:
      E[(c_i - sbar_i)^2] = b_i^2 - b_i E[n_1,i + n_2,i] + E[(n_1,i + n_2,i)^2] / 4 = b_i^2 + sigma_i^2 / 2,
  so the error of clipped, e_c^2 = mean(b^2), is estimated without bias by
      e_c^2 = mean((c - sbar)^2) - e256^2 / 2 = rmse(c, sbar)^2 - e256^2 / 2,
  clamped at 0. Its noise: it is the mean of q_i = (c_i - sbar_i)^2 - d_i^2 / 4. Pixels are
  independent (streams derive from seed, frame, pixel and sample), the channels of one pixel are not,
  so the standard error is SE = std(q_p) / sqrt(P) over the P pixels, q_p the mean of q over a
  pixel's R, G, B. An estimate below 2 SE cannot be told from 0: such a rung is marked "within noise"
  and its error reported as the bound sqrt(max(e_c^2, 0) + 2 SE). The same holds for e256^2 with
  q_p = mean over R, G, B of d^2 / 2; its relative SE is printed beside it.
"""

import argparse
import csv
import datetime
import json
import math
import re
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import benchlib  # noqa: E402
import peers  # noqa: E402

DEFAULT_SCENES = ["table1_spin", "table1_pan", "table1_spin_pan", "table1_recede", "table1_recede_spin_pan",
                  "propeller", "sweep"]
SPP = 256
RATIO_GOAL = 5.0
THREAD_GOAL = 1.8
# The clipped variants the ladders run: the paper's point subframes (rung = subframes) and sweep
# integration (rung = re-clips, with positions benchlib.SWEEP_SPACING_1 / rung pixels apart).
SWEEP_SPACING_MIN = 0.01  # px, render.sweep_spacing's lower bound (docs/config.md)
COARSEST_SPACING_RUNG = 1 / 8  # sweep_spacing below rung 1: positions up to 64 px apart
METHODS = {"clipped": lambda rung: benchlib.ladder_overrides("clipped", rung), "sweep": benchlib.sweep_overrides,
           "sweep_spacing": benchlib.sweep_spacing_overrides, "auto_spacing": benchlib.auto_spacing_overrides,
           "auto_exact": benchlib.auto_exact_overrides}
# Both seeds differ from benchlib.REFERENCE_SEED and from each other: independent sample streams.
DEFAULT_SEEDS = (1001, 2002)
LOOP_SEED = 3003  # the plain loop's own stream, independent of the pair's

# The peer's sample counts whose errors the clipped ladders must reach (issue 21): e_N = e256 sqrt(256 / N),
# at the peer's time at e256 times N / 256 (error ~ 1/sqrt(samples)).
LEVELS = (256, 1024)
LEVEL_GOALS = {256: 10.0, 1024: 30.0}

CSV_FIELDS = ["scene", "role", "method", "param", "seed", "threads", "seconds", "wall_seconds", "subframes_total",
              "subframes_max_per_tile", "reclip_fragments", "fragments_per_subframe", "peak_memory_mb",
              "error", "error_se", "within_noise", "identical_across_threads", "width", "height", "image"]


def rgb(path):
    return [str(path), "--ch", "R,G,B"]


def pixel_mean_stats(expression, scale):
    """Mean and population standard deviation over pixels of the per-pixel mean of an RGB expression
    (oiiotool stack arguments). --printstats prints six decimals, so the values are first scaled by
    `scale` to be of order 1; the result is divided back."""
    cmd = ["oiiotool", "--no-autopremult"] + expression + ["--chsum", "--mulc", repr(scale / 3.0), "--printstats"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    out = r.stdout + r.stderr
    avg = re.search(r"Stats Avg:\s*([-0-9.eE+naif]+)", out)
    std = re.search(r"Stats StdDev:\s*([-0-9.eE+naif]+)", out)
    if r.returncode != 0 or not avg or not std:
        raise benchlib.BenchError(f"oiiotool --printstats failed: {' '.join(cmd)}\n{out.strip()}")
    return float(avg.group(1)) / scale, float(std.group(1)) / scale


class StochasticPair:
    """The two 256 spp renders of one scene, their mean and the noise level e256."""

    def __init__(self, s1, s2, sbar, pixels):
        self.s1, self.s2, self.sbar, self.pixels = s1, s2, sbar, pixels
        self.e256 = benchlib.image_error(s1, s2)["rmse"] / math.sqrt(2.0)
        self.e256_sq_se = 0.0
        if self.e256 > 0:
            _, std = pixel_mean_stats(rgb(s1) + rgb(s2) + ["--sub", "--dup", "--mul", "--mulc", "0.5"],
                                      1.0 / self.e256 ** 2)
            self.e256_sq_se = std / math.sqrt(pixels)

    def clipped_error(self, image):
        """(e_c, SE of e_c^2, within_noise) for a deterministic render, as in the module docstring."""
        raw = benchlib.image_error(self.sbar, image)["rmse"] ** 2 - self.e256 ** 2 / 2.0
        scale = 1.0 / self.e256 ** 2 if self.e256 > 0 else 1.0
        q = (rgb(image) + [str(self.sbar), "--sub", "--dup", "--mul"] + rgb(self.s1) + rgb(self.s2)
             + ["--sub", "--dup", "--mul", "--mulc", "0.25", "--sub"])
        _, std = pixel_mean_stats(q, scale)
        se = std / math.sqrt(self.pixels)
        if raw < 2.0 * se:
            return math.sqrt(max(raw, 0.0) + 2.0 * se), se, True
        return math.sqrt(raw), se, False


def row(scene, role, method, param, seed, threads, stats, args, image, error="", error_se="", within_noise=""):
    counts = stats.get("counts", {})
    sub_total = counts.get("subframes_total", "")
    fragments = counts.get("reclip_fragments", "")
    per_subframe = fragments / sub_total if isinstance(sub_total, int) and sub_total > 0 and fragments != "" else ""
    return {"scene": scene, "role": role, "method": method, "param": param, "seed": seed,
            "threads": stats.get("threads", threads), "seconds": stats["seconds"]["total"],
            "wall_seconds": stats["process_wall_seconds"],
            "subframes_total": sub_total, "subframes_max_per_tile": counts.get("subframes_max_per_tile", ""),
            "reclip_fragments": fragments, "fragments_per_subframe": per_subframe,
            "peak_memory_mb": stats.get("peak_memory_bytes", 0) / 2 ** 20, "error": error, "error_se": error_se,
            "within_noise": within_noise, "identical_across_threads": "", "width": args.width,
            "height": args.height, "image": str(image)}


def measure_scene(clipblur, scene, args, out, log=print):
    """All renders of one scene; returns (rows, result) with result the figures of the summary."""
    # A scene is a name under configs/bench, or a job's path from the repository's root (configs/shot.yaml).
    config = benchlib.REPO / scene if scene.endswith(".yaml") else benchlib.REPO / "configs" / "bench" / f"{scene}.yaml"
    if not config.is_file():
        raise benchlib.BenchError(f"no bench scene {config}")
    base = benchlib.base_overrides(args.width, args.height)
    folder = out / "renders" / (Path(scene).stem if scene.endswith(".yaml") else scene)
    rows = []

    images = []
    for k, seed in enumerate(args.seeds, 1):
        o = dict(base, **benchlib.ladder_overrides("stochastic", SPP), **{"render.seed": seed})
        image = folder / f"stochastic_{SPP}_seed{seed}.exr"
        stats = benchlib.render(clipblur, config, o, image, args.threads)
        rows.append(row(scene, f"stochastic_{k}", "stochastic", SPP, seed, args.threads, stats, args, image))
        images.append(image)
    sbar = folder / "stochastic_mean.exr"
    r = subprocess.run(["oiiotool", "--no-autopremult"] + rgb(images[0]) + rgb(images[1])
                       + ["--add", "--mulc", "0.5", "-d", "float", "-o", str(sbar)], capture_output=True, text=True)
    if r.returncode != 0:
        raise benchlib.BenchError(f"oiiotool could not average {images}: {r.stderr.strip()}")
    pair = StochasticPair(images[0], images[1], sbar, args.width * args.height)
    for rw in rows:
        rw["error"], rw["error_se"], rw["within_noise"] = pair.e256, pair.e256_sq_se, False
    t_stochastic = sum(rw["seconds"] for rw in rows) / len(rows)
    log(f"  stochastic {SPP} spp  {rows[0]['seconds']:.3f} s, {rows[1]['seconds']:.3f} s  "
        f"e256 {pair.e256:.4g} (SE of e256^2 {pair.e256_sq_se / pair.e256 ** 2 if pair.e256 else 0:.1%})")
    # The strongest peer (issue 19): the plain Embree loop at 256 spp, its time scaled to e256 by
    # error ~ 1/sqrt(samples), against clipblur's stochastic; ratios are against the faster of the two.
    loop_image = folder / f"plain_loop_{SPP}.exr"
    t_loop = peers.plain_loop(peers.plain_loop_binary(clipblur), config, SPP, LOOP_SEED, loop_image, args.threads,
                              (args.width, args.height))
    e_loop, _, _ = pair.clipped_error(loop_image)
    t_loop_e256 = t_loop * (e_loop / pair.e256) ** 2 if pair.e256 > 0 else t_loop
    peer, t_peer = ("plain loop", t_loop_e256) if t_loop_e256 < t_stochastic else ("stochastic", t_stochastic)
    log(f"  plain loop {SPP} spp  {t_loop:.3f} s  error {e_loop:.4g}: {t_loop_e256:.3f} s at e256; peer: {peer}")

    rungs = []
    n = 1
    while n <= args.max_rung:
        rungs.append(n)
        n *= 2
    result = {"scene": scene, "t_stochastic": t_stochastic, "e256": pair.e256, "e256_sq_se": pair.e256_sq_se,
              "t_loop": t_loop, "e_loop": e_loop, "t_loop_e256": t_loop_e256, "peer": peer, "t_peer": t_peer}
    e_finest = level_error(pair.e256, max(LEVELS))
    for method in args.methods:
        overrides = METHODS[method]

        def run(rung):
            """Renders one rung and returns its error against the pair."""
            o = dict(base, **overrides(rung))
            image = folder / f"{method}_{rung}.exr"
            stats = benchlib.render(clipblur, config, o, image, args.threads)
            e, se, noise = pair.clipped_error(image)
            rw = row(scene, method, "clipped", rung, "", args.threads, stats, args, image, e, se, noise)
            rows.append(rw)
            log(f"  {method} {str(rung):>5s}  {rw['seconds']:8.3f} s  subframes {rw['subframes_total']} "
                f"(max/tile {rw['subframes_max_per_tile']})  error {'<= ' if noise else ''}{e:.4g}")
            return e

        reaching = None
        finest = None  # the first rung at the finest level's error
        for rung in rungs + (["auto"] if args.auto == "on" else []):
            if rung != "auto" and finest is not None:
                continue
            # The sweep ladders stop where the spacing would fall below what a job may ask for.
            if rung != "auto" and float(overrides(rung).get("render.sweep_spacing", SWEEP_SPACING_MIN)) < SWEEP_SPACING_MIN:
                continue
            e = run(rung)
            if rung != "auto" and e <= pair.e256 and reaching is None:
                reaching = rung
            if rung != "auto" and e <= e_finest:
                finest = rung
        # A first rung already at e256 only bounds the time from above; positions can also be coarser
        # than the first rung's (16, 32, 64 px apart), so go down until a rung is above e256 and the time
        # is interpolated between two rungs like every other scene's.
        if method in ("sweep_spacing", "auto_spacing", "auto_exact") and reaching == rungs[0]:
            rung = rungs[0] / 2
            while rung >= COARSEST_SPACING_RUNG and run(rung) <= pair.e256:
                reaching = rung
                rung /= 2
        ladder = [rw for rw in rows if rw["role"] == method]
        t = benchlib.time_to_reach([(rw["seconds"], rw["error"]) for rw in ladder], pair.e256)
        walls = {n: benchlib.time_to_reach([(rw["wall_seconds"], rw["error"]) for rw in ladder],
                                           level_error(pair.e256, n)) for n in LEVELS}
        result[method] = {"t": t, "ratio": t_peer / t if t else None,
                          "ratio_stochastic": t_stochastic / t if t else None, "reaching": reaching,
                          "best_error": min(rw["error"] for rw in ladder),
                          "auto": next((rw for rw in ladder if rw["param"] == "auto"), None),
                          "wall": {n: {"t": w, "ratio": t_peer * n / SPP / w if w else None} for n, w in walls.items()}}

    if args.threads_check == "on":
        checks = [(m, METHODS[m], result[m]["reaching"] or "auto") for m in args.methods]
        checks.append(("stochastic", lambda p: dict(benchlib.ladder_overrides("stochastic", p),
                                                    **{"render.seed": args.seeds[0]}), SPP))
        for method, overrides, param in checks:
            o = dict(base, **overrides(param))
            # Alternating 1 and 2 threads, the fastest of each: on a shared machine a render is only ever
            # slowed by its neighbours, and one pair of runs swung the speed-up by 0.2 either way.
            repeats = 1 if method == "stochastic" else args.thread_repeats
            timed = {1: [], 2: []}
            for r in range(repeats):
                for threads in (1, 2):
                    image = folder / "threads" / f"{method}_{param}_t{threads}{f'_r{r}' if r else ''}.exr"
                    stats = benchlib.render(clipblur, config, o, image, threads)
                    timed[threads].append(row(scene, f"{method}_threads", method, param,
                                              args.seeds[0] if method == "stochastic" else "", threads, stats, args,
                                              image))
            first = timed[1][0]["image"]
            identical = all(benchlib.image_error(first, rw["image"])["max_abs"] == 0.0
                            for rw in timed[1][1:] + timed[2])
            for rw in timed[1] + timed[2]:
                rw["identical_across_threads"] = identical
                rows.append(rw)
            t1, t2 = (min(rw["seconds"] for rw in timed[t]) for t in (1, 2))
            speedup = t1 / t2
            result[f"{method}_threads"] = {"param": param, "t1": t1, "t2": t2, "repeats": repeats,
                                           "speedup": speedup, "identical": identical}
            log(f"  {method} {param} threads 1 -> 2 (fastest of {repeats}): {t1:.3f} s -> {t2:.3f} s, "
                f"speed-up {speedup:.2f}, images {'identical' if identical else 'DIFFER'}")
    return rows, result


def level_error(e256, spp):
    return e256 * math.sqrt(SPP / spp)


def fmt(x, spec=".3f"):
    return "-" if x is None or x == "" else format(x, spec)


def headline(results):
    """The table docs/performance.md opens with: per scene and ladder, the peer's time at its 256- and
    1024-spp errors, clipblur's whole-process wall clock to the same errors, and the ratios."""
    head = "| scene | ladder | peer |"
    rule = "|---|---|---|"
    for n in LEVELS:
        head += f" e{n} | peer s | clipblur wall s | ratio (goal {LEVEL_GOALS[n]:g}) |"
        rule += "---|---|---|---|"
    lines = [head, rule]
    for r in results:
        for method in METHODS:
            m = r.get(method)
            if not m:
                continue
            cells = f"| {r['scene']} | {method} | {r['peer']} |"
            for n in LEVELS:
                w = m["wall"][n]
                t_cell = f"{w['t']:.2f}" if w["t"] else f"not reached (best {m['best_error']:.3g})"
                ratio = f"**{w['ratio']:.2f}**" if w["ratio"] and w["ratio"] >= LEVEL_GOALS[n] else fmt(w["ratio"], ".2f")
                cells += f" {level_error(r['e256'], n):.3g} | {r['t_peer'] * n / SPP:.2f} | {t_cell} | {ratio} |"
            lines.append(cells)
    return "\n".join(lines) + "\n"


def summarise(results, rows):
    lines = [f"| scene | method | stochastic {SPP} spp s (mean of 2) | e256 | plain loop s at e256 | peer | clipped s at e256 "
             f"| ratio to the peer (goal >= {RATIO_GOAL:g}) | ratio to stochastic "
             "| first rung <= e256 | auto: max subframes/tile | auto s | auto error |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        rel = f" (SE of e256^2 {r['e256_sq_se'] / r['e256'] ** 2:.1%})" if r["e256"] > 0 else ""
        for method in METHODS:
            m = r.get(method)
            if not m:
                continue
            a = m["auto"]
            if m["t"] is None:
                t_cell, ratio_cell, stochastic_cell = f"not reached (best error {m['best_error']:.4g})", "-", "-"
            else:
                ok = "met" if m["ratio"] >= RATIO_GOAL else "not met"
                t_cell, ratio_cell = f"{m['t']:.3f}", f"{m['ratio']:.3g} ({ok})"
                stochastic_cell = f"{m['ratio_stochastic']:.3g}"
            auto_cells = ("- | - | -" if a is None else f"{a['subframes_max_per_tile']} | {a['seconds']:.3f} | "
                          f"{'<= ' if a['within_noise'] else ''}{a['error']:.4g}")
            lines.append(f"| {r['scene']} | {method} | {r['t_stochastic']:.3f} | {r['e256']:.4g}{rel} | "
                         f"{r['t_loop_e256']:.3f} | {r['peer']} | {t_cell} | "
                         f"{ratio_cell} | {stochastic_cell} | {fmt(m['reaching'], '')} | {auto_cells} |")
    text = ("Headline (issue 21): whole-process wall clock against the peer's time scaled to its 256- and "
            "1024-spp errors:\n\n" + headline(results) + "\nEvery ladder (stats seconds.total):\n\n"
            + "\n".join(lines) + "\n")

    if any("stochastic_threads" in r for r in results):
        lines = [f"| scene | method | rung | 1 thread s | 2 threads s | speed-up (goal >= {THREAD_GOAL:g}) | "
                 "images identical |", "|---|---|---|---|---|---|---|"]
        for r in results:
            for method in list(METHODS) + ["stochastic"]:
                c = r.get(f"{method}_threads")
                if not c:
                    continue
                ok = "" if method == "stochastic" else " (met)" if c["speedup"] >= THREAD_GOAL else " (not met)"
                lines.append(f"| {r['scene']} | {method} | {c['param']} | {c['t1']:.3f} | {c['t2']:.3f} | "
                             f"{c['speedup']:.2f}{ok} | {c['identical']} |")
        text += ("\nThread scaling (clipped: the fastest of the repeated renders at each count):\n\n"
                 + "\n".join(lines) + "\n")

    lines = ["| scene | method | param | s | subframes total | max/tile | fragments per subframe | peak MiB | error |",
             "|---|---|---|---|---|---|---|---|---|"]
    for rw in rows:
        if rw["role"] not in ("stochastic_1", "stochastic_2", *METHODS):
            continue
        param = f"{rw['param']} (seed {rw['seed']})" if rw["method"] == "stochastic" else str(rw["param"])
        err = ("e256 " if rw["method"] == "stochastic" else "<= " if rw["within_noise"] else "") + f"{rw['error']:.4g}"
        lines.append(f"| {rw['scene']} | {rw['role'] if rw['method'] != 'stochastic' else 'stochastic'} | {param} | {rw['seconds']:.3f} | {fmt(rw['subframes_total'], '')} | "
                     f"{fmt(rw['subframes_max_per_tile'], '')} | {fmt(rw['fragments_per_subframe'], '.4g')} | "
                     f"{rw['peak_memory_mb']:.0f} | {err} |")
    text += ("\nEvery render (fragments per subframe: reclip_fragments / subframes_total, i.e. per tile and "
             "subframe; peak MiB: the render process's peak resident set; `<=`: within the noise, an upper "
             "bound):\n\n" + "\n".join(lines) + "\n")
    return text


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenes", default=",".join(DEFAULT_SCENES), help="comma-separated scene names from configs/bench, or job paths "
                    "ending in .yaml from the repository's root")
    ap.add_argument("--width", type=int, default=1280)
    ap.add_argument("--height", type=int, default=720)
    ap.add_argument("--seeds", default=",".join(map(str, DEFAULT_SEEDS)), help="the two stochastic seeds, s1,s2")
    ap.add_argument("--max-rung", type=int, default=1024, help="largest fixed subframe count of the clipped ladder")
    ap.add_argument("--methods", default="clipped,sweep",
                    help="clipped variants to ladder: clipped, sweep (re-clips and positions refined together), "
                         "sweep_spacing (auto re-clips, positions refined), "
                         "auto_spacing (time_integration auto, its spacing refined as sweep_spacing's), "
                         "auto_exact (auto_spacing with render.sweep_time exact)")
    ap.add_argument("--auto", choices=("on", "off"), default="on",
                    help="also render each variant at its automatic settings (off where auto is known to be slow)")
    ap.add_argument("--threads", type=int, default=0, help="render threads of the main runs (0: all cores)")
    ap.add_argument("--threads-check", choices=("on", "off"), default="on",
                    help="also time the rung reaching e256 and stochastic at 1 and 2 threads")
    ap.add_argument("--thread-repeats", type=int, default=3,
                    help="clipped renders per thread count in the thread check, the fastest counting (default 3)")
    ap.add_argument("--out", default=str(benchlib.REPO / "build" / "bench" / "equal_error"))
    ap.add_argument("--clipblur", help="path of the clipblur binary (default build/clipblur or $CLIPBLUR)")
    args = ap.parse_args()
    try:
        args.seeds = [int(s) for s in args.seeds.split(",")]
    except ValueError:
        args.seeds = []
    if len(args.seeds) != 2 or args.seeds[0] == args.seeds[1]:
        ap.error("--seeds needs two different integers, e.g. 1001,2002")
    args.methods = [m for m in args.methods.split(",") if m]
    if not args.methods or any(m not in METHODS for m in args.methods):
        ap.error(f"--methods takes a comma-separated subset of {', '.join(METHODS)}")

    try:
        clipblur = benchlib.find_clipblur(args.clipblur)
        benchlib.require_tool("oiiotool")
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        meta = {"date": datetime.datetime.now().isoformat(timespec="seconds"), "git": benchlib.git_hash(),
                "machine": benchlib.machine_description(), "argv": sys.argv[1:], "clipblur": clipblur,
                "width": args.width, "height": args.height, "spp": SPP, "seeds": args.seeds,
                "max_rung": args.max_rung, "threads": args.threads,
                "thread_repeats": args.thread_repeats}
        rows, results = [], []
        for scene in [s for s in args.scenes.split(",") if s]:
            print(f"{scene}:", flush=True)
            scene_rows, result = measure_scene(clipblur, scene, args, out,
                                               log=lambda line: print(line, flush=True))
            rows += scene_rows
            results.append(result)
            # Rewritten after every scene: a long 1280x720 run leaves its finished scenes behind.
            with open(out / "results.csv", "w", newline="") as f:
                w = csv.DictWriter(f, fieldnames=CSV_FIELDS)
                w.writeheader()
                w.writerows(rows)
            summary = summarise(results, rows)
            with open(out / "summary.md", "w") as f:
                f.write(f"Equal-error benchmark, {meta['date']}, git {meta['git'][:12]}, {args.width}x{args.height}, "
                        f"{meta['machine']['nproc']} x {meta['machine']['cpu_model']}\n\n{summary}")
            with open(out / "run.json", "w") as f:
                json.dump(dict(meta, results=[{k: ({kk: vv for kk, vv in v.items() if kk != "auto"} if k in METHODS else v)
                                                for k, v in r.items()} for r in results]),
                          f, indent=2, default=str)
        print("\n" + summary)
        print(f"wrote {out / 'results.csv'}, {out / 'summary.md'}, {out / 'run.json'}")
    except benchlib.BenchError as e:
        print(f"equal_error: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
