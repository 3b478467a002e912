#!/usr/bin/env bash
# Configures and builds one flavour: release (default) into build/, or sanitize (ASan+UBSan) into build-asan/.
set -euo pipefail
cd "$(dirname "$0")/.."
flavour=${1:-release}
jobs=${CLIPBLUR_JOBS:-$(nproc)}
case "$flavour" in
  release)  dir=build;      flags=(-DCMAKE_BUILD_TYPE=Release) ;;
  # -O1 -g1: line tables for sanitizer reports at a fraction of full debug info's compile time (CI budget).
  sanitize) dir=build-asan; flags=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1"
                                   -DCLIPBLUR_SANITIZE=ON -DCLIPBLUR_BENCH=OFF) ;;
  *) echo "usage: $0 [release|sanitize]" >&2; exit 2 ;;
esac
cmake -S . -B "$dir" -G Ninja "${flags[@]}" >/dev/null
cmake --build "$dir" -j "$jobs"
