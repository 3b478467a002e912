#!/usr/bin/env python3
"""Peak memory of one render (issue 21: at 1920x1080 with a million triangles, under 1 GiB).

Renders a job (default configs/bench/dense_mesh.yaml, 1,046,528 triangles) at each --sizes entry and
prints the process's peak resident set twice: as the render's stats report it (`peak_memory_bytes`,
getrusage of the process) and as the kernel reports it for the finished child (ru_maxrss), beside the
counts that memory follows (triangles, fragment triangles of both frame sets, tiles) and the seconds.
Memory does not depend on the machine's load, so unlike the timings it is a figure any run reproduces.

    scripts/bench/memory.py                                  # dense_mesh at 1920x1080 (about 10 min)
    scripts/bench/memory.py --sizes 320x180,640x360 --set render.subframes=1
"""

import argparse
import json
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import benchlib  # noqa: E402

GOAL_BYTES = 1 << 30


def render(binary, job, width, height, threads, extra, folder):
    stats_path = folder / f"memory_{width}x{height}.json"
    cmd = [binary, "render", job, "--set", f"film.width={width}", "--set", f"film.height={height}",
           "--out", str(folder / f"memory_{width}x{height}.exr"), "--stats", str(stats_path),
           "--progress", "none", "--threads", str(threads)]
    for setting in extra:
        cmd += ["--set", setting]
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    start = time.monotonic()
    r = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.monotonic() - start
    if r.returncode != 0:
        raise benchlib.BenchError(f"render failed ({r.returncode}): {' '.join(cmd)}\n{r.stderr.strip()}")
    # RUSAGE_CHILDREN holds the largest child so far: only a new maximum is this child's own.
    after = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    stats = json.loads(stats_path.read_text())
    return stats, (after * 1024 if after > before else None), wall


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--clipblur")
    ap.add_argument("--job", default=str(benchlib.REPO / "configs" / "bench" / "dense_mesh.yaml"))
    ap.add_argument("--sizes", default="1920x1080", help="comma-separated WxH film sizes")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--set", action="append", default=[], help="extra key.path=value overrides")
    args = ap.parse_args()
    try:
        binary = benchlib.find_clipblur(args.clipblur)
        sizes = [tuple(int(v) for v in s.split("x")) for s in args.sizes.split(",") if s]
    except ValueError:
        ap.error("--sizes takes WxH entries, e.g. 1920x1080,640x360")
    except benchlib.BenchError as e:
        print(f"memory: {e}", file=sys.stderr)
        return 1
    print(f"{args.job}, {args.threads} threads, overrides {args.set or 'none'}; goal: under "
          f"{GOAL_BYTES / 2 ** 20:.0f} MiB at 1920x1080 with 1M triangles\n")
    print("| film | triangles | fragment triangles (open + close) | tiles | peak MiB (stats) | peak MiB (kernel) "
          "| under the goal | wall s | seconds.total |")
    print("|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory(prefix="clipblur_memory_") as d:
        for width, height in sizes:
            try:
                stats, kernel, wall = render(binary, args.job, width, height, args.threads, args.set, Path(d))
            except benchlib.BenchError as e:
                print(f"memory: {e}", file=sys.stderr)
                return 1
            c = stats.get("counts", {})
            peak = stats.get("peak_memory_bytes", 0)
            kernel_cell = f"{kernel / 2 ** 20:.0f}" if kernel else "-"
            fragments = c.get("open_fragment_triangles", 0) + c.get("close_fragment_triangles", 0)
            print(f"| {width}x{height} | {c.get('triangles', '-')} | {fragments} | {c.get('tiles', '-')} | "
                  f"{peak / 2 ** 20:.0f} | {kernel_cell} | {'yes' if peak < GOAL_BYTES else 'no'} | {wall:.1f} | "
                  f"{stats['seconds']['total']:.1f} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
