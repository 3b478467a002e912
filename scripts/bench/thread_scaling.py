#!/usr/bin/env python3
"""Thread scaling of one render: runs the job at each thread count in turn (1, 2, 1, 2, ... so a change in
the machine's load hits every count alike), and prints each stage's median seconds (`seconds.*` of the
stats file, plus the wall clock of the whole process) and its speed-up over one thread.

    scripts/bench/thread_scaling.py [job] [--width 640 --height 360] [--threads 1,2] [--runs 3]
        [--clipblur build/clipblur[,/tmp/before/clipblur ...]] [--set key=value ...]

Several binaries (comma-separated) take turns too, for a before/after comparison under the same load.
The job defaults to the paper's spin_pan (configs/bench/table1_spin_pan.yaml) at 640x360. For two
thread counts p = 1 and q the last column is the serial time Amdahl's law infers from the medians,
s = (q T_q - T_1) / (q - 1): an estimate that holds only when the machine has q idle cores, so the
load average before and after is printed too. Python standard library only.
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import benchlib  # noqa: E402

STAGES = ["scene_build", "hidden_probe", "frame_fragments", "motion_plan", "tiles", "segments", "serial", "total"]


def render_once(clipblur, job, overrides, threads, out_dir):
    image = out_dir / f"t{threads}.exr"
    stats = out_dir / f"t{threads}.json"
    cmd = [clipblur, "render", str(job), "--frames", "0", "--threads", str(threads), "--out", str(image),
           "--stats", str(stats), "--progress", "none"] + benchlib.set_args(overrides)
    start = time.monotonic()
    r = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.monotonic() - start
    if r.returncode != 0:
        raise benchlib.BenchError(f"render failed ({r.returncode}): {' '.join(cmd)}\n{r.stderr.strip()}")
    seconds = json.loads(stats.read_text())["seconds"]
    seconds["wall"] = wall
    return seconds


def print_table(runs, counts):
    """Per stage: the median seconds at each thread count, the speed-ups over the first count and, when
    that is 1, the serial seconds Amdahl's law infers from the first and last."""
    base, last = counts[0], counts[-1]
    amdahl = base == 1 and len(counts) > 1
    header = f"{'stage':<16}" + "".join(f"{str(t) + ' thr s':>11}" for t in counts)
    header += "".join(f"{'x' + str(t):>8}" for t in counts[1:])
    print(header + (f"{'Amdahl serial s':>17}" if amdahl else ""))
    for stage in STAGES + ["cpu", "wall"]:
        if not all(stage in r for t in counts for r in runs[t]):
            continue
        med = {t: statistics.median(r[stage] for r in runs[t]) for t in counts}
        line = f"{stage:<16}" + "".join(f"{med[t]:>11.3f}" for t in counts)
        line += "".join(f"{(med[base] / med[t] if med[t] > 0 else float('nan')):>8.2f}" for t in counts[1:])
        if amdahl and stage not in ("cpu", "serial"):
            line += f"{(last * med[last] - med[base]) / (last - 1):>17.3f}"
        print(line)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("job", nargs="?", default=str(benchlib.REPO / "configs" / "bench" / "table1_spin_pan.yaml"))
    ap.add_argument("--width", type=int, default=640)
    ap.add_argument("--height", type=int, default=360)
    ap.add_argument("--threads", default="1,2", help="comma-separated thread counts; the first is the baseline")
    ap.add_argument("--runs", type=int, default=3, help="renders per thread count (medians are reported)")
    ap.add_argument("--clipblur", default=None)
    ap.add_argument("--set", action="append", default=[], metavar="KEY=VALUE", help="more job overrides")
    args = ap.parse_args()
    binaries = [benchlib.find_clipblur(c) for c in args.clipblur.split(",")] if args.clipblur else [
        benchlib.find_clipblur()]
    counts = [int(t) for t in args.threads.split(",") if t]
    overrides = {"film.width": args.width, "film.height": args.height, "output.png_preview": "false"}
    for kv in args.set:
        key, _, value = kv.partition("=")
        overrides[key] = value
    load_before = os.getloadavg()[0]
    runs = {(b, t): [] for b in binaries for t in counts}
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(args.runs):
            for b in binaries:
                for t in counts:
                    runs[(b, t)].append(render_once(b, args.job, overrides, t, Path(tmp)))
    load_after = os.getloadavg()[0]

    print(f"{Path(args.job).name} at {args.width}x{args.height}, {args.runs} runs per binary and count")
    print(f"load average (1 min): {load_before:.2f} before, {load_after:.2f} after; {os.cpu_count()} cores")
    for b in binaries:
        print(f"\n{b}")
        print_table({t: runs[(b, t)] for t in counts}, counts)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except benchlib.BenchError as e:
        print(f"error: {e}", file=sys.stderr)
        sys.exit(1)
