#!/usr/bin/env python3
"""Writes the shipped shot's glTF 2.0 street (configs/shot/): street.gltf, street.bin, its PNG textures and
street_plain.gltf.

A road between two sidewalks and a row of building facades, three cars passing at different speeds and
directions (each car node translates; its four wheel nodes are children that spin, rolling without
slipping), a skinned walker (eight joints: hips, knees, shoulders, spine) walking along the near sidewalk,
and a camera node that pans and dollies (perspective yfov, 16:9). Wheels and the walker carry NORMAL
(smooth shading); road, sidewalks, facades and wheel caps carry TEXCOORD_0 and a baseColorTexture.
Animation spans glTF seconds 0 .. 2 (48 frames at 24 fps). street_plain.gltf is the same street without
textures and normals (for the plain Embree loop, which shades neither).

Standard library only; the output is the same bytes on every run (`--check` compares against the
committed files instead of writing, exit 1 on a difference).

    scripts/shot/make_street_gltf.py [--out configs/shot] [--check]
"""

import argparse
import json
import math
import struct
import sys
import zlib
from collections import namedtuple
from pathlib import Path

OUT = Path(__file__).resolve().parents[2] / "configs" / "shot"
DURATION = 2.0  # seconds of animation
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963
FLOAT, UNSIGNED_BYTE, UNSIGNED_SHORT = 5126, 5121, 5123
WIDTH = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4, "MAT4": 16}


# ---- PNG (8-bit RGB, filter 0 on every row) ----

def png(width, height, pixel):
    rows = b"".join(b"\x00" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b"")


def grain(x, y, seed):
    """Deterministic per-texel noise in [0, 1): an integer hash, no random module state."""
    h = (x * 73856093 ^ y * 19349663 ^ seed * 83492791) & 0xFFFFFFFF
    h = (h ^ (h >> 13)) * 1274126177 & 0xFFFFFFFF
    return ((h ^ (h >> 16)) & 0xFFFF) / 65536.0


def clamp8(v):
    return max(0, min(255, int(round(v))))


def asphalt(x, y):
    """64x64; u runs along the road (one tile = 6 m), v across it: a dashed centre line at v = 0.5."""
    g = 70 + 30 * grain(x, y, 1)
    if 30 <= y <= 33 and x < 32:
        g = 225
    return (clamp8(g), clamp8(g), clamp8(g + 4))


def paving(x, y):
    """32x32: one paving slab (1.5 m) with dark joints."""
    g = 150 + 25 * grain(x, y, 2)
    if x in (0, 31) or y in (0, 31):
        g = 85
    return (clamp8(g + 6), clamp8(g), clamp8(g - 8))


def facade(x, y):
    """32x32: one bay (2 m wide, one 3 m storey): light wall, a window with a frame and a sill. Coarse on
    purpose: at the shot's 640x360 a texel covers about 1.7 pixels, so textures are magnified."""
    g = 200 + 30 * grain(x, y, 3)
    if 8 <= x < 24 and 6 <= y < 22:
        if 9 <= x < 23 and 7 <= y < 21 and x != 16:
            shade = 0.5 + 0.4 * (y - 7) / 14
            return (clamp8(60 * shade), clamp8(90 * shade), clamp8(140 * shade))
        return (235, 235, 230)
    if 7 <= x < 25 and y == 22:
        return (120, 110, 100)
    return (clamp8(g), clamp8(g * 0.9), clamp8(g * 0.8))


def wheel(x, y):
    """16x16: a disc (the caps' UVs) of tyre, rim and five spokes; the tread reads the corner (tyre)."""
    dx, dy = (x + 0.5) / 8.0 - 1.0, (y + 0.5) / 8.0 - 1.0
    r = math.hypot(dx, dy)
    if r > 0.75:
        return (25, 25, 28)
    if r > 0.6 or r < 0.2:
        return (200, 200, 205)
    a = math.atan2(dy, dx) % (2 * math.pi / 5)
    if abs(a - math.pi / 5) > 0.75:
        return (200, 200, 205)
    return (45, 45, 50)


TEXTURES = {"asphalt.png": (64, 64, asphalt), "paving.png": (32, 32, paving), "facade.png": (32, 32, facade),
            "wheel.png": (16, 16, wheel)}


# ---- binary buffer and accessors ----

class Gltf:
    def __init__(self):
        self.blob = bytearray()
        self.doc = {"asset": {"version": "2.0", "generator": "clipblur scripts/shot/make_street_gltf.py"},
                    "buffers": [], "bufferViews": [], "accessors": [], "images": [], "samplers": [],
                    "textures": [], "materials": [], "meshes": [], "nodes": [], "skins": [], "cameras": [],
                    "animations": [{"name": "street", "samplers": [], "channels": []}], "scene": 0,
                    "scenes": [{"name": "street", "nodes": []}]}

    def view(self, data, target=None):
        while len(self.blob) % 4:
            self.blob.append(0)
        v = {"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(data)}
        if target:
            v["target"] = target
        self.blob.extend(data)
        self.doc["bufferViews"].append(v)
        return len(self.doc["bufferViews"]) - 1

    def floats(self, values, kind, target=None, bounds=False):
        flat = [float(v) for item in values for v in (item if isinstance(item, (tuple, list)) else (item,))]
        data = struct.pack("<%df" % len(flat), *flat)
        acc = {"bufferView": self.view(data, target), "componentType": FLOAT, "count": len(flat) // WIDTH[kind],
               "type": kind}
        if bounds:  # min/max of the float32 values, as the validator recomputes them
            w = WIDTH[kind]
            stored = struct.unpack("<%df" % len(flat), data)
            acc["min"] = [min(stored[i::w]) for i in range(w)]
            acc["max"] = [max(stored[i::w]) for i in range(w)]
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def indices(self, triangles):
        flat = [i for t in triangles for i in t]
        acc = {"bufferView": self.view(struct.pack("<%dH" % len(flat), *flat), ELEMENT_ARRAY_BUFFER),
               "componentType": UNSIGNED_SHORT, "count": len(flat), "type": "SCALAR"}
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def joints(self, quads):
        flat = [j for q in quads for j in q]
        acc = {"bufferView": self.view(bytes(flat), ARRAY_BUFFER), "componentType": UNSIGNED_BYTE,
               "count": len(quads), "type": "VEC4"}
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def add(self, kind, item):
        self.doc[kind].append(item)
        return len(self.doc[kind]) - 1

    def mesh(self, name, geometry, material):
        attributes = {"POSITION": geometry["POSITION"]}
        for key in ("NORMAL", "TEXCOORD_0", "JOINTS_0", "WEIGHTS_0"):
            if key in geometry:
                attributes[key] = geometry[key]
        return self.add("meshes", {"name": name, "primitives": [
            {"attributes": attributes, "indices": geometry["indices"], "material": material}]})

    def animate(self, node, path, times, values):
        kind = {"translation": "VEC3", "rotation": "VEC4"}[path]
        anim = self.doc["animations"][0]
        anim["samplers"].append({"input": self.floats(times, "SCALAR", bounds=True),
                                 "output": self.floats(values, kind), "interpolation": "LINEAR"})
        anim["channels"].append({"sampler": len(anim["samplers"]) - 1, "target": {"node": node, "path": path}})


def geometry(g, mesh):
    """Writes a mesh dict {positions, normals?, uvs?, triangles, joints?, weights?} as accessors."""
    out = {"POSITION": g.floats(mesh["positions"], "VEC3", ARRAY_BUFFER, bounds=True),
           "indices": g.indices(mesh["triangles"])}
    if "normals" in mesh:
        out["NORMAL"] = g.floats(mesh["normals"], "VEC3", ARRAY_BUFFER)
    if "uvs" in mesh:
        out["TEXCOORD_0"] = g.floats(mesh["uvs"], "VEC2", ARRAY_BUFFER)
    if "joints" in mesh:
        out["JOINTS_0"] = g.joints(mesh["joints"])
        out["WEIGHTS_0"] = g.floats(mesh["weights"], "VEC4", ARRAY_BUFFER)
    return out


# ---- shapes ----

def box(lo, hi, tile=None, v_offset=0.0):
    """An axis-aligned box, each face counter-clockwise seen from outside (flat: no normals). With `tile`
    (metres per texture repeat along u and v) the side faces' u runs along the face and v down from the
    top of each repeat (glTF's v = 0 is the image's top row); the top and bottom faces take u = x, v = z
    (plus `v_offset` repeats)."""
    positions, uvs, triangles = [], [], []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            a, b = [k for k in range(3) if k != axis]
            corners = []
            for ca, cb in ((0, 0), (1, 0), (1, 1), (0, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis] = hi[axis] if sign > 0 else lo[axis]
                p[a] = hi[a] if ca else lo[a]
                p[b] = hi[b] if cb else lo[b]
                corners.append(tuple(p))
            e1 = [corners[1][k] - corners[0][k] for k in range(3)]
            e2 = [corners[2][k] - corners[0][k] for k in range(3)]
            normal = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
            if normal[axis] * sign < 0:
                corners.reverse()
            base = len(positions)
            positions += corners
            triangles += [(base, base + 1, base + 2), (base, base + 2, base + 3)]
            if tile:
                for p in corners:
                    if axis == 1:
                        uvs.append((p[0] / tile[0], p[2] / tile[1] + v_offset))
                    else:
                        uvs.append(((p[2] if axis == 0 else p[0]) / tile[0], -p[1] / tile[1]))
    mesh = {"positions": positions, "triangles": triangles}
    if tile:
        mesh["uvs"] = uvs
    return mesh


def wheel_mesh(radius, width, segments):
    """A cylinder along z (the axle), centred on the origin: the tread smooth (radial normals), the two caps
    flat with the disc of wheel.png on them."""
    positions, normals, uvs, triangles = [], [], [], []
    for i in range(segments + 1):
        a = 2 * math.pi * i / segments
        c, s = math.cos(a), math.sin(a)
        for z in (-width / 2, width / 2):
            positions.append((radius * c, radius * s, z))
            normals.append((c, s, 0.0))
            uvs.append((0.02, 0.02))  # the tyre-black corner of the texture
    for i in range(segments):
        k = 2 * i
        triangles += [(k, k + 2, k + 3), (k, k + 3, k + 1)]
    for z, nz in ((width / 2, 1.0), (-width / 2, -1.0)):
        centre = len(positions)
        positions.append((0.0, 0.0, z))
        normals.append((0.0, 0.0, nz))
        uvs.append((0.5, 0.5))
        for i in range(segments):
            a = 2 * math.pi * i / segments
            positions.append((radius * math.cos(a), radius * math.sin(a), z))
            normals.append((0.0, 0.0, nz))
            uvs.append((0.5 + 0.5 * math.cos(a), 0.5 - 0.5 * math.sin(a)))
        for i in range(segments):
            p, q = centre + 1 + i, centre + 1 + (i + 1) % segments
            triangles.append((centre, p, q) if nz > 0 else (centre, q, p))
    return {"positions": positions, "normals": normals, "uvs": uvs, "triangles": triangles}


def car_body():
    """A body and a cabin, 4.2 m long along x, as one mesh (flat)."""
    lower = box((-2.1, 0.3, -0.9), (2.1, 1.0, 0.9))
    cabin = box((-1.2, 1.0, -0.8), (1.0, 1.55, 0.8))
    offset = len(lower["positions"])
    return {"positions": lower["positions"] + cabin["positions"],
            "triangles": lower["triangles"] + [tuple(i + offset for i in t) for t in cabin["triangles"]]}


# ---- the walker: one skinned mesh of hexagonal tubes ----

JOINTS = ["pelvis", "spine", "hip_l", "knee_l", "hip_r", "knee_r", "shoulder_l", "shoulder_r"]
PARENT = {"spine": "pelvis", "hip_l": "pelvis", "hip_r": "pelvis", "knee_l": "hip_l", "knee_r": "hip_r",
          "shoulder_l": "spine", "shoulder_r": "spine"}
BIND = {"pelvis": (0.0, 0.9, 0.0), "spine": (0.0, 1.2, 0.0), "hip_l": (0.0, 0.9, 0.12), "knee_l": (0.0, 0.47, 0.12),
        "hip_r": (0.0, 0.9, -0.12), "knee_r": (0.0, 0.47, -0.12), "shoulder_l": (0.0, 1.45, 0.3),
        "shoulder_r": (0.0, 1.45, -0.3)}


def tube(mesh, centre, radius, rings):
    """A closed-ended hexagonal tube along y with radial (smooth) normals; rings: (y, {joint: weight})."""
    sides = 6
    start = len(mesh["positions"])
    for y, weights in rings:
        for i in range(sides):
            a = 2 * math.pi * i / sides
            c, s = math.cos(a), math.sin(a)
            mesh["positions"].append((centre[0] + radius * c, y, centre[1] + radius * s))
            mesh["normals"].append((c, 0.0, s))
            pairs = sorted(weights.items(), key=lambda kv: JOINTS.index(kv[0])) + [("pelvis", 0.0)] * 4
            mesh["joints"].append(tuple(JOINTS.index(j) for j, _ in pairs[:4]))
            mesh["weights"].append(tuple(w for _, w in pairs[:4]))
    for r in range(len(rings) - 1):
        for i in range(sides):
            a, b = start + r * sides + i, start + r * sides + (i + 1) % sides
            # Counter-clockwise seen from outside: going round +y from +x towards +z is clockwise seen
            # from above, so the upper ring comes first.
            triangles = [(a, a + sides, b), (b, a + sides, b + sides)]
            mesh["triangles"] += triangles
    for r, up in ((0, False), (len(rings) - 1, True)):
        ring = [start + r * sides + i for i in range(sides)]
        for i in range(1, sides - 1):
            mesh["triangles"].append((ring[0], ring[i + 1], ring[i]) if up else (ring[0], ring[i], ring[i + 1]))


def walker_mesh():
    mesh = {"positions": [], "normals": [], "triangles": [], "joints": [], "weights": []}
    for side, z in (("l", 0.12), ("r", -0.12)):
        hip, knee = "hip_" + side, "knee_" + side
        tube(mesh, (0.0, z), 0.08, [(0.02, {knee: 1.0}), (0.47, {hip: 0.5, knee: 0.5}), (0.9, {hip: 1.0})])
    for side, z in (("l", 0.3), ("r", -0.3)):
        tube(mesh, (0.0, z), 0.06, [(0.85, {"shoulder_" + side: 1.0}), (1.45, {"shoulder_" + side: 1.0})])
    tube(mesh, (0.0, 0.0), 0.2, [(0.85, {"pelvis": 1.0}), (1.2, {"pelvis": 0.5, "spine": 0.5}),
                                 (1.52, {"spine": 1.0})])
    tube(mesh, (0.0, 0.0), 0.11, [(1.56, {"spine": 1.0}), (1.8, {"spine": 1.0})])
    return mesh


# ---- animation helpers ----

def quat_axis(axis, degrees):
    h = math.radians(degrees) / 2
    s = math.sin(h)
    return (axis[0] * s, axis[1] * s, axis[2] * s, math.cos(h))


def quat_mul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz)


def camera_turn(yaw):
    """Yaw about world y, then the camera's own 7-degree downward tilt."""
    return quat_mul(quat_axis((0, 1, 0), yaw), quat_axis((1, 0, 0), -7.0))


def key_times(step):
    n = int(round(DURATION / step))
    return [DURATION * k / n for k in range(n + 1)]


def add_camera(g):
    camera = g.add("cameras", {"name": "street_camera", "type": "perspective",
                               "perspective": {"yfov": 0.7, "aspectRatio": 16 / 9, "znear": 0.1, "zfar": 200.0}})
    node = g.add("nodes", {"name": "street_camera", "camera": camera, "translation": [1.0, 2.6, 13.0],
                           "rotation": list(camera_turn(14.0))})
    # The dolly moves in 3 m, slightly left and down; the pan turns 28 degrees to the right in 2 s, keyed every
    # half second (each key a few degrees apart, well inside slerp's shortest arc).
    times = key_times(0.5)
    g.animate(node, "translation", times, [(1.0 - 0.6 * t / DURATION, 2.6 - 0.2 * t / DURATION, 13.0 - 3.0 * t / DURATION)
                                           for t in times])
    g.animate(node, "rotation", times, [camera_turn(14.0 - 28.0 * t / DURATION) for t in times])
    return node


# A car: `speed` in m/s along world x (signed), `heading` in degrees about y (facing its motion).
Car = namedtuple("Car", "name color start_x speed lane_z heading")


def add_car(g, car, mesh, wheel):
    """A car node moving along world x, with four spinning wheel children rolling without slipping
    (radius 0.33 m)."""
    wheels = []
    name, speed = car.name, car.speed
    node = g.add("nodes", {"name": name, "mesh": mesh, "translation": [car.start_x, 0.0, car.lane_z],
                           "rotation": list(quat_axis((0, 1, 0), car.heading)), "children": wheels})
    times = key_times(1.0)
    g.animate(node, "translation", times, [(car.start_x + speed * t, 0.0, car.lane_z) for t in times])
    # In the car's frame the car moves along +x; a wheel rolling that way turns about -z.
    omega = math.degrees(abs(speed) / 0.33)
    spin_times = key_times(1.0 / 24.0)  # at most 9 m/s: 65 degrees between keys
    for wx, wz, tag in ((1.35, 0.9, "fl"), (-1.35, 0.9, "rl"), (1.35, -0.9, "fr"), (-1.35, -0.9, "rr")):
        child = g.add("nodes", {"name": f"{name}_wheel_{tag}", "mesh": wheel, "translation": [wx, 0.33, wz]})
        wheels.append(child)
        g.animate(child, "rotation", spin_times, [quat_axis((0, 0, 1), -omega * t) for t in spin_times])
    return node


def add_walker(g, material):
    mesh = walker_mesh()
    acc = geometry(g, mesh)
    mesh_index = g.mesh("walker", acc, material)
    index = {}
    for j in JOINTS:
        parent = PARENT.get(j)
        local = [BIND[j][k] - (BIND[parent][k] if parent else 0.0) for k in range(3)]
        index[j] = g.add("nodes", {"name": j, "translation": local})
    for j, parent in PARENT.items():
        g.doc["nodes"][index[parent]].setdefault("children", []).append(index[j])
    ibm = [(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -BIND[j][0], -BIND[j][1], -BIND[j][2], 1) for j in JOINTS]
    skin = g.add("skins", {"name": "walker", "joints": [index[j] for j in JOINTS], "skeleton": index["pelvis"],
                           "inverseBindMatrices": g.floats(ibm, "MAT4")})
    body = g.add("nodes", {"name": "walker", "mesh": mesh_index, "skin": skin})
    # A stride of 1.1 m per second along the near sidewalk, legs swinging +-24 degrees, knees bending on
    # the back swing, arms against the legs, the spine leaning in and bobbing twice a stride.
    times = key_times(1.0 / 16.0)
    phase = [2 * math.pi * t for t in times]
    g.animate(index["pelvis"], "translation", times,
              [(-3.0 + 1.1 * t, 0.9 + 0.03 * math.cos(2 * p), 4.6) for t, p in zip(times, phase)])
    for side, sign in (("l", 1.0), ("r", -1.0)):
        g.animate(index["hip_" + side], "rotation", times, [quat_axis((0, 0, 1), 24 * sign * math.sin(p)) for p in phase])
        g.animate(index["knee_" + side], "rotation", times,
                  [quat_axis((0, 0, 1), -30 * max(0.0, -sign * math.sin(p + 0.6))) for p in phase])
        g.animate(index["shoulder_" + side], "rotation", times,
                  [quat_axis((0, 0, 1), -20 * sign * math.sin(p)) for p in phase])
    g.animate(index["spine"], "rotation", times, [quat_axis((0, 0, 1), -6 - 3 * math.sin(2 * p)) for p in phase])
    return [body, index["pelvis"]]


def build():
    g = Gltf()
    g.doc["samplers"].append({"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497})
    textures = {}
    for name in TEXTURES:
        image = g.add("images", {"uri": name})
        textures[name] = g.add("textures", {"sampler": 0, "source": image})

    def material(name, color, texture=None, double_sided=False):
        pbr = {"baseColorFactor": list(color) + [1.0], "metallicFactor": 0.0, "roughnessFactor": 0.9}
        if texture:
            pbr["baseColorTexture"] = {"index": textures[texture]}
        return g.add("materials", {"name": name, "pbrMetallicRoughness": pbr, "doubleSided": double_sided})

    roots = g.doc["scenes"][0]["nodes"]
    # The road's v runs 0 .. 1 across it (z = -3 .. 3), so the dashes sit on the centre line.
    road = g.mesh("road", geometry(g, box((-60.0, -0.05, -3.0), (60.0, 0.0, 3.0), tile=(6.0, 6.0), v_offset=0.5)),
                  material("asphalt", (1.0, 1.0, 1.0), "asphalt.png"))
    roots.append(g.add("nodes", {"name": "road", "mesh": road, "translation": [0.0, 0.0, 0.0]}))
    walk = material("paving", (1.0, 1.0, 1.0), "paving.png")
    for name, z0, z1 in (("sidewalk_near", 3.0, 7.0), ("sidewalk_far", -7.0, -3.0)):
        mesh = g.mesh(name, geometry(g, box((-60.0, -0.05, z0), (60.0, 0.15, z1), tile=(1.5, 1.5))), walk)
        roots.append(g.add("nodes", {"name": name, "mesh": mesh}))
    verge = g.mesh("verge", geometry(g, box((-60.0, -0.1, 7.0), (60.0, 0.0, 30.0))), material("verge", (0.25, 0.35, 0.2)))
    roots.append(g.add("nodes", {"name": "verge", "mesh": verge}))
    tints = [(0.95, 0.75, 0.6), (0.8, 0.85, 0.95), (0.95, 0.9, 0.7), (0.75, 0.6, 0.55), (0.9, 0.9, 0.9),
             (0.7, 0.8, 0.7)]
    for i, x0 in enumerate(range(-30, 30, 10)):
        height = (9.0, 12.0, 15.0, 9.0, 12.0, 9.0)[i]
        mesh = g.mesh(f"building_{i}", geometry(g, box((x0, 0.0, -16.0), (x0 + 10.0, height, -7.0), tile=(2.0, 3.0))),
                      material(f"facade_{i}", tints[i], "facade.png"))
        roots.append(g.add("nodes", {"name": f"building_{i}", "mesh": mesh}))

    body = geometry(g, car_body())
    wheel = g.mesh("wheel", geometry(g, wheel_mesh(0.33, 0.24, 16)), material("wheel", (1.0, 1.0, 1.0), "wheel.png"))
    cars = [Car("car_red", (0.75, 0.08, 0.05), -14.0, 9.0, 1.5, 0.0),
            Car("car_blue", (0.08, 0.2, 0.7), 12.0, -6.0, -1.5, 180.0),
            Car("car_yellow", (0.9, 0.75, 0.1), 2.0, -3.5, -1.5, 180.0)]
    for car in cars:
        roots.append(add_car(g, car, g.mesh(car.name, body, material(car.name, car.color)), wheel))
    roots.extend(add_walker(g, material("walker", (0.2, 0.45, 0.6), double_sided=True)))
    roots.append(add_camera(g))
    return g


def plain(doc):
    """The same street without image textures and vertex normals, over the same street.bin: what the
    plain Embree loop (scripts/bench/peers.py) shades the same way as clipblur, for the equal-error
    comparison. Its unused accessors are only an info in the validator's report."""
    doc = json.loads(json.dumps(doc))
    for key in ("images", "samplers", "textures"):
        del doc[key]
    for material in doc["materials"]:
        material["pbrMetallicRoughness"].pop("baseColorTexture", None)
    for mesh in doc["meshes"]:
        for primitive in mesh["primitives"]:
            primitive["attributes"].pop("NORMAL", None)
            primitive["attributes"].pop("TEXCOORD_0", None)
    doc["asset"]["generator"] += " (plain: no textures, no normals)"
    return doc


def serialise(g):
    g.doc["buffers"] = [{"uri": "street.bin", "byteLength": len(g.blob)}]
    files = {"street.gltf": (json.dumps(g.doc, indent=1) + "\n").encode(), "street.bin": bytes(g.blob),
             "street_plain.gltf": (json.dumps(plain(g.doc), indent=1) + "\n").encode()}
    for name, (w, h, pixel) in TEXTURES.items():
        files[name] = png(w, h, pixel)
    return files


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", type=Path, default=OUT)
    ap.add_argument("--check", action="store_true", help="compare with the files in --out instead of writing")
    args = ap.parse_args()
    files = serialise(build())
    if args.check:
        stale = [n for n, data in files.items() if not (args.out / n).is_file() or (args.out / n).read_bytes() != data]
        for n in stale:
            print(f"{args.out / n}: differs from what {Path(__file__).name} writes now", file=sys.stderr)
        return 1 if stale else 0
    args.out.mkdir(parents=True, exist_ok=True)
    for n, data in files.items():
        (args.out / n).write_bytes(data)
    print(f"wrote {', '.join(sorted(files))} to {args.out} ({sum(map(len, files.values()))} bytes)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
