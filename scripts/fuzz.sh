#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan+UBSan) in build-fuzz and runs each for a bounded time,
# the total split between them: the job loader seeded with the shipped configs, the OBJ loader with the
# repo's .obj files, the glTF loader with the assets the glTF tests write (build/tests/gltf_assets, when
# present) and tests/fuzz/seeds. Usage: scripts/fuzz.sh [total seconds, default 60] [fuzzer name: only it]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
only=${2:-}
CLIPBLUR_FUZZ=1 bash scripts/setup.sh
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" \
  -DCLIPBLUR_FUZZ=ON -DCLIPBLUR_SANITIZE=ON -DCLIPBLUR_BENCH=OFF >/dev/null
cmake --build build-fuzz --target ${only:-job_loader_fuzz obj_loader_fuzz gltf_loader_fuzz} -j "${CLIPBLUR_JOBS:-$(nproc)}"

corpus=build-fuzz/corpus/job_loader
mkdir -p "$corpus"
# Not the dense-mesh benchmark: its million-triangle sphere loads at a few inputs a second under ASan, and
# its size mutations (4M triangles: 40 s) time out on geometry cost, not parsing (see docs/config.md limits).
find configs \( -name '*.yaml' -o -name '*.json' \) ! -path '*/schema/*' ! -name dense_mesh.yaml |
  while read -r f; do cp "$f" "$corpus/"; done
# A JSON rendering of the demo job seeds the JSON side too.
cp tests/fuzz/seeds/*.json "$corpus/" 2>/dev/null || true

obj_corpus=build-fuzz/corpus/obj_loader
mkdir -p "$obj_corpus"
find configs tests -name '*.obj' | while read -r f; do cp "$f" "$obj_corpus/"; done

gltf_corpus=build-fuzz/corpus/gltf_loader
mkdir -p "$gltf_corpus"
find build/tests/gltf_assets tests/fuzz/seeds \( -name '*.gltf' -o -name '*.glb' \) 2>/dev/null |
  while read -r f; do cp "$f" "$gltf_corpus/"; done

mkdir -p build-fuzz/artifacts
run() {  # fuzzer, corpus, seconds
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    "build-fuzz/tests/$1" "$2" -max_total_time="$3" -max_len=65536 -rss_limit_mb=2048 \
    -timeout=10 -artifact_prefix="build-fuzz/artifacts/$1-" -print_final_stats=1
}
case "$only" in
  job_loader_fuzz) run job_loader_fuzz "$corpus" "$seconds" ;;
  obj_loader_fuzz) run obj_loader_fuzz "$obj_corpus" "$seconds" ;;
  gltf_loader_fuzz) run gltf_loader_fuzz "$gltf_corpus" "$seconds" ;;
  *)
    run job_loader_fuzz "$corpus" $(( (seconds + 2) / 3 ))
    run obj_loader_fuzz "$obj_corpus" $(( (seconds + 1) / 3 ))
    run gltf_loader_fuzz "$gltf_corpus" $(( seconds / 3 )) ;;
esac
