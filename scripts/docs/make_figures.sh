#!/usr/bin/env bash
# Regenerates every figure of docs/design.md (docs/img/design_*.png) with gnuplot (Debian gnuplot-nox).
# Each figure's script states its data; none needs a build.
# Usage: bash scripts/docs/make_figures.sh
set -euo pipefail
cd "$(dirname "$0")"
for figure in pixel_fragments swept_footprint tiles_spills shutter_segments; do
  bash "$figure.sh"
done
ls -l ../../docs/img/design_*.png
