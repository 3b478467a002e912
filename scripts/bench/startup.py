#!/usr/bin/env python3
"""Start-up cost of clipblur's commands (issue 21: `--version`, `validate` and a 16x9 render each under
50 ms): wall-clock median and minimum over repeated runs, and with --callgrind the instruction count of
one run of each (valgrind; repeatable whatever else the machine does). For the render it also prints
the render's own `seconds.total` from its stats, so what is not rendering shows as the difference."""

import argparse
import json
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import benchlib  # noqa: E402


def commands(binary, job, out):
    tiny = ["--set", "film.width=16", "--set", "film.height=9", "--progress", "none", "--out", str(out)]
    return {
        "--version": [binary, "--version"],
        "validate": [binary, "validate", job],
        "render 16x9": [binary, "render", job, *tiny],
    }


def wall_ms(cmd, runs):
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
        times.append((time.perf_counter() - start) * 1e3)
    return statistics.median(times), min(times)


def instructions(cmd):
    with tempfile.TemporaryDirectory() as d:
        out = subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={d}/cg.out", *cmd],
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, check=True).stderr
    for line in out.splitlines():
        if "refs:" in line:
            return int(line.split("refs:")[1].replace(",", ""))
    raise benchlib.BenchError("valgrind printed no instruction count")


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--clipblur")
    ap.add_argument("--job", default=str(benchlib.REPO / "configs" / "default.yaml"))
    ap.add_argument("--runs", type=int, default=15)
    ap.add_argument("--callgrind", action="store_true", help="also count instructions (valgrind)")
    args = ap.parse_args()
    binary = benchlib.find_clipblur(args.clipblur)
    with tempfile.TemporaryDirectory() as d:
        out = Path(d) / "tiny.exr"
        print("| command | wall median ms | wall min ms |" + (" instructions |" if args.callgrind else ""))
        print("|---|---|---|" + ("---|" if args.callgrind else ""))
        for name, cmd in commands(binary, args.job, out).items():
            median, least = wall_ms(cmd, args.runs)
            if name.startswith("render"):
                stats = json.loads(out.with_suffix(".stats.json").read_text())
            row = f"| `{name}` | {median:.1f} | {least:.1f} |"
            if args.callgrind:
                row += f" {instructions(cmd) / 1e6:.1f} M |"
            print(row)
        print(f"\nrender 16x9: the render's own seconds.total {stats['seconds']['total'] * 1e3:.1f} ms "
              "(last timed run)")


if __name__ == "__main__":
    try:
        main()
    except (benchlib.BenchError, subprocess.CalledProcessError) as e:
        sys.exit(f"startup.py: {e}")
