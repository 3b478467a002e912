#!/usr/bin/env bash
# Issue 4's still-frame benchmark: a 1280x720 render of a still dense sphere (about 100k and 1M
# triangles) with the clipped method against the stochastic method at 16 and 64 samples per pixel, all
# in this one run so the ratios are fair on a noisy machine. Prints seconds, fragments per pixel and
# peak memory from each render's stats JSON.
# Usage: scripts/bench/still_frame.sh [build/clipblur] [width] [height]
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=${1:-build/clipblur}
width=${2:-1280}
height=${3:-720}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
printf '%-9s %-22s %9s %9s %12s %10s\n' triangles method seconds ratio frags/pixel peak_MB
for segments in 316 1024; do
  base=""
  for method in stochastic:16 stochastic:64 clipped:2 clipped:4; do
    name=${method%%:*}
    value=${method##*:}
    if [ "$name" = stochastic ]; then extra=(--set render.samples="$value"); label="stochastic ${value} spp"
    else extra=(--set render.visibility_rays="$value"); label="clipped rays ${value}x${value}"; fi
    "$bin" render configs/bench/dense_mesh.yaml --progress none --set "objects.0.transform=[]" \
      --set "objects.0.primitive.segments=$segments" --set film.width="$width" --set film.height="$height" \
      --set render.method="$name" "${extra[@]}" --out "$out/r.exr" --stats "$out/r.json" >/dev/null
    python3 - "$out/r.json" "$segments" "$label" "$width" "$height" "$base" <<'PY' > "$out/line"
import json, sys
s = json.load(open(sys.argv[1]))
seg, label, w, h, base = int(sys.argv[2]), sys.argv[3], int(sys.argv[4]), int(sys.argv[5]), sys.argv[6]
c = s["counts"]
t = s["seconds"]["total"]
frags = c.get("open_fragments", 0) / (w * h)
ratio = t / float(base) if base else 1.0
print(f'{c.get("triangles", 0):<9} {label:<22} {t:9.2f} {ratio:9.2f} {frags:12.2f} {s["peak_memory_bytes"] / 2**20:10.0f}|{t}')
PY
    line=$(cat "$out/line")
    echo "${line%%|*}"
    [ -n "$base" ] || base=${line##*|}
  done
done
echo "ratio: seconds / seconds of stochastic 16 spp on the same mesh"
