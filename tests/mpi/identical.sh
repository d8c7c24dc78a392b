#!/usr/bin/env bash
# Cluster images are the same bytes as strahl's: for K = 1..4 ranks with 1 and 2 threads each,
# every sampler, a wide filter, adaptive sampling, AOVs and motion blur.
. "$(dirname "$0")/common.sh"

# check NAME NP THREADS TILE SCENE ARGS...: strahl-mpi's PFM (and AOVs) = strahl's.
check() {
  local name=$1 np=$2 threads=$3 tile=$4 scene=$5 before=$failures
  shift 5
  local args=("$SRC/scenes/$scene" --width 48 --height 27 -q "$@")
  "$CLI" "${args[@]}" --threads 1 -o "$WORK/$name.ref.pfm" || { fail "$name: strahl failed"; return; }
  if ! mpirun_strahl "$np" "${args[@]}" --threads "$threads" --tile-size "$tile" -o "$WORK/$name.mpi.pfm"; then
    fail "$name: strahl-mpi -np $np failed"
    return
  fi
  cmp -s "$WORK/$name.ref.pfm" "$WORK/$name.mpi.pfm" || fail "$name: -np $np --threads $threads: the images differ"
  for aov in "$WORK/$name".ref.*.exr; do
    [ -e "$aov" ] || continue
    local other=${aov/.ref./.mpi.}
    cmp -s "$aov" "$other" || fail "$name: AOV $(basename "$other") differs"
  done
  [ -e "$WORK/$name.mpi.pfm.journal" ] && fail "$name: the journal of a finished render was left behind"
  [ "$failures" = "$before" ] && echo "ok: $name (-np $np, $threads threads, tile $tile)"
}

check grid-1       1 2 16 lecture-whitted.yaml --supersample 2
check grid-2       2 1 8  lecture-whitted.yaml --supersample 2
check stratified-3 3 2 5  lecture-whitted.yaml --sampler stratified --spp 4
check sobol-4      4 1 7  lecture-distributed.yaml --sampler sobol --spp 4
check random-2     2 2 9  soft-shadows.yaml --sampler random --spp 3
check adaptive-2   2 2 8  lecture-whitted.yaml --sampler adaptive --spp 16 --adaptive-min 2
check adaptive-4   4 1 6  lecture-whitted.yaml --sampler adaptive --spp 16 --adaptive-min 2
check mitchell-3   3 1 8  lecture-whitted.yaml --sampler stratified --spp 4 --filter mitchell --filter-radius 2
check aov-2        2 2 16 lecture-whitted.yaml --aov depth,normal,albedo,id
check motion-4     4 2 8  motion-blur.yaml --sampler sobol --spp 4
check dof-3        3 1 8  depth-of-field.yaml --sampler sobol --spp 4
check path-3       3 2 8  cornell-box-path.yaml --spp 4

# A worker with T render threads gets prefetch × T tiles in flight (3 × T by default), not 3: with
# 3 its other threads would idle. The summary says how many it held at once.
if mpirun_strahl 2 "$SRC/scenes/lecture.yaml" --width 160 --height 90 --tile-size 8 --threads 3 \
  -o "$WORK/inflight.png" > "$WORK/inflight.txt" 2>&1; then
  grep -q "^  rank 1 .* up to 9 tiles in flight" "$WORK/inflight.txt" ||
    fail "a 3-thread worker did not get 9 tiles in flight: $(grep '^  rank 1' "$WORK/inflight.txt")"
  mpirun_strahl 2 "$SRC/scenes/lecture.yaml" --width 160 --height 90 --tile-size 8 --threads 3 --prefetch 2 \
    -o "$WORK/inflight2.png" > "$WORK/inflight.txt" 2>&1
  grep -q "^  rank 1 .* up to 6 tiles in flight" "$WORK/inflight.txt" ||
    fail "--prefetch 2 with 3 threads: not 6 tiles in flight: $(grep '^  rank 1' "$WORK/inflight.txt")"
  echo "ok: tiles in flight follow the worker's threads"
else
  fail "in-flight run failed: $(tail -3 "$WORK/inflight.txt")"
fi
finish
