#!/usr/bin/env python3
"""Checks that a refactor changed nothing: renders every bench job with two clipblur binaries and
compares the images bit for bit (`oiiotool --diff --fail 0`) and the stats' noise-free counts.

    scripts/bench/bit_identical.py --before /tmp/base/clipblur [--after build/clipblur]
        [--width 320 --height 180] [--only sweep,street] [--skip particles]

Every job runs at the given film size with its own method and settings; the sweep and subframes variants
of each job are both rendered (render.time_integration) so either path is compared. Exit 1 when any
image or count differs.
"""

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import benchlib  # noqa: E402

REPO = benchlib.REPO


def bench_jobs():
    jobs = sorted((REPO / "configs" / "bench").glob("*.yaml"))
    jobs += sorted((REPO / "configs" / "bench" / "many").glob("*.yaml"))
    jobs += sorted((REPO / "configs" / "bench" / "peers").glob("*.yaml"))
    return jobs + [REPO / "configs" / "default.yaml"]


def render(binary, job, overrides, out_dir, name):
    image = out_dir / f"{name}.exr"
    stats = out_dir / f"{name}.json"
    args = [binary, "render", str(job), "--frames", "0", "--out", str(image), "--stats", str(stats),
            "--progress", "none"]
    for o in overrides:
        args += ["--set", o]
    run = subprocess.run(args, capture_output=True, text=True)
    if run.returncode != 0:
        return None, f"exit {run.returncode}: {run.stderr.strip()[:300]}"
    return (image, json.loads(stats.read_text())), None


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--before", required=True)
    ap.add_argument("--after", default=str(REPO / "build" / "clipblur"))
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=180)
    ap.add_argument("--only", default="", help="comma-separated job stems")
    ap.add_argument("--skip", default="", help="comma-separated job stems")
    args = ap.parse_args()
    benchlib.require_tool("oiiotool")
    only = {s for s in args.only.split(",") if s}
    skip = {s for s in args.skip.split(",") if s}
    failures = 0
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp)
        for job in bench_jobs():
            if (only and job.stem not in only) or job.stem in skip:
                continue
            for integration in ("sweep", "subframes"):
                overrides = [f"film.width={args.width}", f"film.height={args.height}",
                             f"render.time_integration={integration}"]
                label = f"{job.parent.name}/{job.stem} {integration}"
                before, err_b = render(args.before, job, overrides, out, "before")
                after, err_a = render(args.after, job, overrides, out, "after")
                if err_b or err_a:
                    same = (err_b is None) == (err_a is None)
                    print(f"{label}: before {err_b or 'ok'} / after {err_a or 'ok'}", flush=True)
                    failures += 0 if same else 1
                    continue
                diff = subprocess.run(["oiiotool", "--diff", "--fail", "0", "--failpercent", "0", str(before[0]),
                                       str(after[0])], capture_output=True, text=True)
                counts_b, counts_a = before[1].get("counts", {}), after[1].get("counts", {})
                changed = sorted(k for k in set(counts_b) | set(counts_a) if counts_b.get(k) != counts_a.get(k))
                ok = diff.returncode == 0 and not changed
                failures += 0 if ok else 1
                t_b = before[1].get("seconds", {}).get("total", 0.0)
                t_a = after[1].get("seconds", {}).get("total", 0.0)
                print(f"{label}: {'identical' if diff.returncode == 0 else 'IMAGES DIFFER'}"
                      f"{'' if not changed else ', counts differ: ' + ', '.join(changed[:8])}"
                      f" ({t_b:.2f} s -> {t_a:.2f} s)", flush=True)
    print(f"{failures} difference(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
