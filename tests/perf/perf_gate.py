#!/usr/bin/env python3
"""Performance regression gate.

Renders tests/perf/gate_scene.yaml with the clipped method (point subframes and sweep integration)
and with the stochastic method, then each many-object bench scene (configs/bench/many/, made after the
tuning) once with sweep integration and automatic re-clips, once more with `render.sweep_time: exact`,
and once with the default `time_integration: auto`, and checks against tests/perf/thresholds.json:
  - INSTRUCTIONS: each of the three gate methods is rendered once more, single-threaded, under valgrind's
    callgrind, counting only the instructions executed inside `renderFrame` (process start-up, job
    loading and image writing excluded). Another process on the cores, a slow or a shared CPU do not
    move that count (repeats agree to about 1e-5), so the gate holds under any load; valgrind reports no
    AVX-512, so other x86-64 models with AVX2 should count alike (measured on one). The limit is the
    committed count times a slack below 1.5, so work that makes a method 1.5x slower fails. What it cannot see: a change
    that costs cache misses or stalls without executing more instructions;
  - EXACT noise-free counts from the stats (subframes, fragments, candidates, rays), which change
    only when the algorithm does, and must not differ between the two native repeats. The many-object
    scenes are gated by their counts only (re-clips, positions, fragments: where a wrong re-clip rule
    shows as a 10x count, as it did before 3da2aca).
CPU seconds (stats `seconds.cpu`) of the native renders are printed, not gated: they move with the load.

    tests/perf/perf_gate.py --clipblur build/clipblur                # short mode (CI, about 1 min)
    tests/perf/perf_gate.py --clipblur build/clipblur --mode full    # also writes a JSON record
    tests/perf/perf_gate.py --clipblur build/clipblur --update       # commit the instructions and the counts

Exit codes: 0 pass, 1 a gate failed, 2 the gate could not run.
"""

import argparse
import concurrent.futures
import datetime
import json
import os
import platform
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
SCENE = HERE / "gate_scene.yaml"
THRESHOLDS = HERE / "thresholds.json"

# Native renders at width x height give the counts (`samples` is the stochastic one's, the setting the
# committed counts were made with); the instruction renders run under callgrind at about
# 40x the native time, so at a quarter of the pixels and with fewer stochastic samples (about 1.1, 1.8 and
# 0.15 G instructions in short mode: 25, 32 and 5 s of one core; the gate takes about a minute on 2 cores).
MODES = {
    "short": {"width": 64, "height": 36, "samples": 1024, "instr_width": 32, "instr_height": 18, "instr_samples": 128},
    "full": {"width": 160, "height": 90, "samples": 1024, "instr_width": 64, "instr_height": 36, "instr_samples": 256},
}
REPEATS = 2  # native renders per gate method: their counts must agree

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
# How the many-object scenes are rendered. "exact" is sweep with render.sweep_time exact, gated under
# "many-exact/<name>" by the same counts as sweep.
MANY_METHODS = {"sweep": METHOD_SETTINGS["sweep"], "exact": METHOD_SETTINGS["sweep"] + ["render.sweep_time=exact"],
                "auto": ["render.method=clipped"]}

# The instruction limit is the committed count times this. Below 1.5, so that a 1.5x slowdown of any
# gated method fails; above what a Debian point release of the compiler, libm or Embree might move.
DEFAULT_SLACK = 1.25
# The function whose instructions are counted: one frame's render, whatever the method.
COUNTED_FUNCTION = "clipblur::renderFrame*"


class GateError(RuntimeError):
    pass


def render_command(clipblur, scene, image, size, samples, settings):
    cmd = [clipblur, "render", str(scene), "--out", str(image), "--stats", str(image.with_suffix(".stats.json")),
           "--progress", "none", "--threads", "1", "--set", f"film.width={size[0]}",
           "--set", f"film.height={size[1]}", "--set", f"render.samples={samples}"]
    for setting in settings:
        cmd += ["--set", setting]
    return cmd


def run(cmd, what):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise GateError(f"{what} failed ({r.returncode}): {' '.join(cmd)}\n{r.stderr.strip()[-2000:]}")
    return r


def render(clipblur, mode, workdir, name, scene, settings):
    """Stats of one native single-threaded render at the mode's size."""
    m = MODES[mode]
    image = Path(workdir) / f"{name}.exr"
    run(render_command(clipblur, scene, image, (m["width"], m["height"]), m["samples"], settings), "render")
    with open(image.with_suffix(".stats.json")) as f:
        return json.load(f)


def instructions(clipblur, mode, workdir, method):
    """Instructions callgrind counts inside renderFrame for one gate method at the mode's instruction size."""
    m = MODES[mode]
    image = Path(workdir) / f"instr_{method}.exr"
    out = Path(workdir) / f"instr_{method}.callgrind"
    cmd = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", f"--toggle-collect={COUNTED_FUNCTION}",
           *render_command(clipblur, SCENE, image, (m["instr_width"], m["instr_height"]), m["instr_samples"],
                           METHOD_SETTINGS[method])]
    found = re.search(r"Collected\s*:\s*(\d+)", run(cmd, f"callgrind render ({method})").stderr)
    if not found or int(found.group(1)) == 0:
        raise GateError(f"callgrind counted no instructions in {COUNTED_FUNCTION} ({method}): renamed?")
    return int(found.group(1))


def measure(clipblur, mode, counts_only=False):
    if not counts_only and shutil.which("valgrind") is None:
        raise GateError("valgrind is not installed (bash scripts/setup.sh installs it)")
    seconds = {m: [] for m in METHOD_SETTINGS}
    counts = {}
    with tempfile.TemporaryDirectory(prefix="clipblur_perf_") as workdir:
        # The callgrind renders (the gate's longest part, the longest first) run two at a time beside the
        # native ones: their counts do not depend on what shares the cores.
        with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
            pending = {} if counts_only else {
                m: pool.submit(instructions, clipblur, mode, workdir, m) for m in ("sweep", "clipped", "stochastic")}
            for i in range(REPEATS):
                for method, settings in METHOD_SETTINGS.items():
                    s = render(clipblur, mode, workdir, f"{method}_{i}", SCENE, settings)
                    seconds[method].append(s["seconds"]["cpu"])
                    c = {k: s["counts"].get(k) for k in EXACT_COUNTS[method]}
                    if method in counts and counts[method] != c:
                        raise GateError(f"{method} counts differ between repeats: {counts[method]} vs {c}")
                    counts[method] = c
            for name in MANY_SCENES:
                scene = REPO / "configs/bench/many" / f"{name}.yaml"
                for method, settings in MANY_METHODS.items():
                    key = many_key(method, name)
                    s = render(clipblur, mode, workdir, key.replace("/", "_"), scene, settings)
                    counts[key] = {k: s["counts"].get(k) for k in many_counts(method)}
                    seconds[key] = [s["seconds"]["cpu"]]
            instr = {m: f.result() for m, f in pending.items()}
    return {"cpu_seconds": seconds, "min_cpu_seconds": {m: min(v) for m, v in seconds.items()},
            "instructions": instr, "counts": counts}


def many_key(method, name):
    return f"many/{name}" if method == "sweep" else f"many-{method}/{name}"


def many_counts(method):
    return AUTO_COUNTS if method == "auto" else MANY_COUNTS


def cpu_model():
    """The CPU model name from /proc/cpuinfo, for the record, else the platform's."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def check(result, expected, counts_only):
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
    if counts_only:
        return failures
    committed = expected.get("instructions", {})
    slack = committed.get("slack", DEFAULT_SLACK)
    for method, got in result["instructions"].items():
        want = committed.get(method)
        if want is None:
            failures.append(f"{method}: no committed instruction count (run --update)")
            continue
        print(f"perf gate: {method} {got / 1e6:.1f} M instructions, {got / want:.3f}x committed "
              f"{want / 1e6:.1f} M (limit {slack}x)")
        if got > want * slack:
            failures.append(f"{method} instructions {got} > limit {round(want * slack)} (committed {want} x {slack})")
        elif got * slack < want:
            print(f"perf gate: {method} runs {want / got:.2f}x fewer instructions than committed: --update "
                  "locks the gain in")
    return failures


def valgrind_version():
    return subprocess.run(["valgrind", "--version"], capture_output=True, text=True).stdout.strip()


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
    ap.add_argument("--update", action="store_true", help="rewrite this mode's thresholds from this run")
    ap.add_argument("--slack", type=float, default=DEFAULT_SLACK,
                    help="instruction limit = committed count x slack (--update)")
    ap.add_argument("--counts-only", action="store_true", help="skip the instruction gate (no valgrind run)")
    ap.add_argument("--thresholds", default=str(THRESHOLDS))
    ap.add_argument("--record", help="JSON record path (full mode default: build/perf/perf_<git>.json)")
    args = ap.parse_args()

    try:
        if not Path(args.clipblur).is_file():
            raise GateError(f"no clipblur binary at {args.clipblur}")
        counts_only = args.counts_only and not args.update
        result = measure(args.clipblur, args.mode, counts_only)
        least = result["min_cpu_seconds"]
        print(f"perf gate ({args.mode}): least CPU seconds of {REPEATS} (printed, not gated): clipped "
              f"{least['clipped']:.4f}, sweep {least['sweep']:.4f}, stochastic {least['stochastic']:.4f}")
        for m in MANY_METHODS:
            print(f"perf gate: many-object scenes, {m}, CPU seconds: " +
                  ", ".join(f"{n} {least[many_key(m, n)]:.3f}" for n in MANY_SCENES))

        path = Path(args.thresholds)
        table = json.loads(path.read_text()) if path.is_file() else {}
        if args.update:
            table[args.mode] = {"counts": result["counts"],
                                "instructions": dict(result["instructions"], slack=args.slack, git=git_hash(),
                                                     valgrind=valgrind_version())}
            path.write_text(json.dumps(table, indent=2, sort_keys=True) + "\n")
            print(f"updated {path} [{args.mode}]: " +
                  ", ".join(f"{m} {n / 1e6:.1f} M instructions" for m, n in result["instructions"].items()))
            failures = []
        else:
            failures = check(result, table.get(args.mode, {}), counts_only)

        if args.mode == "full" or args.record:
            record = dict(result, mode=args.mode, git=git_hash(), cpu=cpu_model(),
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
