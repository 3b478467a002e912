#!/usr/bin/env bash
# End-to-end farm test on a throwaway one-node Slurm cluster:
#   1. the cluster starts, runs a job array and an afterok-dependent job (plain shell, no clipblur);
#   2. `clipblur submit` renders a two-frame, four-tile job with one element made to fail, reports the
#      failure, and a second submit renders only that element and merges;
#   3. the merged frames equal a single-machine render bit for bit, with the full data window.
# Usage: slurm_cluster_test.sh CLIPBLUR_BINARY SOURCE_DIR
# Environment: CLIPBLUR_FARM_TEST_JOB (default SOURCE_DIR/configs/default.yaml),
#   CLIPBLUR_FARM_TEST_STAGE=cluster to run stage 1 only, CLIPBLUR_SLURM_PORT (default 6917 here).
set -euo pipefail

[ $# -eq 2 ] || { echo "usage: $0 CLIPBLUR_BINARY SOURCE_DIR" >&2; exit 2; }
bin=$(realpath "$1")
src=$(realpath "$2")
job=${CLIPBLUR_FARM_TEST_JOB:-$src/configs/default.yaml}
export CLIPBLUR_SLURM_PORT=${CLIPBLUR_SLURM_PORT:-6917}

fail() { echo "FAIL: $*" >&2; exit 1; }
for tool in slurmctld slurmd sbatch squeue idiff oiiotool; do
  command -v "$tool" >/dev/null || fail "$tool not installed (CLIPBLUR_SLURM=1 bash scripts/setup.sh)"
done

work=$(mktemp -d /tmp/clipblur-farm-test.XXXXXX)
cluster=$work/cluster
cleanup() {
  bash "$src/scripts/slurm-cluster.sh" stop "$cluster" >/dev/null 2>&1 || true
  rm -rf "$work"
}
trap cleanup EXIT

# Prints the daemon logs itself and exits non-zero when the node never becomes idle.
bash "$src/scripts/slurm-cluster.sh" start "$cluster" || fail "cluster did not start"
export SLURM_CONF=$cluster/slurm.conf

echo "== stage 1: array + afterok"
mkdir -p "$work/smoke"
cat >"$work/smoke/array.sh" <<SCRIPT
#!/bin/bash
#SBATCH --array=0-3
#SBATCH --output=$work/smoke/array-%A_%a.log
echo "\$SLURM_ARRAY_TASK_ID" > "$work/smoke/done-\$SLURM_ARRAY_TASK_ID"
SCRIPT
cat >"$work/smoke/after.sh" <<SCRIPT
#!/bin/bash
#SBATCH --output=$work/smoke/after-%j.log
cat "$work"/smoke/done-* | sort | tr '\n' ' ' > "$work/smoke/after"
SCRIPT
array_id=$(sbatch --parsable "$work/smoke/array.sh")
sbatch --parsable --wait --dependency="afterok:$array_id" "$work/smoke/after.sh" >/dev/null ||
  fail "afterok job failed"
[ "$(cat "$work/smoke/after")" = "0 1 2 3 " ] || fail "dependent job saw: $(cat "$work/smoke/after" 2>/dev/null)"
echo "stage 1 ok (${SECONDS}s)"
[ "${CLIPBLUR_FARM_TEST_STAGE:-all}" = cluster ] && exit 0

echo "== stage 2: submit, fail one element, resubmit"
[ -f "$job" ] || fail "no job file $job"
# Tiny and cheap: the test is about the farm, not the renderer (the shard tests cover clipped too).
sets=(--set film.width=64 --set film.height=48 --set render.method=stochastic --set render.samples=4
      --set output.png_preview=false)
farm_sets=("${sets[@]}" --set "output.path=$work/farm/beauty.####.exr")
ref_sets=("${sets[@]}" --set "output.path=$work/ref/beauty.####.exr")
shard() { printf '%s/farm/beauty.%04d.tile-%d-of-4.exr' "$work" "$1" "$2"; }

# A directory where frame 2, tile 1 must go makes that element's atomic rename fail: a real failure,
# no test hook in clipblur.
mkdir -p "$(shard 2 1)"
set +e
"$bin" submit "$job" "${farm_sets[@]}" --engine slurm --frames 1-2 --tiles 4 --wait >"$work/submit1.txt" 2>&1
status=$?
set -e
cat "$work/submit1.txt"
[ "$status" -eq 6 ] || fail "first submit should report unmerged frames (exit 6), got $status"
grep -q "8 of 8 shards to render (array 0-7)" "$work/submit1.txt" || fail "first submit did not render all 8"
before=""
for f in 1 2; do
  for t in 0 1 2 3; do
    [ "$f$t" = 21 ] && continue
    [ -f "$(shard "$f" "$t")" ] || fail "shard $f/$t missing after first submit"
    before+="$(stat -c '%i %Y' "$(shard "$f" "$t")") "
  done
done
rmdir "$(shard 2 1)"

"$bin" submit "$job" "${farm_sets[@]}" --engine slurm --frames 1-2 --tiles 4 --wait | tee "$work/submit2.txt" ||
  fail "second submit failed; logs in $work/farm/.clipblur-farm"
grep -q "1 of 8 shards to render (array 5)" "$work/submit2.txt" || fail "resubmission did not render only element 5"
after=""
for f in 1 2; do
  for t in 0 1 2 3; do
    [ "$f$t" = 21 ] && continue
    after+="$(stat -c '%i %Y' "$(shard "$f" "$t")") "
  done
done
[ "$before" = "$after" ] || fail "a complete shard was rendered again"
"$bin" submit "$job" "${farm_sets[@]}" --engine slurm --frames 1-2 --tiles 4 --dry-run | grep -q "^0 of 8" ||
  fail "a finished job still has pending shards"

echo "stage 2 ok (${SECONDS}s)"
echo "== stage 3: compare with a single-machine render"
"$bin" render "$job" "${ref_sets[@]}" --frames 1-2
for f in 1 2; do
  merged=$(printf '%s/farm/beauty.%04d.exr' "$work" "$f")
  ref=$(printf '%s/ref/beauty.%04d.exr' "$work" "$f")
  # -fail 0 -warn 0: any difference at all fails (idiff exits 0 only when identical).
  idiff -fail 0 -warn 0 "$ref" "$merged" || fail "frame $f differs from the single-machine render"
  info=$(oiiotool --info -v "$merged")
  grep -q "64 x   48" <<<"$info" || fail "frame $f is not 64x48: $info"
  if grep -q -e "pixel data origin" -e "full/display size" <<<"$info"; then fail "frame $f has a partial data window"; fi
done
echo "PASS (${SECONDS}s)"
