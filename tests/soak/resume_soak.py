#!/usr/bin/env python3
"""Soak: a 240-frame animation rendered with `render --resume`, killed with SIGKILL at seeded random
moments five times and resumed with the same command each time; every EXR must then open and equal an
uninterrupted render's pixels bit for bit (oiiotool --diff with a zero threshold). Issue 24.

Usage: resume_soak.py --clipblur BUILD/clipblur --job configs/default.yaml [--seed N] [--kills K]
"""
import argparse
import random
import subprocess
import sys
import tempfile
import time
from pathlib import Path

FRAMES = 240
# The default job's motion stretched over the whole animation, at a size that keeps a frame cheap.
SETTINGS = ["film.width=24", "film.height=14", "camera.keys.1.time=240", "objects.1.transform.1.time=240",
            "objects.2.transform.1.time=240", "render.subframes=4"]


def command(clipblur, job, folder):
    cmd = [clipblur, "render", job, "--frames", f"0-{FRAMES - 1}", "--out", str(folder / "f.####.exr"),
           "--progress", "none", "--threads", "2", "--resume"]
    for s in SETTINGS:
        cmd += ["--set", s]
    return cmd


def images(folder):
    return sorted(folder.glob("f.*.exr"))


def differing(pairs):
    """Failure messages for the pairs whose pixels differ at all. One oiiotool process diffs them all (it
    goes on after a failing pair): one per pair spent 0.5 s each loading OpenImageIO, 2 minutes here."""
    if not pairs:
        return []
    args = ["oiiotool"]
    for a, b in pairs:
        args += [str(a), str(b), "--fail", "0", "--diff", "--pop", "--pop"]
    diff = subprocess.run(args, capture_output=True, text=True)
    reports = diff.stdout.split("Computing diff of ")[1:]
    if len(reports) != len(pairs):
        return [f"oiiotool reported {len(reports)} of {len(pairs)} diffs (exit {diff.returncode}):\n"
                f"{diff.stdout}{diff.stderr}"]
    failures = [f"{b.name} differs from the uninterrupted render:\n{report}"
                for (a, b), report in zip(pairs, reports) if "FAILURE" in report]
    if diff.returncode != 0 and not failures:
        failures.append(f"oiiotool failed (exit {diff.returncode}):\n{diff.stderr}")
    return failures


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--clipblur", required=True)
    ap.add_argument("--job", required=True)
    ap.add_argument("--seed", type=int, default=24)
    ap.add_argument("--kills", type=int, default=5)
    args = ap.parse_args()
    rng = random.Random(args.seed)
    with tempfile.TemporaryDirectory(prefix="clipblur_soak_") as tmp:
        whole, killed = Path(tmp) / "whole", Path(tmp) / "killed"
        whole.mkdir()
        killed.mkdir()
        start = time.monotonic()
        subprocess.run(command(args.clipblur, args.job, whole), check=True, stdout=subprocess.DEVNULL)
        full = time.monotonic() - start
        print(f"uninterrupted: {len(images(whole))} frames in {full:.1f} s")

        kills = 0
        for k in range(args.kills):
            # Within the first half of what is left, so each run is cut short while it still renders.
            left = full * (FRAMES - len(images(killed))) / FRAMES
            delay = rng.uniform(0.05, max(0.1, 0.5 * left))
            proc = subprocess.Popen(command(args.clipblur, args.job, killed), stdout=subprocess.DEVNULL)
            time.sleep(delay)
            if proc.poll() is None:
                proc.kill()
                kills += 1
            proc.wait()
            print(f"run {k + 1}: SIGKILL after {delay:.2f} s, {len(images(killed))} frames on disk")
        final = subprocess.run(command(args.clipblur, args.job, killed), check=True, capture_output=True, text=True)
        skipped = final.stdout.count("complete, skipped")
        print(f"resumed: {skipped} frames skipped, {kills} runs killed")

        failures = []
        if kills < args.kills:
            failures.append(f"only {kills} of {args.kills} runs were still rendering when killed")
        if skipped == 0:
            failures.append("the final run skipped no frame: nothing was resumed")
        if [p.name for p in images(whole)] != [p.name for p in images(killed)] or len(images(whole)) != FRAMES:
            failures.append(f"frames differ: {len(images(whole))} uninterrupted, {len(images(killed))} resumed")
        failures += differing(list(zip(images(whole), images(killed))))
        for f in failures:
            print("FAIL:", f, file=sys.stderr)
        return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
