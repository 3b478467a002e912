#!/usr/bin/env python3
"""Writes seeded random scenes for checks that must hold on scenes nobody tuned for (issue 20 asks
`render.error_target` to hold "over the bench scenes and seeded random scenes"). Seed k gives one job:
a checker ground and a striped back wall, 4 to 14 boxes and spheres at random places, sizes and
paints, each translating and spinning by random amounts (some still), and a camera whose move mixes a
pan, a roll, a sideways step and a dolly at random strengths (sometimes still), under one directional
light. The same seed writes the same file, so a run names its seeds and can be repeated.

    scripts/bench/random_scenes.py --seeds 1,2,3 --out build/bench/random    # seed_1.yaml ...

scripts/bench/error_estimate.py --random-seeds 1,2,3 writes and measures them in one command.
"""

import argparse
import math
import random
from pathlib import Path

from make_many_objects import MATERIALS, PAINTS, box, ground, vec

HEADER = """# Random scene (seed {seed}), written by scripts/bench/random_scenes.py; regenerate, do not edit.
version: 1

film: {{width: 320, height: 180, background: 0.05}}
"""

FOOTER = """
render: {{method: clipped, subframes: auto}}

output: {{path: random_{seed}.exr, half: false}}
"""


def sphere(name, material, size, keys):
    """An object line for a sphere, keys as box()'s."""
    lines = box(name, material, [size] * 3, keys).split("\n")
    lines[2] = f"    primitive: {{type: sphere, size: {size:.4g}, segments: 24}}"
    return "\n".join(lines)


def random_axis(rng):
    axis = [rng.gauss(0, 1) for _ in range(3)]
    return axis if math.hypot(*axis) > 1e-3 else [0, 1, 0]


def moving_object(rng, index):
    at = [rng.uniform(-4, 4), rng.uniform(-1.5, 2), rng.uniform(5, 14)]
    moves = rng.random() < 0.8
    shift = [rng.gauss(0, 0.4) for _ in range(3)] if moves else [0, 0, 0]
    axis, spin = random_axis(rng), (rng.uniform(-50, 50) if moves and rng.random() < 0.6 else 0.0)
    end = [a + d for a, d in zip(at, shift)]
    keys = [(0, at, (axis, 0)), (1, end, (axis, spin))]
    paint = rng.choice(PAINTS)
    if rng.random() < 0.3:
        return sphere(f"s{index:02d}", paint, rng.uniform(0.5, 1.8), keys)
    return box(f"b{index:02d}", paint, [rng.uniform(0.3, 2.5) for _ in range(3)], keys)


def camera(rng):
    """Keys at 0 and 1: position and view direction, `up` rolled about the view."""
    def view(yaw, pitch):
        return [math.sin(yaw) * math.cos(pitch), math.sin(pitch), math.cos(yaw) * math.cos(pitch)]

    still = rng.random() < 0.15
    strength = 0.0 if still else 1.0
    pan = strength * math.radians(rng.uniform(-4, 4)) * (rng.random() < 0.7)
    roll = strength * math.radians(rng.uniform(-6, 6)) * (rng.random() < 0.5)
    step = strength * rng.uniform(-0.5, 0.5) * (rng.random() < 0.5)
    dolly = strength * rng.uniform(-1.0, 1.5) * (rng.random() < 0.5)
    pitch = math.radians(rng.uniform(-6, 2))
    keys = []
    for t, sign in ((0, -0.5), (1, 0.5)):
        position = [sign * step, 1.0, sign * dolly]
        up = [math.sin(sign * roll), math.cos(sign * roll), 0]
        keys.append(f"    - {{time: {t}, position: {vec(position)}, view: {vec(view(sign * pan, pitch))}, up: {vec(up)}}}")
    return "\ncamera:\n  vfov: 45\n  keys:\n" + "\n".join(keys) + "\n"


def scene_text(seed):
    rng = random.Random(seed)
    objects = [ground([40, 40], [0, -1.5, 12])]
    objects.append(box("back_wall", "wall", [40, 20, 0.5], [(0, [0, 3, 22], None)]))
    for i in range(rng.randint(4, 14)):
        objects.append(moving_object(rng, i))
    return (HEADER.format(seed=seed) + camera(rng) + MATERIALS + "\nobjects:\n" + "\n".join(objects) + "\n"
            + FOOTER.format(seed=seed))


def write_scenes(seeds, out):
    """Writes seed_<k>.yaml per seed into `out`; returns {name: path}."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    written = {}
    for seed in seeds:
        path = out / f"seed_{seed}.yaml"
        path.write_text(scene_text(seed))
        written[f"random/seed_{seed}"] = path
    return written


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seeds", default="1,2,3,4", help="comma-separated seeds, one scene each")
    ap.add_argument("--out", default="build/bench/random")
    args = ap.parse_args()
    for name, path in write_scenes([int(s) for s in args.seeds.split(",")], args.out).items():
        print(f"{name}: {path}")


if __name__ == "__main__":
    main()
