#!/usr/bin/env python3
"""Issue 24's many-sided polygon: one OBJ face of n vertices on a circle, moving sideways during the
shutter, rendered at 32x18 by the clipped method. Prints, per n, the CPU seconds (user + system; on a
shared machine far steadier than wall time) of `validate` (loading) and of `render` (loading and
rendering, one thread), each the least of --repeats runs.

    scripts/bench/ngon.py --clipblur build/clipblur --n 5000,10000,20000
"""

import argparse
import math
import resource
import subprocess
import tempfile
from pathlib import Path

JOB = """version: 1
film: {width: 32, height: 18}
camera: {keys: [{position: [0, 0, -3]}]}
objects:
  - obj: ngon.obj
    transform:
      - {time: 0, translate: [-0.2, 0, 0]}
      - {time: 1, translate: [0.2, 0, 0]}
"""


def write_ngon(folder, n):
    lines = [f"v {math.cos(2 * math.pi * i / n):.17g} {math.sin(2 * math.pi * i / n):.17g} 0" for i in range(n)]
    lines.append("f " + " ".join(str(i + 1) for i in range(n)))
    (folder / "ngon.obj").write_text("\n".join(lines) + "\n")
    (folder / "job.yaml").write_text(JOB)


def cpu_seconds():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def least_seconds(cmd, repeats):
    best = math.inf
    for _ in range(repeats):
        start = cpu_seconds()
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        best = min(best, cpu_seconds() - start)
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--clipblur", default="build/clipblur")
    ap.add_argument("--n", default="5000,10000,20000")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--threads", type=int, default=1)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory(prefix="clipblur_ngon_") as tmp:
        folder = Path(tmp)
        print("n,validate_cpu_s,render_cpu_s")
        for n in (int(x) for x in args.n.split(",")):
            write_ngon(folder, n)
            job = str(folder / "job.yaml")
            load = least_seconds([args.clipblur, "validate", job], args.repeats)
            render = least_seconds([args.clipblur, "render", job, "--out", str(folder / "ngon.exr"), "--progress",
                                    "none", "--threads", str(args.threads)], args.repeats)
            print(f"{n},{load:.3f},{render:.3f}", flush=True)


if __name__ == "__main__":
    main()
