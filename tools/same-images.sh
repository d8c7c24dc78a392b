#!/usr/bin/env bash
# tools/same-images.sh OLD_BIN NEW_BIN — did a change move any pixel? (docs/testing.md)
# Renders every scene in scenes/ with two builds' `strahl` (OLD_BIN/strahl, NEW_BIN/strahl: keep a
# copy of build/bin from before the change) at 320x180 and compares the .pfm files byte for byte:
# each scene with 2x2 grid supersampling, the distributed scenes with the stratified, random, sobol
# and adaptive samplers too, and two scenes with each wide filter. A render that differs is named
# with strahl-diff's figures (RMSE, PSNR, how many pixels).
# Exit codes: 0 every image the same bytes, 1 some differ (or a render failed), 2 usage.
set -u
if [ $# -ne 2 ] || [ ! -x "$1/strahl" ] || [ ! -x "$2/strahl" ]; then
  echo "usage: tools/same-images.sh OLD_BIN NEW_BIN   (directories holding a strahl program each)" >&2
  exit 2
fi
old=$(cd "$1" && pwd)
new=$(cd "$2" && pwd)
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
renders=0
differ=0

compare() {  # compare NAME strahl-arguments…
  local name=$1
  shift
  renders=$((renders + 1))
  if ! "$old/strahl" "$@" --width 320 --height 180 -q -o "$work/old.pfm" 2> "$work/old.err"; then
    differ=$((differ + 1))
    echo "FAILED (old): $name: $(head -1 "$work/old.err")"
    return
  fi
  if ! "$new/strahl" "$@" --width 320 --height 180 -q -o "$work/new.pfm" 2> "$work/new.err"; then
    differ=$((differ + 1))
    echo "FAILED (new): $name: $(head -1 "$work/new.err")"
    return
  fi
  if ! cmp -s "$work/old.pfm" "$work/new.pfm"; then
    differ=$((differ + 1))
    echo "DIFFERS: $name: $("$new/strahl-diff" "$work/old.pfm" "$work/new.pfm" 2>&1 | head -1)"
  fi
}

for scene in "$root"/scenes/*.yaml; do
  compare "$(basename "$scene" .yaml)" "$scene" --supersample 2
done
for scene in depth-of-field glossy lecture-distributed motion-blur soft-shadows; do
  for sampler in stratified random sobol adaptive; do
    compare "$scene --sampler $sampler" "$root/scenes/$scene.yaml" --sampler "$sampler"
  done
done
for filter in tent gaussian mitchell; do
  compare "lecture --filter $filter" "$root/scenes/lecture.yaml" --supersample 2 --filter "$filter" --filter-radius 2
  compare "csg --filter $filter" "$root/scenes/csg.yaml" --supersample 2 --filter "$filter" --filter-radius 1.5
done
echo "same-images: $renders renders, $differ differ"
[ "$differ" -eq 0 ]
