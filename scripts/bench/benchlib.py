"""Shared pieces of the benchmark scripts: running `clipblur`, measuring image error against a
cached converged reference, log-log interpolation and gnuplot charts. Python standard library only
(numpy and the OpenImageIO bindings are not installed); image differences come from `oiiotool`."""

import json
import math
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]

# The reference uses its own seed so that no ladder render shares its sample streams: a stochastic
# render at N spp with the reference's seed would reuse the reference's first N samples per pixel and
# look closer to it than it is.
REFERENCE_SEED = 987654321


class BenchError(RuntimeError):
    pass


def find_clipblur(explicit=None):
    candidates = [explicit] if explicit else [os.environ.get("CLIPBLUR"), REPO / "build" / "clipblur"]
    for c in candidates:
        if c and Path(c).is_file() and os.access(c, os.X_OK):
            return str(Path(c).resolve())
    raise BenchError("clipblur binary not found (build with scripts/build.sh release or pass --clipblur)")


def require_tool(name):
    if shutil.which(name) is None:
        raise BenchError(f"{name} not found on PATH (scripts/setup.sh installs it)")


def set_args(overrides):
    args = []
    for key, value in overrides.items():
        args += ["--set", f"{key}={value}"]
    return args


def git_hash():
    try:
        return subprocess.run(["git", "rev-parse", "HEAD"], cwd=REPO, capture_output=True, text=True,
                              check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def config_hash(clipblur, config, overrides):
    """The job's own config hash (FNV-1a of the canonical document after overrides)."""
    r = subprocess.run([clipblur, "validate", str(config)] + set_args(overrides), capture_output=True, text=True)
    if r.returncode != 0:
        raise BenchError(f"validate {config} failed ({r.returncode}): {r.stderr.strip()}")
    m = re.search(r"config hash:\s*([0-9a-f]+)", r.stdout)
    if not m:
        raise BenchError(f"validate {config}: no config hash in output")
    return m.group(1)


# Each method's ladder parameter is the job key it varies.
LADDER_KEY = {"clipped": "render.subframes", "stochastic": "render.samples", "accumulation": "render.samples"}


def base_overrides(width, height):
    """Film size, full-float RGBA output and no AOVs or preview: the images are only compared."""
    return {"film.width": width, "film.height": height, "output.half": "false", "output.png_preview": "false",
            "output.aovs": "[]"}


def ladder_overrides(method, rung):
    o = {"render.method": method, LADDER_KEY[method]: rung}
    if method == "clipped":
        o["render.time_integration"] = "subframes"  # the paper's point subframes, not the default auto
    if method == "clipped" and rung != "auto":
        o["render.max_subframes"] = max(256, int(rung))
    return o


# Sweep integration's ladder refines re-clips and positions together: rung r has r re-clips per shutter
# segment and positions SWEEP_SPACING_1 / r pixels apart, so each rung halves both error sources.
SWEEP_SPACING_1 = 8.0


def sweep_overrides(rung):
    o = {"render.method": "clipped", "render.time_integration": "sweep"}
    if rung != "auto":
        o.update({"render.subframes": rung, "render.sweep_spacing": SWEEP_SPACING_1 / int(rung),
                  "render.max_subframes": max(256, int(rung))})
    return o


# The other sweep ladder: re-clips as `auto` picks them (what a user runs) and only the positions refined,
# SWEEP_SPACING_1 / r pixels apart at rung r. Where visibility does not change between re-clips (a camera
# pan) the error is the positions' alone, and the re-clip-coupled ladder above pays for re-clips that do
# not lower it.
def sweep_spacing_overrides(rung):
    o = {"render.method": "clipped", "render.time_integration": "sweep"}
    if rung != "auto":
        o["render.sweep_spacing"] = SWEEP_SPACING_1 / float(rung)  # rungs below 1 (0.5, 0.25) are coarser
    return o


# time_integration auto (the default) along the same spacings: each segment picks point subframes or
# sweep, both placed SWEEP_SPACING_1 / r pixels apart at rung r.
def auto_spacing_overrides(rung):
    o = {"render.method": "clipped", "render.time_integration": "auto"}
    if rung != "auto":
        o["render.sweep_spacing"] = SWEEP_SPACING_1 / float(rung)
    return o


# The same ladder with time integrated exactly between sweep positions (render.sweep_time exact).
def auto_exact_overrides(rung):
    return dict(auto_spacing_overrides(rung), **{"render.sweep_time": "exact"})


def render(clipblur, config, overrides, image, threads=0):
    """Renders one frame; returns the stats JSON as a dict, with the process's wall clock added."""
    image = Path(image)
    image.parent.mkdir(parents=True, exist_ok=True)
    stats_path = image.with_suffix(".stats.json")
    cmd = [clipblur, "render", str(config), "--out", str(image), "--stats", str(stats_path), "--progress", "none"]
    cmd += set_args(overrides)
    if threads:
        cmd += ["--threads", str(threads)]
    start = time.monotonic()
    r = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.monotonic() - start
    if r.returncode != 0:
        raise BenchError(f"render failed ({r.returncode}): {' '.join(cmd)}\n{r.stderr.strip()}")
    with open(stats_path) as f:
        stats = json.load(f)
    # The whole process, start-up and image writing included: what a user waits for.
    stats["process_wall_seconds"] = wall
    return stats


_DIFF_FIELDS = {"rmse": r"RMS error\s*=\s*([0-9.eE+-]+|nan|inf)", "max_abs": r"Max error\s*=\s*([0-9.eE+-]+|nan|inf)",
                "mean_abs": r"Mean error\s*=\s*([0-9.eE+-]+|nan|inf)"}


def image_error(reference, image):
    """RMSE, max and mean absolute error over the R, G, B channels (alpha excluded: it is coverage,
    not colour). oiiotool prints only PASS with no figures when the images are identical."""
    cmd = ["oiiotool", "--no-autopremult", str(reference), "--ch", "R,G,B", str(image), "--ch", "R,G,B",
           "--diff", "--fail", "1e30", "--warn", "1e30"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    out = r.stdout + r.stderr
    if "Max error" not in out:
        if "PASS" in out and r.returncode == 0 and "Mean error" not in out:
            return {"rmse": 0.0, "max_abs": 0.0, "mean_abs": 0.0}
        raise BenchError(f"oiiotool --diff gave no figures for {image}: {out.strip()}")
    result = {}
    for key, pattern in _DIFF_FIELDS.items():
        m = re.search(pattern, out)
        result[key] = float(m.group(1)) if m else float("nan")
    return result


def earlier_references(references_from, stem, *names):
    """The images `names` of scene `stem` under an earlier run's --out (its renders/<stem>/), for a run
    that reuses its references (--references-from); None when there is no earlier run to reuse."""
    if not references_from:
        return None
    paths = [Path(references_from) / "renders" / stem / n for n in names]
    missing = [p for p in paths if not p.exists()]
    if missing:
        raise BenchError(f"no reference {missing[0]}")
    return paths


def reference_image(clipblur, config, overrides, spp, cache_dir, threads=0, refresh=False, log=print):
    """Converged reference: stochastic at `spp` samples, cached under the config hash of the job with
    every override applied (film size, method, samples, seed), so any change of scene or settings
    makes a new entry. `refresh` re-renders it (e.g. after a change to the stochastic renderer)."""
    ref_overrides = dict(overrides)
    ref_overrides.update({"render.method": "stochastic", "render.samples": spp, "render.seed": REFERENCE_SEED})
    key = config_hash(clipblur, config, ref_overrides)
    path = Path(cache_dir) / f"{Path(config).stem}-{key}.exr"
    if refresh or not path.is_file():
        log(f"  reference {path.name}: stochastic {spp} spp ...")
        stats = render(clipblur, config, ref_overrides, path, threads)
        log(f"  reference done in {stats['seconds']['total']:.1f} s")
    return path


def envelope(points):
    """(time, error) pairs sorted by time with the error replaced by its running minimum: spending
    more time never has to buy a worse answer, one can always keep the better cheaper render."""
    best = math.inf
    out = []
    for t, e in sorted(points):
        best = min(best, e)
        out.append((t, best))
    return out


def time_to_reach(points, error):
    """Time a method needs to reach `error`, interpolated linearly in log-log between the two ladder
    rungs that bracket it; None if no rung reaches it, and the first rung's time if that already does."""
    env = envelope([(t, e) for t, e in points if t > 0])
    if not env:
        return None
    if env[0][1] <= error:
        return env[0][0]
    for (t0, e0), (t1, e1) in zip(env, env[1:]):
        if e1 <= error < e0:
            if e1 == 0:
                return t1
            s = (math.log(error) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + s * (math.log(t1) - math.log(t0)))
    return None


def gnuplot_chart(path_stem, title, series, xlabel, ylabel, logx=True, logy=True):
    """One chart as PNG and SVG. series: list of (label, [(x, y, point_label), ...])."""
    stem = Path(path_stem)
    stem.parent.mkdir(parents=True, exist_ok=True)
    dat = stem.with_suffix(".dat")
    plots = []
    with open(dat, "w") as f:
        for i, (label, pts) in enumerate(series):
            f.write(f"# {label}\n")
            for x, y, tag in pts:
                if x > 0 and y > 0:
                    f.write(f"{x:.6g} {y:.6g} {tag}\n")
            f.write("\n\n")
            plots.append(f"'{dat}' index {i} using 1:2 with linespoints lw 2 pt {5 + i} title '{label}'")
            plots.append(f"'{dat}' index {i} using 1:2:3 with labels offset 0.8,0.6 font ',8' notitle")
    body = [
        "set termoption noenhanced",
        f"set title '{title}'",
        f"set xlabel '{xlabel}'", f"set ylabel '{ylabel}'",
        "set logscale x" if logx else "unset logscale x", "set logscale y" if logy else "unset logscale y",
        "set grid", "set key outside right top",
        "plot " + ", \\\n     ".join(plots),
    ]
    script = "\n".join(body) + "\n"
    for term, ext in (("pngcairo size 900,560", ".png"), ("svg size 900,560", ".svg")):
        out = stem.with_suffix(ext)
        full = f"set terminal {term}\nset output '{out}'\n" + script
        r = subprocess.run(["gnuplot"], input=full, capture_output=True, text=True)
        if r.returncode != 0:
            raise BenchError(f"gnuplot failed for {out}: {r.stderr.strip()}")


def machine_description():
    model = "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return {"nproc": os.cpu_count(), "cpu_model": model, "python": sys.version.split()[0]}
