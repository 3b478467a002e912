#!/usr/bin/env python3
"""Writes issue 20's many-object bench scenes into configs/bench/many/ (seeded, so the files are
reproducible; they are checked in and this script is how they were made):

  street.yaml          a street under a camera panning 4.6 degrees: 24 cars and 8 pedestrians moving at their own
                       speeds in both directions between still facades (38 objects);
  particles.yaml       500 small boxes, each with its own translation and spin, before a still wall;
  building_dolly.yaml  a facade cut into 92 still objects (panels, ledges, roof), camera dollying 1 unit in;
  deforming.yaml       a character-like figure: a body walking sideways and a bending arm and leg
                       (deformation keys, OBJ files written beside the job) before a still wall.

    scripts/bench/make_many_objects.py [--out configs/bench/many] [--seed 20]
"""

import argparse
import math
import random
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]

HEADER = """# Bench (issue 20, many objects): {what}
# Written by scripts/bench/make_many_objects.py --seed {seed}; edit the script, not this file.
version: 1

film: {{width: 320, height: 180, background: 0.05}}
"""

MATERIALS = """
materials:
  - {name: ground, color: 0.5, texture: {type: checker, color2: 0.25, scale: 2}}
  - {name: wall, color: 0.7, texture: {type: stripe, color2: 0.35, scale: 1.5}}
  - {name: red, color: [0.8, 0.15, 0.1]}
  - {name: blue, color: [0.1, 0.25, 0.8]}
  - {name: yellow, color: [0.9, 0.8, 0.2]}
  - {name: white, color: 0.9}
  - {name: dark, color: 0.12}

lights:
  - {type: directional, direction: [-0.4, -1, 0.6], intensity: 0.8}
ambient: 0.35
"""

FOOTER = """
render: {{method: clipped, subframes: auto}}

output: {{path: bench_many_{name}.exr, half: false}}
"""

PAINTS = ("red", "blue", "yellow", "white", "dark")


def vec(v):
    return "[" + ", ".join(f"{x:.4g}" for x in v) + "]"


def box(name, material, size, keys):
    """An object line for a box with transform keys [(time, translate, (axis, angle) or None)]."""
    lines = [f"  - name: {name}", f"    material: {material}", f"    primitive: {{type: box, size: {vec(size)}}}",
             "    transform:"]
    for t, translate, rotate in keys:
        rot = "" if rotate is None else f", rotate: {{axis: {vec(rotate[0])}, angle_deg: {rotate[1]:.4g}}}"
        lines.append(f"      - {{time: {t:g}, translate: {vec(translate)}{rot}}}")
    return "\n".join(lines)


def still_box(name, material, size, at):
    return box(name, material, size, [(0, at, None)])


def ground(size, at):
    return ("  - name: ground\n    material: ground\n"
            f"    primitive: {{type: grid, size: {vec(size)}, divisions: [16, 16]}}\n"
            f"    transform:\n      - {{time: 0, translate: {vec(at)}}}")


def street(rng):
    objects = [ground([40, 60], [0, 0, 25])]
    for side in (-1, 1):  # facades, still
        for k in range(3):
            objects.append(still_box(f"facade_{'lr'[side > 0]}{k}", "wall", [1, 6 + 2 * k, 14],
                                     [side * 9, 3 + k, 8 + 15 * k]))
    for c in range(24):  # cars in four lanes, both directions
        lane = c % 4
        direction = 1 if lane < 2 else -1
        x0 = rng.uniform(-10, 10)
        speed = direction * rng.uniform(0.6, 2.0)  # units per frame
        z = 9 + 3 * lane + rng.uniform(-0.3, 0.3) + 1.5 * (c // 4)
        objects.append(box(f"car{c:02d}", rng.choice(PAINTS), [1.8, 0.9, 0.9],
                           [(0, [x0, 0.45, z], None), (1, [x0 + speed, 0.45, z], None)]))
    for p in range(8):  # pedestrians on the pavements, slow
        x0, z = rng.choice((-7, 7)) + rng.uniform(-0.5, 0.5), rng.uniform(6, 30)
        dz = rng.uniform(-0.15, 0.15)
        objects.append(box(f"walker{p}", rng.choice(PAINTS), [0.4, 1.7, 0.3],
                           [(0, [x0, 0.85, z], None), (1, [x0, 0.85, z + dz], None)]))
    camera = """
camera:
  vfov: 45
  keys:
    - {time: 0, position: [0, 1.6, 0], view: [-0.04, -0.05, 1]}
    - {time: 1, position: [0, 1.6, 0], view: [0.04, -0.05, 1]}
"""
    return "a street, 24 cars and 8 walkers moving differently, the camera panning 4.6 degrees", camera, objects


def particles(rng):
    objects = [still_box("wall", "wall", [30, 20, 0.5], [0, 0, 16])]
    for i in range(500):
        at = [rng.uniform(-5, 5), rng.uniform(-3, 3), rng.uniform(5, 14)]
        d = [rng.gauss(0, 0.25) for _ in range(3)]
        axis = [rng.gauss(0, 1) for _ in range(3)]
        if math.hypot(*axis) < 1e-3:
            axis = [0, 0, 1]
        spin = rng.uniform(-60, 60)
        end = [a + b for a, b in zip(at, d)]
        objects.append(box(f"p{i:03d}", rng.choice(PAINTS), [0.15] * 3,
                           [(0, at, (axis, 0)), (1, end, (axis, spin))]))
    camera = """
camera:
  vfov: 45
  keys:
    - {time: 0, position: [0, 0, 0]}
"""
    return "500 small boxes, each with its own translation and spin, still camera", camera, objects


def building(rng):
    objects = [ground([60, 60], [0, -6, 20])]
    for floor in range(10):
        y = -5 + floor * 1.2
        objects.append(still_box(f"ledge{floor}", "dark", [12.4, 0.15, 0.5], [0, y, 11.8]))
        for bay in range(8):
            x = -5.25 + bay * 1.5
            objects.append(still_box(f"panel{floor}_{bay}", rng.choice(("white", "wall")), [1.45, 1.05, 0.3],
                                     [x, y + 0.6, 12]))
    objects.append(still_box("roof", "dark", [13, 0.4, 2], [0, 7.2, 12.5]))
    camera = """
camera:
  vfov: 50
  keys:
    - {time: 0, position: [1.5, -2, -2], view: [-0.1, 0.25, 1]}
    - {time: 1, position: [1.4, -1.95, -1], view: [-0.1, 0.25, 1]}
"""
    return "a facade cut into 92 still objects, the camera dollying 1 unit in (of 14)", camera, objects


def tube_obj(length, radius, bend_deg, rings=24, sides=12):
    """A capped tube along +y of `length`, bent by `bend_deg` in the xy-plane (uniform curvature), as OBJ
    text. Every bend has the same vertices and faces, so the files are deformation keys of one another."""
    lines = []
    bend = math.radians(bend_deg)
    for r in range(rings + 1):
        s = length * r / rings
        if abs(bend) < 1e-9:
            cx, cy, tx, ty = 0.0, s, 0.0, 1.0
        else:
            rc = length / bend
            a = bend * r / rings
            cx, cy, tx, ty = rc * (1 - math.cos(a)), rc * math.sin(a), math.sin(a), math.cos(a)
        nx, ny = ty, -tx  # in-plane normal of the centre line
        for k in range(sides):
            phi = 2 * math.pi * k / sides
            u, w = math.cos(phi) * radius, math.sin(phi) * radius
            lines.append(f"v {cx + nx * u:.6f} {cy + ny * u:.6f} {w:.6f}")
    lines.append(f"v 0 0 0\nv {cx:.6f} {cy:.6f} 0")
    base, tip = (rings + 1) * sides + 1, (rings + 1) * sides + 2
    for r in range(rings):
        for k in range(sides):
            a = r * sides + k + 1
            b = r * sides + (k + 1) % sides + 1
            lines.append(f"f {a} {b} {b + sides} {a + sides}")
    for k in range(sides):
        lines.append(f"f {base} {(k + 1) % sides + 1} {k + 1}")
        lines.append(f"f {tip} {rings * sides + k + 1} {rings * sides + (k + 1) % sides + 1}")
    return "\n".join(lines) + "\n"


def deforming(rng, out):
    limbs = {"arm": (2.0, 0.18, (-20, 70, 120)), "leg": (2.4, 0.22, (10, -35, -60))}
    objects = [still_box("wall", "wall", [30, 20, 0.5], [0, 0, 12])]
    for name, (length, radius, bends) in limbs.items():
        for i, b in enumerate(bends):
            (out / f"{name}_{i}.obj").write_text(tube_obj(length, radius, b))
    walk = [(0, -0.3), (0.5, 0.0), (1, 0.3)]
    objects.append(box("body", "blue", [1.0, 1.6, 0.6], [(t, [x, 0.6, 7], None) for t, x in walk]))
    objects.append(box("head", "yellow", [0.5, 0.5, 0.5], [(t, [x, 1.75, 7], None) for t, x in walk]))
    placement = {"arm": (0.6, 1.2, 6.9, 180), "leg": (0.25, -0.2, 7.0, 180)}
    for name in limbs:
        dx, y, z, flip = placement[name]
        lines = [f"  - name: {name}", "    material: red", f"    obj: {name}_0.obj", "    deformation:"]
        lines += [f"      - {{time: {t:g}, obj: {name}_{i}.obj}}" for i, (t, _) in enumerate(walk)]
        lines.append("    transform:")
        lines += [f"      - {{time: {t:g}, translate: {vec([x + dx, y, z])}, rotate: {{axis: [0, 0, 1], "
                  f"angle_deg: {flip}}}}}" for t, x in walk]
        objects.append("\n".join(lines))
    camera = """
camera:
  vfov: 40
  keys:
    - {time: 0, position: [0, 0.5, -1], view: [0, 0, 1]}
"""
    return "a figure walking, its arm and leg bending (deformation keys), still camera", camera, objects


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=str(REPO / "configs" / "bench" / "many"))
    ap.add_argument("--seed", type=int, default=20)
    args = ap.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    scenes = {"street": street, "particles": particles, "building_dolly": building,
              "deforming": lambda rng: deforming(rng, out)}
    for name, make in scenes.items():
        what, camera, objects = make(random.Random(f"{args.seed}-{name}"))
        text = (HEADER.format(what=what, seed=args.seed) + camera + MATERIALS + "\nobjects:\n" + "\n".join(objects)
                + "\n" + FOOTER.format(name=name))
        (out / f"{name}.yaml").write_text(text)
        print(f"{out / name}.yaml: {len(objects)} objects")


if __name__ == "__main__":
    main()
