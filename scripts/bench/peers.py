#!/usr/bin/env python3
"""clipblur's stochastic method against its peers at equal samples, in one run: a minimal Embree loop
(tests/bench/plain_embree_loop.cpp, built as build/tests/clipblur_plain_loop) over the same scene, and
Blender Cycles where `--cycles` is given and blender is installed (scripts/bench/cycles_peer.py).

For every scene in configs/bench/peers/: a converged reference (the plain loop at --reference-spp with
its own seed), then each renderer at --spp, alternating, --repeats times, and a markdown table of the
least loop seconds (scene build excluded: the loop's own timer, clipblur's stats `seconds.render`), the
RMSE against the reference (first repeat), and clipblur's ratios to the loop. Goals (issue 19): time
per sample within 1.15x of the loop, RMSE within 1.1x.

    scripts/bench/peers.py [--spp 256] [--width 640 --height 360] [--threads 2] [--scenes spin_pan_checker,...]
                           [--cycles] [--ladder 16,64,256,1024] [--out build/bench/peers]

With --ladder, also one render per renderer and rung and a chart of RMSE against seconds per scene
(<out>/<scene>_<size>_ladder.png/.svg).
"""

import argparse
import json
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import benchlib  # noqa: E402

PEERS = benchlib.REPO / "configs" / "bench" / "peers"
TIME_GOAL = 1.15
ERROR_GOAL = 1.1


def plain_loop_binary(clipblur):
    path = Path(clipblur).parent / "tests" / "clipblur_plain_loop"
    if not path.is_file():
        raise benchlib.BenchError(f"{path} not found: build the release flavour with CLIPBLUR_BENCH=ON")
    return str(path)


def plain_loop(binary, config, spp, seed, image, threads, size):
    cmd = [binary, str(config), "--spp", str(spp), "--seed", str(seed), "--out", str(image), "--threads", str(threads),
           "--set", f"film.width={size[0]}", "--set", f"film.height={size[1]}"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise benchlib.BenchError(f"plain loop failed ({r.returncode}): {' '.join(cmd)}\n{r.stderr.strip()}")
    fields = r.stdout.split()
    return float(fields[fields.index("seconds") + 1])


def clipblur_stochastic(clipblur, config, spp, seed, image, threads, size):
    stats = benchlib.render(clipblur, config, {"render.method": "stochastic", "render.samples": spp, "render.seed": seed,
                                               "film.width": size[0], "film.height": size[1]}, image, threads)
    return stats["seconds"]["render"]


def measure_scene(args, clipblur, loop, config, log):
    size = (args.width, args.height)
    folder = Path(args.out) / f"{config.stem}_{args.width}x{args.height}"
    reference = folder / f"reference_{args.reference_spp}.exr"
    if args.refresh or not reference.is_file():
        log(f"  reference: plain loop at {args.reference_spp} spp")
        folder.mkdir(parents=True, exist_ok=True)
        plain_loop(loop, config, args.reference_spp, benchlib.REFERENCE_SEED, reference, args.threads, size)
    runners = {"plain loop": lambda spp, image: plain_loop(loop, config, spp, 1, image, args.threads, size),
               "clipblur stochastic": lambda spp, image: clipblur_stochastic(clipblur, config, spp, 1, image,
                                                                             args.threads, size)}
    if args.cycles:
        import cycles_peer  # noqa: E402  (only with --cycles: it needs blender)
        runners["Cycles"] = lambda spp, image: cycles_peer.render(config, spp, image, args.threads, size,
                                                                  clipblur=clipblur)

    ladder = {}
    for spp in args.ladder:  # error against time per renderer: the chart (one render per rung)
        for name, run in runners.items():
            image = folder / f"{name.replace(' ', '_')}_ladder_{spp}.exr"
            t = run(spp, image)
            ladder.setdefault(name, []).append((t, benchlib.image_error(reference, image)["rmse"], spp))
    seconds = {name: [] for name in runners}
    errors = {}
    for i in range(args.repeats):
        for name, run in runners.items():  # alternating, so a burst of load hits all of them
            image = folder / f"{name.replace(' ', '_')}_{args.spp}.exr"
            seconds[name].append(run(args.spp, image))
            if i == 0:
                errors[name] = benchlib.image_error(reference, image)["rmse"]
    if ladder:
        benchlib.gnuplot_chart(Path(args.out) / f"{folder.name}_ladder",
                               f"{config.stem} {args.width}x{args.height}: RMSE against time (labels: spp)",
                               list(ladder.items()), "seconds (scene build excluded)", "RMSE")
    return {name: {"seconds": min(s), "all_seconds": s, "rmse": errors[name], "ladder": ladder.get(name, [])}
            for name, s in seconds.items()}


def table(results, spp):
    lines = [f"| scene | renderer, {spp} spp | seconds | RMSE | time / loop (goal <= {TIME_GOAL}) | "
             f"RMSE / loop (goal <= {ERROR_GOAL}) |", "|---|---|---|---|---|---|"]
    for scene, rows in results.items():
        base = rows["plain loop"]
        for name, r in rows.items():
            t = r["seconds"] / base["seconds"]
            e = r["rmse"] / base["rmse"] if base["rmse"] > 0 else float("nan")
            lines.append(f"| {scene} | {name} | {r['seconds']:.3f} | {r['rmse']:.5f} | {t:.2f} | {e:.2f} |")
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--spp", type=int, default=256)
    ap.add_argument("--width", type=int, default=640)
    ap.add_argument("--height", type=int, default=360)
    ap.add_argument("--reference-spp", type=int, default=4096)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--ladder", default="", help="spp rungs for an RMSE-against-time chart, e.g. 16,64,256,1024")
    ap.add_argument("--scenes", help="comma-separated names from configs/bench/peers (default all)")
    ap.add_argument("--cycles", action="store_true", help="also Blender Cycles (scripts/bench/cycles_peer.py)")
    ap.add_argument("--refresh", action="store_true", help="render the references again")
    ap.add_argument("--out", default=str(benchlib.REPO / "build" / "bench" / "peers"))
    ap.add_argument("--clipblur", help="path of the clipblur binary (default build/clipblur or $CLIPBLUR)")
    args = ap.parse_args()
    args.ladder = [int(x) for x in args.ladder.split(",") if x]
    try:
        benchlib.require_tool("oiiotool")
        clipblur = benchlib.find_clipblur(args.clipblur)
        loop = plain_loop_binary(clipblur)
        names = args.scenes.split(",") if args.scenes else sorted(p.stem for p in PEERS.glob("*.yaml"))
        results = {}
        for name in names:
            config = PEERS / f"{name}.yaml"
            if not config.is_file():
                raise benchlib.BenchError(f"no scene {config}")
            print(f"{name}:", flush=True)
            results[name] = measure_scene(args, clipblur, loop, config, lambda m: print(m, flush=True))
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        record = {"git": benchlib.git_hash(), "machine": benchlib.machine_description(), "spp": args.spp,
                  "size": [args.width, args.height], "threads": args.threads, "results": results}
        (out / "peers.json").write_text(json.dumps(record, indent=2) + "\n")
        print(table(results, args.spp))
        print(f"wrote {out / 'peers.json'}")
    except (benchlib.BenchError, RuntimeError) as e:
        print(f"peers: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
