#!/usr/bin/env python3
"""Blender round trip (issue 22): a shot built and exported by Blender renders in clipblur with its camera,
animation, normals and textures.

Installs Blender when it is missing (cycles_peer.ensure_blender: Debian's blender 3.4 and python3-numpy),
runs scripts/shot/blender_export.py headless into OUT (a temporary folder unless --out), then checks:

1. export: a second export gives the same bytes; the Khronos glTF validator's verdict when tests/gltf
   has it (`npm ci` there; errors fail, Blender's skinned-mesh-not-at-root warning is expected);
2. `clipblur validate` accepts the job with no warning, and the export uses KHR_texture_transform (the
   floor's Mapping node);
3. materials: the textured meshes have UVs and checker.png, the emissive cube its emission, the ball and
   the bar shading normals, every animated object motion (keys or an exact glTF motion);
4. camera: at each frame Blender recorded (truth.json), clipblur's camera key at that frame against the
   camera's matrix_world (Blender Z up to glTF Y up: (x, y, z) -> (x, z, -y)): position, view and up;
   and the vertical field of view;
5. poses: at the same frames `clipblur scene-json --at FRAME` against every mesh's evaluated world-space
   vertices in Blender (the car's child wheel and the skinned bar included): the largest distance from a
   vertex of either to the nearest of the other (the exporter splits vertices at UV and normal seams, so
   the lists differ in order and length but not as point sets);
6. images: `clipblur render` at the job's own settings (clipped, `auto` subframes), and two stochastic
   renders at --spp with different seeds; RMSE of clipped against the first and of the two against each
   other (their noise; clipped's bias is about sqrt(RMSE_cs^2 - RMSE_ss^2 / 2)); then the same pair
   (clipped, one stochastic) with the shutter closed to an instant, where no motion is left.

Exit 0 when 1-5 pass (tolerance TOL: glTF stores float32, about 1e-6 relative on a shot 20 m across),
1 otherwise; the RMSEs are reported, not gated (the per-piece shading floor of textures and smooth
normals, docs/performance.md "Shipped shot", is what they measure). Seconds are wall clock.

    scripts/shot/blender_roundtrip.py [--out DIR] [--clipblur PATH] [--spp 1024] [--threads 2] [--skip-render]
"""

import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
sys.path.insert(0, str(REPO / "scripts" / "bench"))
import benchlib  # noqa: E402
from cycles_peer import ensure_blender  # noqa: E402

TOL = 1e-4           # metres and radians: float32 storage, with margin for chains of float32 transforms
TEXTURED = ("floor", "wall", "ball", "wheel")
SMOOTH = ("ball", "bar")
ANIMATED = ("ball", "car", "wheel", "bar")


class Report:
    def __init__(self):
        self.failures = []

    def check(self, ok, what):
        print(f"  {'ok  ' if ok else 'FAIL'} {what}", flush=True)
        if not ok:
            self.failures.append(what)


def run(cmd, **kw):
    r = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, **kw)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(map(str, cmd))} failed ({r.returncode}):\n{r.stdout}\n{r.stderr}")
    return r.stdout


def blender_env():
    """The environment without other Pythons' folders on PATH: Debian's Blender embeds the system Python and
    takes its prefix from the first python3 on PATH, so under pyenv or a virtualenv it loses
    /usr/lib/python3/dist-packages and with it numpy, which the glTF exporter imports."""
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PYENV", "VIRTUAL_ENV", "PYTHONHOME", "PYTHONPATH"))}
    keep = [p for p in env.get("PATH", "").split(os.pathsep)
            if p in ("/usr/bin", "/bin") or not (Path(p) / "python3").exists()]
    env["PATH"] = os.pathsep.join(keep)
    return env


def export(blender, out):
    t0 = time.monotonic()
    run([blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python", HERE / "blender_export.py", "--",
         out], env=blender_env())
    return time.monotonic() - t0


def gltf_validator(out, report):
    script = REPO / "tests" / "gltf" / "validate.js"
    if shutil.which("node") is None or not (REPO / "tests" / "gltf" / "node_modules" / "gltf-validator").is_dir():
        print("  skip glTF validator (node or tests/gltf/node_modules missing: run npm ci in tests/gltf)")
        return
    r = subprocess.run(["node", str(script), str(out), "1"], capture_output=True, text=True)
    text = (r.stdout + r.stderr).strip()
    m = re.search(r"(\d+) errors, (\d+) warnings", text)
    for line in text.splitlines():
        if ": /" in line:
            print(f"       {line}")
    report.check(m is not None and m.group(1) == "0", f"Khronos validator: {m.group(0) if m else text}")


def by_name(scene):
    return {o["name"]: o for o in scene["objects"]}


def check_materials(scene, report):
    objects, materials = by_name(scene), scene["materials"]
    for name in TEXTURED:
        o = objects[name]
        image = materials[o["material"]]["image"]
        report.check(o["uvs"] and Path(image).name == "checker.png", f"{name}: UVs and texture {Path(image).name}")
    for name in SMOOTH:
        report.check(objects[name]["smooth"], f"{name}: shading normals")
    lamp = materials[objects["lamp"]["material"]]
    report.check(norm(sub(lamp["emission"], [1.0, 0.75, 0.3])) <= 1e-6 and lamp["base_color"] == [0.0, 0.0, 0.0],
                 f"lamp: emission {lamp['emission']}, base colour {lamp['base_color']}")
    for name in ANIMATED:
        o = objects[name]
        how = "exact glTF motion" if o["exact_motion"] else f"{len(o['transform'])} transform keys"
        report.check(o["exact_motion"] or len(o["transform"]) > 1, f"{name}: moves ({how})")


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def norm(a):
    return math.sqrt(sum(x * x for x in a))


def angle(a, b):
    c = sum(x * y for x, y in zip(a, b)) / (norm(a) * norm(b))
    return math.acos(max(-1.0, min(1.0, c)))


def check_camera(scene, truth, report):
    keys = scene["camera"]["keys"]
    worst = [0.0, 0.0, 0.0]
    for frame, record in truth["frames"].items():
        # Key times are float32 seconds times fps: frame 1 is 1.0000000298.
        key = next((k for k in keys if abs(k["time"] - float(frame)) < 1e-5), None)
        cam = record["camera"]
        if key is None:
            report.check(False, f"camera: no key at frame {frame}")
            continue
        errors = [norm(sub(key["position"], cam["position"])), angle(key["view"], cam["view"]),
                  angle(key["up"], cam["up"])]
        worst = [max(w, e) for w, e in zip(worst, errors)]
    report.check(max(worst) <= TOL, f"camera at frames {', '.join(truth['frames'])} ({len(keys)} keys): position "
                 f"{worst[0]:.2e} m, view {worst[1]:.2e} rad, up {worst[2]:.2e} rad from Blender's")
    dv = abs(scene["camera"]["vfov"] - truth["vfov_degrees"])
    report.check(dv <= 1e-4, f"camera vfov {scene['camera']['vfov']:.6f} degrees, Blender's {truth['vfov_degrees']:.6f}")


def hausdorff(a, b):
    def one_way(p, q):
        return max(min(sum((x - y) ** 2 for x, y in zip(u, v)) for v in q) for u in p)
    return math.sqrt(max(one_way(a, b), one_way(b, a)))


def check_poses(clipblur, job, truth, report):
    for frame, record in truth["frames"].items():
        posed = by_name(json.loads(run([clipblur, "scene-json", job, "--at", frame])))
        worst, where = 0.0, ""
        for name, vertices in record["meshes"].items():
            if name not in posed:
                report.check(False, f"frame {frame}: {name} missing from clipblur's scene")
                continue
            d = hausdorff(posed[name]["posed"]["positions"], vertices)
            if d >= worst:
                worst, where = d, name
        report.check(worst <= TOL, f"frame {frame}: every mesh's vertices within {worst:.2e} m of Blender's "
                     f"(largest: {where})")


def render(clipblur, job, out, threads, overrides, reference=None):
    cmd = [clipblur, "render", job, "--threads", threads, "--progress", "none", "--out", out,
           "--set", "output.half=false"]
    for k, v in overrides.items():
        cmd += ["--set", f"{k}={v}"]
    if reference:
        cmd += ["--reference", reference]
    t0 = time.monotonic()
    text = run(cmd)
    seconds = time.monotonic() - t0
    m = re.search(r"RMSE ([0-9.eE+-]+)", text)
    return seconds, float(m.group(1)) if m else None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", help="folder for the export and renders (default: a temporary one, removed)")
    ap.add_argument("--clipblur", help="clipblur binary (default: $CLIPBLUR, else build/clipblur)")
    ap.add_argument("--spp", type=int, default=1024, help="stochastic samples per pixel (default 1024)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--skip-render", action="store_true", help="checks 1-5 only")
    args = ap.parse_args()
    clipblur = benchlib.find_clipblur(args.clipblur)
    temp = None if args.out else tempfile.TemporaryDirectory(prefix="blender_shot_")
    out = Path(args.out or temp.name).resolve()
    report = Report()
    try:
        blender = ensure_blender()
        print(f"{run([blender, '--version']).splitlines()[0]}; clipblur {clipblur}; out {out}")
        print(f"export: {export(blender, out):.1f} s")
        again = out / "again"
        export(blender, again)
        same = [f.name for f in sorted(again.iterdir()) if f.read_bytes() == (out / f.name).read_bytes()]
        report.check(len(same) == len(list(again.iterdir())), f"a second export is the same bytes: {', '.join(same)}")
        job, truth = out / "job.yaml", json.loads((out / "truth.json").read_text())
        gltf_validator(out, report)
        summary = run([clipblur, "validate", job])
        warnings = re.search(r"warnings:\s+(\d+)", summary)
        report.check(warnings is not None and warnings.group(1) == "0", "clipblur validate: " + "; ".join(
            " ".join(line.split()) for line in summary.splitlines()
            if re.match(r"\s+(objects|triangles|camera keys|warnings)", line)))
        gltf = json.loads((out / "blender_shot.gltf").read_text())
        report.check("KHR_texture_transform" in gltf.get("extensionsUsed", []),
                     f"export uses {', '.join(gltf.get('extensionsUsed', [])) or 'no extensions'}")
        scene = json.loads(run([clipblur, "scene-json", job]))
        check_materials(scene, report)
        check_camera(scene, truth, report)
        check_poses(clipblur, job, truth, report)
        if not args.skip_render:
            a = out / "stochastic_a.exr"
            sa, _ = render(clipblur, job, a, args.threads, {"render.method": "stochastic", "render.samples": args.spp,
                                                            "render.seed": 1})
            sb, ess = render(clipblur, job, out / "stochastic_b.exr", args.threads,
                             {"render.method": "stochastic", "render.samples": args.spp, "render.seed": 2}, a)
            sc, ecs = render(clipblur, job, out / "clipped.exr", args.threads, {}, a)
            bias = math.sqrt(max(0.0, ecs * ecs - ess * ess / 2.0))
            print(f"  clipped (job settings) {sc:.1f} s; stochastic {args.spp} spp {sa:.1f} s and {sb:.1f} s "
                  f"({args.threads} threads, 320x180)")
            print(f"  RMSE clipped vs stochastic {ecs:.5f}; stochastic vs stochastic (seeds 1, 2) {ess:.5f}; "
                  f"clipped's bias about {bias:.5f}")
            # The same frame with the shutter closed to an instant: what is left is shading, not motion.
            still = {"shutter.open": 0, "shutter.close": 0}
            ref = out / "still_stochastic.exr"
            render(clipblur, job, ref, args.threads, {**still, "render.method": "stochastic", "render.samples": args.spp,
                                                      "render.seed": 1})
            _, estill = render(clipblur, job, out / "still_clipped.exr", args.threads, still, ref)
            print(f"  still frame (shutter 0 .. 0): RMSE clipped vs stochastic {estill:.5f}")
    finally:
        if temp:
            temp.cleanup()
    print("PASS" if not report.failures else f"FAIL: {len(report.failures)} check(s)")
    return 0 if not report.failures else 1


if __name__ == "__main__":
    sys.exit(main())
