#!/usr/bin/env python3
"""Performance regression gate.

Renders tests/perf/gate_scene.yaml with the clipped method (point subframes and sweep integration)
and with a stochastic baseline, alternating, several times, then each many-object bench scene
(configs/bench/many/, made after the tuning) once with sweep integration and automatic re-clips, once
more with `render.sweep_time: exact`, and once with the default `time_integration: auto`, and checks
against tests/perf/thresholds.json:
  - the RATIOS min(clipped CPU seconds) / min(stochastic CPU seconds) and the same for sweep. CPU
    seconds are the render's own (stats `seconds.cpu`, getrusage around the frame, process start-up
    excluded), so a neighbour that competes for the cores stretches wall clock but hardly moves them.
    Every render of one gate run is pinned to the same CPU: on these virtual machines one core can run
    30 % slower than the other for minutes (a busy sibling on the host), which alone moved single
    renders by that much. The baseline's sample count makes its run about as long as the clipped ones,
    so fixed costs weigh alike; the minimum of the repeats is the least disturbed. The limit is the
    committed ratio times a slack below 1.5, so a 1.5x slowdown fails. Ratios between Embree's SIMD
    traversal and the clipped scalar code differ between CPU models, so each model has its own
    committed ratio;
  - EXACT noise-free counts from the stats (subframes, fragments, candidates, rays), which change
    only when the algorithm does, and must not differ between repeats. The many-object scenes are
    gated by their counts only (re-clips, positions, fragments: where a wrong re-clip rule shows as
    a 10x count, as it did before 3da2aca); their CPU seconds are printed.

    tests/perf/perf_gate.py --clipblur build/clipblur                # short mode (CI, < 1 min)
    tests/perf/perf_gate.py --clipblur build/clipblur --mode full    # also writes a JSON record
    tests/perf/perf_gate.py --clipblur build/clipblur --update       # commit this CPU model's ratios and the counts

Exit codes: 0 pass, 1 a gate failed, 2 the gate could not run.
"""

import argparse
import datetime
import json
import os
import platform
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
SCENE = HERE / "gate_scene.yaml"
THRESHOLDS = HERE / "thresholds.json"

# `samples` is the stochastic baseline's: chosen so that its run takes about as long as the clipped
# ones (between point subframes and sweep in CPU seconds), not for its image.
MODES = {
    "short": {"width": 64, "height": 36, "repeats": 5, "samples": 1024},
    "full": {"width": 160, "height": 90, "repeats": 5, "samples": 1024},
}

# Counts that depend only on the scene and the algorithm, not on timing or thread count.
EXACT_COUNTS = {
    "clipped": ["triangles", "tiles", "segments", "open_deep_tiles", "close_deep_tiles", "hidden_probe_samples",
                "hidden_probe_hits", "frame_sets", "still_tiles", "subframes_total", "subframes_max_per_tile", "capped_tiles",
                "measured_fragment_paths", "propagated_triangles", "reclip_fragments", "reclip_mixed_fragments",
                "reclip_near_clipped", "open_rays", "open_candidates", "open_fragments", "open_shaded_pieces",
                "close_rays", "close_candidates", "close_fragments", "close_shaded_pieces"],
    "sweep": ["subframes_total", "subframes_max_per_tile", "reclip_fragments", "sweep_positions",
              "sweep_spilled_pixels", "sweep_unswept_fragments"],
    "stochastic": ["triangles", "rays", "primary_rays", "samples", "max_time_steps", "vertex_evaluations"],
}
# The many-object scenes' counts (sweep, automatic re-clips), rendered at the mode's size.
MANY_SCENES = ["particles", "street", "deforming", "building_dolly"]
MANY_COUNTS = ["segments", "open_deep_tiles", "close_deep_tiles", "frame_sets", "subframes_total",
               "subframes_max_per_tile", "capped_tiles", "reclip_fragments", "sweep_positions", "sweep_spilled_pixels",
               "sweep_unswept_fragments"]
# The same scenes under the default `time_integration: auto`, gated under "many-auto/<name>": which
# method each segment takes is a count too, so a cost-model change that flips a choice shows here.
AUTO_COUNTS = MANY_COUNTS + ["segments_points", "segments_sweep"]
# What each gate method renders, on top of the scene's own settings.
# Point subframes explicitly: the default time_integration is auto, which sweeps the gate scene.
METHOD_SETTINGS = {"clipped": ["render.method=clipped", "render.time_integration=subframes"],
                   "sweep": ["render.method=clipped", "render.time_integration=sweep"],
                   "stochastic": ["render.method=stochastic"]}
# How the many-object scenes are rendered: not part of the timed alternation above. "exact" is sweep with
# render.sweep_time exact, gated under "many-exact/<name>" by the same counts as sweep.
MANY_METHODS = {"sweep": METHOD_SETTINGS["sweep"], "exact": METHOD_SETTINGS["sweep"] + ["render.sweep_time=exact"],
                "auto": ["render.method=clipped"]}

# The committed ratio limit is the measured ratio times this. Below 1.5, so that a 1.5x slowdown of
# the clipped code fails; above the spread of CPU-second ratios between runs under load (docs/performance.md).
DEFAULT_SLACK = 1.3
# On a CPU model with no committed ratio the limit is the committed ratio times this: another model's
# SIMD width alone moves the Embree baseline against scalar code by tens of percent, so such a run can
# catch only gross regressions, and says so.
FOREIGN_CPU_SLACK = 2.0


class GateError(RuntimeError):
    pass


def render(clipblur, method, mode, workdir, index, threads, cpu, scene=SCENE, settings=None):
    m = MODES[mode]
    image = Path(workdir) / f"{scene.stem}_{method}_{index}.exr"
    stats = image.with_suffix(".stats.json")
    cmd = [clipblur, "render", str(scene), "--out", str(image), "--stats", str(stats), "--progress", "none",
           "--threads", str(threads), "--set", f"film.width={m['width']}",
           "--set", f"film.height={m['height']}", "--set", f"render.samples={m['samples']}"]
    for setting in settings if settings is not None else METHOD_SETTINGS[method]:
        cmd += ["--set", setting]
    r = subprocess.run(cmd, capture_output=True, text=True,
                       preexec_fn=(lambda: os.sched_setaffinity(0, {cpu})) if cpu is not None else None)
    if r.returncode != 0:
        raise GateError(f"render failed ({r.returncode}): {' '.join(cmd)}\n{r.stderr.strip()}")
    with open(stats) as f:
        return json.load(f)


def measure(clipblur, mode, threads, counts_only=False):
    # Counts need only two repeats to show they agree (the sanitizer build, where each render is slow).
    repeats = 2 if counts_only else MODES[mode]["repeats"]
    # One CPU for every render (the first this process may use) when they are single-threaded.
    cpu = min(os.sched_getaffinity(0)) if threads == 1 and hasattr(os, "sched_getaffinity") else None
    seconds = {m: [] for m in METHOD_SETTINGS}
    counts = {}
    with tempfile.TemporaryDirectory(prefix="clipblur_perf_") as workdir:
        # Alternate the methods so a burst of load elsewhere hits both rather than one.
        for i in range(repeats):
            for method in METHOD_SETTINGS:
                s = render(clipblur, method, mode, workdir, i, threads, cpu)
                if "cpu" not in s["seconds"]:
                    raise GateError(f"{method} stats have no seconds.cpu: is {clipblur} older than this gate?")
                seconds[method].append(s["seconds"]["cpu"])
                c = {k: s["counts"].get(k) for k in EXACT_COUNTS[method]}
                if method in counts and counts[method] != c:
                    raise GateError(f"{method} counts differ between repeats: {counts[method]} vs {c}")
                counts[method] = c
        for name in MANY_SCENES:
            scene = REPO / "configs/bench/many" / f"{name}.yaml"
            for method, settings in MANY_METHODS.items():
                s = render(clipblur, method, mode, workdir, 0, threads, cpu, scene, settings)
                key = many_key(method, name)
                counts[key] = {k: s["counts"].get(k) for k in many_counts(method)}
                seconds[key] = [s["seconds"]["cpu"]]
    least = {m: min(v) for m, v in seconds.items()}
    return {"cpu_seconds": seconds, "min_cpu_seconds": least, "pinned_cpu": cpu,
            "ratio": least["clipped"] / least["stochastic"],
            "ratio_sweep": least["sweep"] / least["stochastic"], "counts": counts}


def many_key(method, name):
    return f"many/{name}" if method == "sweep" else f"many-{method}/{name}"


def many_counts(method):
    return AUTO_COUNTS if method == "auto" else MANY_COUNTS


def cpu_model():
    """The CPU model name from /proc/cpuinfo (the timing baseline is per model), else the platform's."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def timing_limits(expected, model):
    """(ratio limit, sweep ratio limit, note) for this CPU model from the committed table."""
    timing = expected.get("timing", {})
    if model in timing:
        t = timing[model]
        return t["ratio_max"], t["ratio_sweep_max"], f"committed for {model}"
    if not timing:
        return None, None, "no committed timing"
    ratio = max(t["ratio_measured"] for t in timing.values()) * FOREIGN_CPU_SLACK
    sweep = max(t["ratio_sweep_measured"] for t in timing.values()) * FOREIGN_CPU_SLACK
    return ratio, sweep, (f"no committed timing for CPU '{model}': limits are the committed ratios x "
                          f"{FOREIGN_CPU_SLACK} and catch only gross slowdowns; run --update on this machine")


def check(result, expected, counts_only, model):
    failures = []
    gated = dict(EXACT_COUNTS, **{many_key(m, n): many_counts(m) for m in MANY_METHODS for n in MANY_SCENES})
    for method, keys in gated.items():
        want = expected.get("counts", {}).get(method, {})
        got = result["counts"][method]
        for k in keys:
            if k not in want:
                failures.append(f"{method}.{k}: no committed value (run --update)")
            elif got.get(k) != want[k]:
                failures.append(f"{method}.{k}: {got.get(k)} != committed {want[k]}")
    if not counts_only:
        ratio_max, sweep_max, note = timing_limits(expected, model)
        print(f"perf gate: timing limits {note}")
        if ratio_max is None:
            failures.append("timing: no committed ratios (run --update)")
        else:
            if result["ratio"] > ratio_max:
                failures.append(f"clipped/stochastic CPU ratio {result['ratio']:.3f} > limit {ratio_max:.3f}")
            if result["ratio_sweep"] > sweep_max:
                failures.append(f"sweep/stochastic CPU ratio {result['ratio_sweep']:.3f} > limit {sweep_max:.3f}")
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
        result = measure(args.clipblur, args.mode, args.threads, args.counts_only and not args.update)
        least = result["min_cpu_seconds"]
        model = cpu_model()
        print(f"perf gate ({args.mode}, {model}, renders on CPU {result['pinned_cpu']}): least CPU seconds of {len(result['cpu_seconds']['clipped'])}: clipped "
              f"{least['clipped']:.4f}, sweep {least['sweep']:.4f}, stochastic {least['stochastic']:.4f}; "
              f"ratios {result['ratio']:.3f} and {result['ratio_sweep']:.3f}")
        for m in MANY_METHODS:
            print(f"perf gate: many-object scenes, {m}, CPU seconds: " +
                  ", ".join(f"{n} {least[many_key(m, n)]:.3f}" for n in MANY_SCENES))

        path = Path(args.thresholds)
        table = json.loads(path.read_text()) if path.is_file() else {}
        if args.update:
            entry = table.get(args.mode, {})
            timing = entry.get("timing", {})
            if entry.get("counts") != result["counts"]:
                # The algorithm changed: other models' ratios were measured on the old one.
                if set(timing) - {model}:
                    print(f"counts changed: dropping the timing of {sorted(set(timing) - {model})}")
                timing = {}
            timing[model] = {"ratio_measured": round(result["ratio"], 4),
                             "ratio_max": round(result["ratio"] * args.slack, 4),
                             "ratio_sweep_measured": round(result["ratio_sweep"], 4),
                             "ratio_sweep_max": round(result["ratio_sweep"] * args.slack, 4),
                             "slack": args.slack, "git": git_hash()}
            table[args.mode] = {"counts": result["counts"], "timing": timing}
            path.write_text(json.dumps(table, indent=2, sort_keys=True) + "\n")
            print(f"updated {path} [{args.mode}]")
            failures = []
        else:
            failures = check(result, table.get(args.mode, {}), args.counts_only, model)

        if args.mode == "full" or args.record:
            record = dict(result, mode=args.mode, git=git_hash(), threads=args.threads, cpu=model,
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
