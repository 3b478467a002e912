#!/usr/bin/env python3
"""Performance regression gate.

Renders tests/perf/gate_scene.yaml with the clipped method (point subframes and sweep integration)
and with a fixed stochastic baseline, alternating, several times, and checks against
tests/perf/thresholds.json:
  - the RATIOS median(clipped seconds) / median(stochastic seconds) and the same for sweep (all timed
    in this same job, so a slower or busier machine moves both), with the generous slack stored in the
    file;
  - EXACT noise-free counts from the stats (subframes, fragments, candidates, rays), which change
    only when the algorithm does, and must not differ between repeats.

    tests/perf/perf_gate.py --clipblur build/clipblur                # short mode (CI, < 1 min)
    tests/perf/perf_gate.py --clipblur build/clipblur --mode full    # also writes a JSON record
    tests/perf/perf_gate.py --clipblur build/clipblur --update       # rewrite this mode's thresholds

Exit codes: 0 pass, 1 a gate failed, 2 the gate could not run.
"""

import argparse
import datetime
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
SCENE = HERE / "gate_scene.yaml"
THRESHOLDS = HERE / "thresholds.json"

MODES = {
    "short": {"width": 64, "height": 36, "repeats": 3, "samples": 64},
    "full": {"width": 160, "height": 90, "repeats": 3, "samples": 64},
}

# Counts that depend only on the scene and the algorithm, not on timing or thread count.
EXACT_COUNTS = {
    "clipped": ["triangles", "tiles", "segments", "hidden_probe_samples", "hidden_probe_hits", "frame_sets",
                "still_tiles", "subframes_total", "subframes_max_per_tile", "capped_tiles",
                "measured_fragment_paths", "propagated_triangles", "reclip_fragments", "reclip_mixed_fragments",
                "reclip_near_clipped", "open_rays", "open_candidates", "open_fragments", "open_shaded_pieces",
                "close_rays", "close_candidates", "close_fragments", "close_shaded_pieces"],
    "sweep": ["subframes_total", "subframes_max_per_tile", "reclip_fragments", "sweep_positions",
              "sweep_spilled_pixels", "sweep_unswept_fragments"],
    "stochastic": ["triangles", "rays", "primary_rays", "samples", "max_time_steps", "vertex_evaluations"],
}
# What each gate method renders, on top of the scene's own settings.
METHOD_SETTINGS = {"clipped": ["render.method=clipped"],
                   "sweep": ["render.method=clipped", "render.time_integration=sweep"],
                   "stochastic": ["render.method=stochastic"]}

# The committed ratio limit is the measured ratio times this: timing on a shared 2-core machine
# varies by tens of percent between runs, a real regression worth stopping for is a factor.
DEFAULT_SLACK = 2.0


class GateError(RuntimeError):
    pass


def render(clipblur, method, mode, workdir, index, threads):
    m = MODES[mode]
    image = Path(workdir) / f"{method}_{index}.exr"
    stats = image.with_suffix(".stats.json")
    cmd = [clipblur, "render", str(SCENE), "--out", str(image), "--stats", str(stats), "--progress", "none",
           "--threads", str(threads), "--set", f"film.width={m['width']}",
           "--set", f"film.height={m['height']}", "--set", f"render.samples={m['samples']}"]
    for setting in METHOD_SETTINGS[method]:
        cmd += ["--set", setting]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise GateError(f"render failed ({r.returncode}): {' '.join(cmd)}\n{r.stderr.strip()}")
    with open(stats) as f:
        return json.load(f)


def measure(clipblur, mode, threads):
    repeats = MODES[mode]["repeats"]
    seconds = {m: [] for m in METHOD_SETTINGS}
    counts = {}
    with tempfile.TemporaryDirectory(prefix="clipblur_perf_") as workdir:
        # Alternate the methods so a burst of load elsewhere hits both rather than one.
        for i in range(repeats):
            for method in METHOD_SETTINGS:
                s = render(clipblur, method, mode, workdir, i, threads)
                seconds[method].append(s["seconds"]["total"])
                c = {k: s["counts"].get(k) for k in EXACT_COUNTS[method]}
                if method in counts and counts[method] != c:
                    raise GateError(f"{method} counts differ between repeats: {counts[method]} vs {c}")
                counts[method] = c
    medians = {m: statistics.median(v) for m, v in seconds.items()}
    return {"seconds": seconds, "median_seconds": medians,
            "ratio": medians["clipped"] / medians["stochastic"],
            "ratio_sweep": medians["sweep"] / medians["stochastic"], "counts": counts}


def check(result, expected, counts_only):
    failures = []
    for method, keys in EXACT_COUNTS.items():
        want = expected.get("counts", {}).get(method, {})
        got = result["counts"][method]
        for k in keys:
            if k not in want:
                failures.append(f"{method}.{k}: no committed value (run --update)")
            elif got.get(k) != want[k]:
                failures.append(f"{method}.{k}: {got.get(k)} != committed {want[k]}")
    if not counts_only:
        limit = expected.get("ratio_max")
        if limit is None:
            failures.append("ratio_max: no committed value (run --update)")
        elif result["ratio"] > limit:
            failures.append(f"clipped/stochastic time ratio {result['ratio']:.3f} > limit {limit:.3f}")
        limit = expected.get("ratio_sweep_max")
        if limit is None:
            failures.append("ratio_sweep_max: no committed value (run --update)")
        elif result["ratio_sweep"] > limit:
            failures.append(f"sweep/stochastic time ratio {result['ratio_sweep']:.3f} > limit {limit:.3f}")
    return failures


def git_hash():
    try:
        return subprocess.run(["git", "rev-parse", "HEAD"], cwd=REPO, capture_output=True, text=True,
                              check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--clipblur", default=os.environ.get("CLIPBLUR", str(REPO / "build" / "clipblur")))
    ap.add_argument("--mode", choices=sorted(MODES), default="short")
    ap.add_argument("--threads", type=int, default=1,
                    help="render threads (default 1: least disturbed by other processes; counts do not depend on it)")
    ap.add_argument("--update", action="store_true", help="rewrite this mode's thresholds from this run")
    ap.add_argument("--slack", type=float, default=DEFAULT_SLACK, help="ratio limit = measured ratio x slack (--update)")
    ap.add_argument("--counts-only", action="store_true", help="skip the timing gate (sanitizer builds)")
    ap.add_argument("--thresholds", default=str(THRESHOLDS))
    ap.add_argument("--record", help="JSON record path (full mode default: build/perf/perf_<git>.json)")
    args = ap.parse_args()

    try:
        if not Path(args.clipblur).is_file():
            raise GateError(f"no clipblur binary at {args.clipblur}")
        result = measure(args.clipblur, args.mode, args.threads)
        med = result["median_seconds"]
        print(f"perf gate ({args.mode}): clipped median {med['clipped']:.4f} s, sweep median {med['sweep']:.4f} s, "
              f"stochastic median {med['stochastic']:.4f} s, ratios {result['ratio']:.3f} and {result['ratio_sweep']:.3f}")

        path = Path(args.thresholds)
        table = json.loads(path.read_text()) if path.is_file() else {}
        if args.update:
            table[args.mode] = {"ratio_measured": round(result["ratio"], 4),
                                "ratio_max": round(result["ratio"] * args.slack, 4),
                                "ratio_sweep_measured": round(result["ratio_sweep"], 4),
                                "ratio_sweep_max": round(result["ratio_sweep"] * args.slack, 4),
                                "slack": args.slack, "git": git_hash(), "counts": result["counts"]}
            path.write_text(json.dumps(table, indent=2, sort_keys=True) + "\n")
            print(f"updated {path} [{args.mode}]")
            failures = []
        else:
            failures = check(result, table.get(args.mode, {}), args.counts_only)

        if args.mode == "full" or args.record:
            record = dict(result, mode=args.mode, git=git_hash(), threads=args.threads,
                          date=datetime.datetime.now().isoformat(timespec="seconds"), host=platform.node(),
                          nproc=os.cpu_count(), failures=failures)
            rec = Path(args.record) if args.record else REPO / "build" / "perf" / f"perf_{record['git'][:12]}.json"
            rec.parent.mkdir(parents=True, exist_ok=True)
            rec.write_text(json.dumps(record, indent=2) + "\n")
            print(f"wrote {rec}")
    except (GateError, OSError, json.JSONDecodeError) as e:
        print(f"perf gate: cannot run: {e}", file=sys.stderr)
        return 2
    for f in failures:
        print(f"FAIL {f}", file=sys.stderr)
    if failures:
        print("perf gate: if the change is intended, run with --update and commit tests/perf/thresholds.json",
              file=sys.stderr)
        return 1
    print("perf gate: pass")
    return 0


if __name__ == "__main__":
    sys.exit(main())
