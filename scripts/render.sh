#!/usr/bin/env bash
# Installs what is missing, builds the release binary and renders the default job (or the job given).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh release
job=${1:-configs/default.yaml}
./build/clipblur render "$job" "${@:2}"
