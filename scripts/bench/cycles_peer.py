#!/usr/bin/env python3
"""Blender Cycles as an external peer of clipblur's benchmark (scripts/bench/peers.py --cycles).

render(config, spp, image, threads, size) turns a clipblur job into a Blender scene through
`clipblur scene-json` (the loaded, expanded scene: meshes, keys, materials) and renders frame `frames.first`
headless with Cycles into a float RGBA EXR at `image`; it returns the seconds of Cycles' sampling loop
(scene sync, BVH build and kernel loading excluded, see loop_seconds). Blender is installed here, and only
here, when it is not on PATH (Debian's `blender`, 3.4, and python3-numpy).

The same file is the script Blender runs: `blender -b --factory-startup -P cycles_peer.py -- SCENE.json
IMAGE SPP THREADS TIMING.json SHUTTER_FIX(0|1) SEED`. Standalone: `scripts/bench/cycles_peer.py JOB.yaml --spp 64 --out x.exr
[--width 320 --height 180] [--threads 2] [--seed 0] [--no-shutter-fix]`.

How the scene follows clipblur's conventions (docs/performance.md, "Cycles as a peer"):
- Camera: clipblur's basis e1 = up (orthogonal to view), e2 = e3 x e1 (image right), e3 = view. A Blender
  camera looks down local -Z with +Y up and +X right, so its rotation has columns (e2, e1, -e3); vfov with
  sensor_fit VERTICAL. Objects: object-to-world = T R S, Blender's own order for location, quaternion and
  scale. Between keys clipblur moves linearly and turns at a constant rate (slerp): the path is sampled
  here (16 keys per key interval, slerp in Python) and keyed LINEAR, so Blender's component-wise quaternion
  lerp stays on the arc; Cycles itself then samples the animation at its motion steps (objects: 2^3 + 1)
  and interpolates the decomposed transforms between them (slerp), which is exact while the shutter lies
  in one key interval, where the path is one slerp; across camera keys inside the shutter it is a close
  approximation only.
- Deformation keys: one relative shape key per key with weights that are the linear-interpolation hat
  functions (Cycles exports them as deformation motion and interpolates linearly between its steps).
  Refused on an object whose transform also turns: Cycles renders that combination biased
  (check_supported).
- Shutter: frame `first` spans [first + open, first + close] frames. Blender frame F0 = 1 is mapped to
  clipblur time first + open and motion_blur_position is START. Cycles 3.4 draws a sample's time through
  a 256-entry table (its shutter curve's inverted CDF) that leans towards the shutter's start, so the
  shutter is set to (close - open) * 65536/65025 = (256/255)^2 frames and the keys are extended past the
  close linearly (the last segment continued): on spin_pan_checker at 1024 spp this takes Cycles against
  clipblur from 0.0064 RMSE to 0.0050, clipblur's own seed-to-seed noise (docs/performance.md). The
  extension is not in clipblur's path, which holds after the last key: Cycles' times past close are
  what the fix assumes it (almost) never draws. --no-shutter-fix turns it off.
- Film: Box filter 1 px, Standard view transform, no look, no denoising, no adaptive sampling, fixed
  seed, max bounces 0 (direct light only), film transparent and the world black: RGBA premultiplied
  with no background in the colour, as clipblur writes its EXR (docs/config.md, "What the EXR holds"),
  so RGB compares directly (baking film.background in here only would differ by (1 - A) x background
  at every blurred edge). Objects are visible to
  camera and shadow rays only and no material is sampled as a light, so the ambient emission lights
  nothing (see the object loop).
- Shading: albedo is clipblur's checker/stripe built from math nodes on the rest-mesh position, a point
  attribute interpolated over the triangle exactly as clipblur does (not the Texture Coordinate node's
  Object output: see _material). Emission(albedo * ambient) is added to every surface; with
  lights a Diffuse BSDF(albedo) is added, suns of strength pi * intensity (Cycles' diffuse BSDF is
  albedo / pi) and point lights of power 4 pi^2 * intensity (radiant intensity P / 4 pi, then albedo / pi),
  radius and angle 0. Shadows off unless the job's render.shadows is on. One-sided materials render back
  faces black, as clipblur does.
"""

import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

SUBKEYS = 16                      # intermediate keys per key interval
SHUTTER_FIX = 65536.0 / 65025.0   # (256/255)^2, Cycles 3.4's shutter table (see above)
FIRST_BLENDER_FRAME = 1
REST_ATTRIBUTE = "clipblur_rest"   # point attribute: the rest-mesh position
last_timing = None                # the last render's timing record (loop, total, whether the loop was seen)
OBJECT_MOTION_STEPS = 3           # Cycles: 2^3 + 1 = 9 motion samples per object


# ---------------------------------------------------------------------------------------------------
# Host side (plain python3): install, export the scene, run blender.

def ensure_blender():
    """Installs Debian's blender (and numpy for its Python) when `blender` is not on PATH."""
    path = shutil.which("blender")
    if path:
        return path
    print("cycles_peer: blender not on PATH: apt-get install blender python3-numpy", file=sys.stderr, flush=True)
    subprocess.run(["apt-get", "update"], check=True)
    subprocess.run(["apt-get", "install", "-y", "--no-install-recommends", "blender", "python3-numpy"], check=True)
    path = shutil.which("blender")
    if not path:
        raise RuntimeError("blender is still not on PATH after apt-get install")
    return path


def _clipblur():
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    import benchlib  # noqa: E402
    return benchlib.find_clipblur()


def scene_json(config, size=None, clipblur=None):
    cmd = [clipblur or _clipblur(), "scene-json", str(config)]
    if size:
        cmd += ["--set", f"film.width={size[0]}", "--set", f"film.height={size[1]}"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({r.returncode}): {r.stderr.strip()}")
    return json.loads(r.stdout)


def check_supported(scene):
    """Refuses what this peer does not render like clipblur: deformation keys on an object whose transform
    keys turn it. Measured (a bent sheet, 3 deformation keys, 40 degree turn, 128 spp, 320x180): Cycles
    against clipblur 0.0126 RMSE where Cycles against itself (another seed) is 0.0082 and clipblur 0.0028,
    so about 0.011 of bias, unchanged with 33 motion steps instead of 9; deformation alone (0.0029 against
    0.0037 and 0.0016) and deformation with translation (0.0100 against 0.0136 and 0.0037) are within
    noise, as is the turn without deformation (0.0059 against 0.0078 and 0.0023). Two-sided, the bias
    stays (0.0133 against 0.0101 and 0.0029), and clipblur's accumulation method (128 still renders)
    agrees with its stochastic one (0.0023) but not with Cycles (0.0135): the bias is Cycles'.
    A shutter curve is refused too: Blender's own curve is a 256-entry table whose CDF this peer already
    corrects for a box (the shutter fix above), and nothing here maps clipblur's curve onto it.
    Unlit and emissive materials are refused: this peer's node trees were never checked against them (no
    Blender on the machine that added them). So are exact glTF motions (scene-json's exact_motion: a wheel
    under a moving car, a skin; they have no keys here and were rendered still), image textures (no node
    tree here builds them) and shading normals (faces render flat here)."""
    if scene["shutter"].get("curve"):
        raise RuntimeError("a shutter curve is not supported by the Cycles peer (a box shutter only)")
    for o in scene["objects"]:
        if o.get("smooth"):
            raise RuntimeError(f"object {o['name']}: shading normals are not supported by the Cycles peer (flat only)")
        if o.get("exact_motion"):
            raise RuntimeError(f"object {o['name']}: glTF motion followed exactly (no keys to rebuild it from) "
                               "is not supported by the Cycles peer")
    for i, m in enumerate(scene["materials"]):
        if m.get("image") or m.get("emission_image"):
            raise RuntimeError(f"material {i}: image textures are not supported by the Cycles peer")
        if m.get("unlit") or any(c != 0.0 for c in m.get("emission", [0.0])):
            raise RuntimeError(f"material {i}: unlit and emissive materials are not supported by the Cycles peer")
    for o in scene["objects"]:
        if not o["deformation"]:
            continue
        rotations = [tuple(k["rotate"]) for k in o["transform"]]
        if any(r != rotations[0] for r in rotations[1:]):
            raise RuntimeError(f"object '{o['name']}': deformation keys together with a turning transform are "
                               "not supported by the Cycles peer (Cycles renders them biased, see check_supported)")


def render(config, spp, image, threads, size, shutter_fix=True, clipblur=None, seed=0):
    """Renders `config` at `size` with Cycles at `spp` into `image`; returns the sampling loop's seconds."""
    blender = ensure_blender()
    scene = scene_json(config, size, clipblur)
    check_supported(scene)
    image = Path(image).resolve()
    image.parent.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="cycles_peer_") as tmp:
        scene_file = Path(tmp) / "scene.json"
        timing_file = Path(tmp) / "timing.json"
        scene_file.write_text(json.dumps(scene))
        cmd = [blender, "-b", "--factory-startup", "-noaudio", "-P", str(Path(__file__).resolve()), "--",
               str(scene_file), str(image), str(spp), str(threads), str(timing_file), "1" if shutter_fix else "0", str(seed)]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0 or not timing_file.is_file():
            raise RuntimeError(f"blender failed ({r.returncode}): {' '.join(cmd)}\n{r.stdout[-3000:]}\n{r.stderr[-3000:]}")
        timing = json.loads(timing_file.read_text())
    timing.update(loop_seconds(r.stdout, spp))
    global last_timing
    last_timing = timing
    return timing["loop_seconds"]


_STATUS = re.compile(r"\| Time:(\d+):(\d+\.\d+) \|.*\| Sample (\d+)/(\d+)\s*$")


def loop_seconds(stdout, spp):
    """Cycles' sampling loop from Blender's status lines: the elapsed Time (10 ms resolution) at
    "Sample 0/N", printed once sync, BVH build and kernel loading are done, to that at "Sample N/N"."""
    start = end = None
    for line in stdout.splitlines():
        m = _STATUS.search(line)
        if not m:
            continue
        t = 60.0 * int(m.group(1)) + float(m.group(2))
        if int(m.group(3)) == 0 and start is None:
            start = t
        if int(m.group(3)) == int(m.group(4)) == spp:
            end = t
    if start is None or end is None:
        raise RuntimeError("no 'Sample 0/N' and 'Sample N/N' status lines in blender's output")
    return {"loop_seconds": end - start, "loop_start": start, "loop_end": end}


# ---------------------------------------------------------------------------------------------------
# Path math shared by both sides (plain Python, no numpy): quaternions are (w, x, y, z).

def _sub(a, b): return [a[i] - b[i] for i in range(3)]
def _dot(a, b): return sum(a[i] * b[i] for i in range(3))
def _cross(a, b): return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
def _scale(a, s): return [x * s for x in a]
def _lerp(a, b, f): return [a[i] + f * (b[i] - a[i]) for i in range(len(a))]


def _normalize(v):
    n = math.sqrt(sum(x * x for x in v))
    return [x / n for x in v]


def _qmul(a, b):
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return [aw * bw - ax * bx - ay * by - az * bz, aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw]


def _slerp(q0, q1, f):
    """Constant-rate rotation from q0 to q1 along the shorter arc; any real f (f > 1 extrapolates)."""
    if sum(q0[i] * q1[i] for i in range(4)) < 0.0:
        q1 = [-x for x in q1]
    rel = _qmul(q1, [q0[0], -q0[1], -q0[2], -q0[3]])   # q1 q0^-1
    w = max(-1.0, min(1.0, rel[0]))
    half = math.acos(w)
    s = math.sin(half)
    if s < 1e-15:
        return list(q0)
    axis = [rel[1] / s, rel[2] / s, rel[3] / s]
    h = half * f
    return _normalize(_qmul([math.cos(h), axis[0] * math.sin(h), axis[1] * math.sin(h), axis[2] * math.sin(h)], q0))


def _matrix_to_quat(c0, c1, c2):
    """Rotation matrix given by its columns -> unit quaternion (w, x, y, z)."""
    m = [[c0[0], c1[0], c2[0]], [c0[1], c1[1], c2[1]], [c0[2], c1[2], c2[2]]]
    tr = m[0][0] + m[1][1] + m[2][2]
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        q = [0.25 * s, (m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s]
    elif m[0][0] > m[1][1] and m[0][0] > m[2][2]:
        s = math.sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]) * 2
        q = [(m[2][1] - m[1][2]) / s, 0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s]
    elif m[1][1] > m[2][2]:
        s = math.sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]) * 2
        q = [(m[0][2] - m[2][0]) / s, (m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s]
    else:
        s = math.sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]) * 2
        q = [(m[1][0] - m[0][1]) / s, (m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s]
    return _normalize(q)


def camera_pose(key):
    """clipblur camera key -> (position, Blender quaternion): columns (e2, e1, -e3) = local (X, Y, Z)."""
    e3 = _normalize(key["view"])
    up = key["up"]
    e1 = _normalize(_sub(up, _scale(e3, _dot(up, e3))))
    e2 = _cross(e3, e1)
    return list(key["position"]), _matrix_to_quat(e2, e1, _scale(e3, -1.0))


def _bracket(times, t, close):
    """(i, f) of the key segment for time t: clipblur holds outside the keys, except that past `close` the
    segment containing close is continued (f > 1), the shutter fix's linear extension."""
    n = len(times)
    if n == 1:
        return 0, 0.0
    if t > close and times[0] < close <= times[-1]:
        i = next(k for k in range(n - 1) if times[k] < close <= times[k + 1])
        return i, (t - times[i]) / (times[i + 1] - times[i])
    if t <= times[0]:
        return 0, 0.0
    if t >= times[-1]:
        return n - 2, 1.0
    i = next(k for k in range(n - 1) if times[k] <= t < times[k + 1])
    return i, (t - times[i]) / (times[i + 1] - times[i])


def sample_times(key_times, t0, t1):
    """Times to key in [t0, t1]: the ends, the keys inside, and SUBKEYS per key interval (at least 16 over
    the window)."""
    times = {t0, t1}
    times.update(t for t in key_times if t0 < t < t1)
    steps = [b - a for a, b in zip(key_times, key_times[1:]) if b > a]
    step = min(steps + [t1 - t0]) / SUBKEYS if t1 > t0 else 1.0
    n = min(4096, int(math.ceil((t1 - t0) / step)))
    times.update(t0 + (t1 - t0) * k / n for k in range(1, n))
    return sorted(times)


# ---------------------------------------------------------------------------------------------------
# Blender side (runs inside blender -b -P this file -- ...).

def _albedo_nodes(nt, material, coord_socket):
    """Node output giving clipblur's albedo at coord_socket (object-space rest position)."""
    base = list(material["base_color"])
    tex = material["texture"]
    if tex["kind"] == "none":
        rgb = nt.nodes.new("ShaderNodeRGB")
        rgb.outputs[0].default_value = base + [1.0]
        return rgb.outputs[0]

    def vmath(op, a, b=None):
        n = nt.nodes.new("ShaderNodeVectorMath")
        n.operation = op
        for i, v in enumerate([a, b]):
            if v is None:
                continue
            if isinstance(v, (list, tuple)):
                n.inputs[i].default_value = v
            else:
                nt.links.new(v, n.inputs[i])
        return n.outputs["Value" if op == "DOT_PRODUCT" else "Vector"]

    def math_node(op, a, b):
        n = nt.nodes.new("ShaderNodeMath")
        n.operation = op
        for i, v in enumerate([a, b]):
            if isinstance(v, (int, float)):
                n.inputs[i].default_value = v
            else:
                nt.links.new(v, n.inputs[i])
        return n.outputs[0]

    s = float(tex["scale"])
    cells = vmath("FLOOR", vmath("DIVIDE", coord_socket, (s, s, s)))
    weights = (1.0, 1.0, 1.0) if tex["kind"] == "checker" else (1.0, 0.0, 0.0)
    total = vmath("DOT_PRODUCT", cells, weights)                              # integer-valued
    parity = math_node("SUBTRACT", total, math_node("MULTIPLY", math_node("FLOOR", math_node("MULTIPLY", total, 0.5), 0.0), 2.0))
    color2 = list(tex["color2"])
    diff = [color2[i] - base[i] for i in range(3)]
    scaled = nt.nodes.new("ShaderNodeVectorMath")
    scaled.operation = "SCALE"
    scaled.inputs[0].default_value = diff
    nt.links.new(parity, scaled.inputs["Scale"])
    return vmath("ADD", scaled.outputs["Vector"], base)                       # odd -> color2, even -> base


def _material(bpy, scene, index, lit):
    m = scene["materials"][index]
    mat = bpy.data.materials.new(f"clipblur_{index}")
    mat.use_nodes = True
    # Not a mesh light: the ambient emission would otherwise share next-event estimation with the real
    # lights (every triangle a light), doubling the noise of the lit scene and adding nothing clipblur has.
    mat.cycles.sample_as_light = False
    nt = mat.node_tree
    nt.nodes.clear()
    # The rest-mesh position interpolated over the triangle, as clipblur computes it, not the Texture
    # Coordinate node's Object output: that one is the hit point taken back through the inverse transform
    # in float, which lands at +-1e-7 off a mesh lying in a cell plane (spin_pan_checker's wall is the
    # object's y = 0 plane) and flips the parity there.
    attr = nt.nodes.new("ShaderNodeAttribute")
    attr.attribute_type = "GEOMETRY"
    attr.attribute_name = REST_ATTRIBUTE
    coord = attr.outputs["Vector"]
    albedo = _albedo_nodes(nt, m, coord)
    ambient = nt.nodes.new("ShaderNodeVectorMath")
    ambient.operation = "MULTIPLY"
    nt.links.new(albedo, ambient.inputs[0])
    ambient.inputs[1].default_value = scene["ambient"]
    emission = nt.nodes.new("ShaderNodeEmission")
    emission.inputs["Strength"].default_value = 1.0
    nt.links.new(ambient.outputs["Vector"], emission.inputs["Color"])
    shader = emission.outputs[0]
    if lit:
        diffuse = nt.nodes.new("ShaderNodeBsdfDiffuse")
        diffuse.inputs["Roughness"].default_value = 0.0
        nt.links.new(albedo, diffuse.inputs["Color"])
        add = nt.nodes.new("ShaderNodeAddShader")
        nt.links.new(diffuse.outputs[0], add.inputs[0])
        nt.links.new(emission.outputs[0], add.inputs[1])
        shader = add.outputs[0]
    if not m["two_sided"]:  # clipblur shades back faces black
        black = nt.nodes.new("ShaderNodeEmission")
        black.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
        geometry = nt.nodes.new("ShaderNodeNewGeometry")
        mix = nt.nodes.new("ShaderNodeMixShader")
        nt.links.new(geometry.outputs["Backfacing"], mix.inputs["Fac"])
        nt.links.new(shader, mix.inputs[1])
        nt.links.new(black.outputs[0], mix.inputs[2])
        shader = mix.outputs[0]
    out = nt.nodes.new("ShaderNodeOutputMaterial")
    nt.links.new(shader, out.inputs["Surface"])
    return mat


def _key_linear(action_owner):
    anim = action_owner.animation_data
    if anim and anim.action:
        for fc in anim.action.fcurves:
            for kp in fc.keyframe_points:
                kp.interpolation = "LINEAR"
            fc.extrapolation = "CONSTANT"


def _blender_main(argv):
    import time
    import bpy

    scene_file, image, spp, threads, timing_file, shutter_fix, seed = argv
    spp, threads, shutter_fix, seed = int(spp), int(threads), shutter_fix == "1", int(seed)
    scene = json.loads(Path(scene_file).read_text())

    for obj in list(bpy.data.objects):  # the factory startup's cube, light and camera
        bpy.data.objects.remove(obj)
    bs = bpy.context.scene
    bs.render.engine = "CYCLES"
    cy = bs.cycles
    cy.device = "CPU"
    cy.samples = spp
    cy.use_adaptive_sampling = False
    cy.use_denoising = False
    cy.seed = seed
    cy.use_animated_seed = False
    cy.pixel_filter_type = "BOX"
    cy.filter_width = 1.0
    cy.max_bounces = 0
    cy.diffuse_bounces = cy.glossy_bounces = cy.transmission_bounces = cy.volume_bounces = 0
    cy.transparent_max_bounces = 0
    cy.sample_clamp_direct = cy.sample_clamp_indirect = 0.0
    cy.caustics_reflective = cy.caustics_refractive = False
    cy.film_exposure = 1.0
    bs.render.threads_mode = "FIXED"
    bs.render.threads = threads
    film = scene["film"]
    bs.render.resolution_x, bs.render.resolution_y = film["width"], film["height"]
    bs.render.resolution_percentage = 100
    bs.render.pixel_aspect_x = bs.render.pixel_aspect_y = 1.0
    bs.render.film_transparent = True  # premultiplied RGBA, as clipblur's EXR
    bs.view_settings.view_transform = "Standard"
    bs.view_settings.look = "None"
    bs.view_settings.exposure = 0.0
    bs.view_settings.gamma = 1.0
    settings = bs.render.image_settings
    settings.file_format = "OPEN_EXR"
    settings.color_mode = "RGBA"
    settings.color_depth = "32"
    settings.exr_codec = "ZIP"
    bs.render.use_compositing = False
    bs.render.use_sequencer = False

    # Time: Blender frame FIRST_BLENDER_FRAME is clipblur's time first + open.
    t_open = scene["frame"] + scene["shutter"]["open"]
    t_close = scene["frame"] + scene["shutter"]["close"]
    length = t_close - t_open
    blender_length = length * (SHUTTER_FIX if shutter_fix else 1.0)
    t_end = t_open + blender_length
    bframe = lambda t: FIRST_BLENDER_FRAME + (t - t_open)  # noqa: E731
    bs.frame_start = bs.frame_end = bs.frame_current = FIRST_BLENDER_FRAME
    bs.render.fps = 24
    moving_blur = blender_length > 0.0
    bs.render.use_motion_blur = moving_blur
    if moving_blur:
        bs.render.motion_blur_shutter = blender_length
    cy.motion_blur_position = "START"

    # World: black, so it lights nothing (as in clipblur); the transparent film leaves it out of the
    # colour where camera rays miss, and film.background is for the compositor, as in clipblur's EXR.
    world = bpy.data.worlds.new("clipblur_world")
    bs.world = world
    world.use_nodes = True
    wt = world.node_tree
    wt.nodes.clear()
    black = wt.nodes.new("ShaderNodeBackground")
    black.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    wout = wt.nodes.new("ShaderNodeOutputWorld")
    wt.links.new(black.outputs[0], wout.inputs["Surface"])
    world.cycles.sampling_method = "NONE"

    # Camera.
    cam = scene["camera"]
    cam_data = bpy.data.cameras.new("clipblur_camera")
    cam_data.type = "PERSP"
    cam_data.sensor_fit = "VERTICAL"
    cam_data.sensor_height = 24.0
    cam_data.lens = 0.5 * cam_data.sensor_height / math.tan(0.5 * math.radians(cam["vfov"]))
    cam_data.shift_x = cam_data.shift_y = 0.0
    cam_data.clip_start = 1e-3
    cam_data.clip_end = 1e6
    cam_obj = bpy.data.objects.new("clipblur_camera", cam_data)
    bs.collection.objects.link(cam_obj)
    bs.camera = cam_obj
    cam_obj.rotation_mode = "QUATERNION"
    keys = cam["keys"]
    key_times = [k["time"] for k in keys]
    poses = [camera_pose(k) for k in keys]
    previous = None
    for t in sample_times(key_times, t_open, t_end):
        i, f = _bracket(key_times, t, t_close)
        if len(keys) == 1:
            position, quat = poses[0]
        else:
            position = _lerp(poses[i][0], poses[i + 1][0], f)
            quat = _slerp(poses[i][1], poses[i + 1][1], f)
        if previous is not None and sum(a * b for a, b in zip(previous, quat)) < 0:
            quat = [-x for x in quat]  # keep neighbouring keys on one hemisphere for the component lerp
        previous = quat
        cam_obj.location = position
        cam_obj.rotation_quaternion = quat
        cam_obj.keyframe_insert("location", frame=bframe(t))
        cam_obj.keyframe_insert("rotation_quaternion", frame=bframe(t))
    _key_linear(cam_obj)

    # Objects.
    lit = len(scene["lights"]) > 0
    materials = {}
    for o_index, o in enumerate(scene["objects"]):
        deformed = len(o["deformation"]) > 0
        mesh = bpy.data.meshes.new(f"clipblur_mesh_{o_index}")
        mesh.from_pydata([tuple(p) for p in o["positions"]], [], [tuple(t) for t in o["triangles"]])
        mesh.validate(clean_customdata=False)
        if len(mesh.polygons) != len(o["triangles"]):
            raise RuntimeError(f"object {o['name']}: blender kept {len(mesh.polygons)} of {len(o['triangles'])} triangles")
        for poly in mesh.polygons:
            poly.use_smooth = False
        rest = mesh.attributes.new(REST_ATTRIBUTE, "FLOAT_VECTOR", "POINT")
        rest.data.foreach_set("vector", [c for p in o["positions"] for c in p])
        if o["material"] not in materials:
            materials[o["material"]] = _material(bpy, scene, o["material"], lit)
        mesh.materials.append(materials[o["material"]])
        obj = bpy.data.objects.new(o["name"] or f"object_{o_index}", mesh)
        bs.collection.objects.link(obj)
        obj.rotation_mode = "QUATERNION"
        obj.cycles.motion_steps = OBJECT_MOTION_STEPS
        # Seen by camera and shadow rays only. Cycles continues a path one segment past max_bounces to pick
        # up emission there, so the ambient emission of one surface would light the others (the box lit
        # the floor beneath it, +0.06 at worst); clipblur's light comes from its lights alone.
        obj.visible_diffuse = obj.visible_glossy = obj.visible_transmission = obj.visible_volume_scatter = False
        tkeys = o["transform"]
        if tkeys:
            tk_times = [k["time"] for k in tkeys]
            previous = None
            for t in sample_times(tk_times, t_open, t_end):
                i, f = _bracket(tk_times, t, t_close)
                if len(tkeys) == 1:
                    k0 = tkeys[0]
                    translate, quat, scale = k0["translate"], _normalize(k0["rotate"]), k0["scale"]
                else:
                    k0, k1 = tkeys[i], tkeys[i + 1]
                    translate = _lerp(k0["translate"], k1["translate"], f)
                    quat = _slerp(_normalize(k0["rotate"]), _normalize(k1["rotate"]), f)
                    scale = _lerp(k0["scale"], k1["scale"], f)
                if previous is not None and sum(a * b for a, b in zip(previous, quat)) < 0:
                    quat = [-x for x in quat]
                previous = quat
                obj.location, obj.rotation_quaternion, obj.scale = translate, quat, scale
                for prop in ("location", "rotation_quaternion", "scale"):
                    obj.keyframe_insert(prop, frame=bframe(t))
            _key_linear(obj)
        if deformed:
            # Relative shape keys, one per deformation key, weighted by the hat functions of linear
            # interpolation between the keys (held outside them, continued past the close for the fix).
            obj.shape_key_add(name="rest", from_mix=False)
            dkeys = o["deformation"]
            d_times = [k["time"] for k in dkeys]
            blocks = []
            for j, dk in enumerate(dkeys):
                sk = obj.shape_key_add(name=f"key_{j}", from_mix=False)
                sk.data.foreach_set("co", [c for p in dk["positions"] for c in p])
                sk.slider_min, sk.slider_max = -10.0, 10.0
                blocks.append(sk)
            for t in sample_times(d_times, t_open, t_end):
                i, f = _bracket(d_times, t, t_close)
                weights = [0.0] * len(dkeys)
                if len(dkeys) == 1:
                    weights[0] = 1.0
                else:
                    weights[i], weights[i + 1] = 1.0 - f, f
                for sk, w in zip(blocks, weights):
                    sk.value = w
                    sk.keyframe_insert("value", frame=bframe(t))
            _key_linear(mesh.shape_keys)

    # Lights: clipblur's irradiance is intensity * color * cos (/ d^2); Cycles' diffuse BSDF is albedo/pi.
    for l_index, light in enumerate(scene["lights"]):
        if light["type"] == "directional":
            data = bpy.data.lights.new(f"clipblur_light_{l_index}", type="SUN")
            data.energy = math.pi * light["intensity"]
            data.angle = 0.0
        else:
            data = bpy.data.lights.new(f"clipblur_light_{l_index}", type="POINT")
            data.energy = 4.0 * math.pi * math.pi * light["intensity"]
            data.shadow_soft_size = 0.0
        data.color = light["color"]
        data.specular_factor = 0.0
        data.cycles.cast_shadow = bool(scene["render"]["shadows"])
        lobj = bpy.data.objects.new(f"clipblur_light_{l_index}", data)
        bs.collection.objects.link(lobj)
        if light["type"] == "directional":
            # A sun shines along its local -Z: rotate -Z onto the travel direction.
            d = _normalize(light["direction"])
            helper = [1.0, 0.0, 0.0] if abs(d[0]) < 0.9 else [0.0, 1.0, 0.0]
            z = _scale(d, -1.0)
            x = _normalize(_cross(helper, z))
            y = _cross(z, x)
            lobj.rotation_mode = "QUATERNION"
            lobj.rotation_quaternion = _matrix_to_quat(x, y, z)
        else:
            lobj.location = light["position"]

    bs.render.filepath = str(image)
    bs.render.use_file_extension = False
    begin = time.perf_counter()
    bpy.ops.render.render(write_still=True)
    Path(timing_file).write_text(json.dumps({"render_call_seconds": time.perf_counter() - begin}))


def _standalone():
    import argparse
    ap = argparse.ArgumentParser(description="Render a clipblur job with Blender Cycles")
    ap.add_argument("job")
    ap.add_argument("--spp", type=int, default=64)
    ap.add_argument("--out", required=True)
    ap.add_argument("--width", type=int)
    ap.add_argument("--height", type=int)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--no-shutter-fix", action="store_true")
    ap.add_argument("--clipblur")
    args = ap.parse_args()
    size = (args.width, args.height) if args.width and args.height else None
    seconds = render(args.job, args.spp, args.out, args.threads, size, shutter_fix=not args.no_shutter_fix,
                     clipblur=args.clipblur, seed=args.seed)
    print(f"cycles loop seconds {seconds:.2f} (loop from {last_timing['loop_start']:.2f} s to "
          f"{last_timing['loop_end']:.2f} s into the render call of {last_timing['render_call_seconds']:.2f} s)")


if __name__ == "__main__":
    if "--" in sys.argv and "bpy" in sys.modules or os.environ.get("CYCLES_PEER_IN_BLENDER"):
        _blender_main(sys.argv[sys.argv.index("--") + 1:])
    else:
        _standalone()
