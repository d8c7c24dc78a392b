#!/usr/bin/env bash
# Renders the lecture scene and its Whitted variant with POV-Ray 3.7 and with strahl, side by side
# in one run: agreement (RMSE on 0..1 values, linear output, no anti-aliasing) and wall time of
# the whole process at 1920x1080 with 4x4 regular supersampling on all cores (median of 3).
#   bench/povray-compare.sh [build-dir]        (needs: apt-get install povray)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
pov_scene=$root/../shared/bench/lecture.pov
[ -f "$pov_scene" ] || { echo "missing $pov_scene" >&2; exit 2; }
command -v povray >/dev/null || { echo "povray is not installed (apt-get install povray)" >&2; exit 2; }
threads=$(nproc)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$pov_scene" "$work/lecture.pov"
cd "$work"

pov() {  # pov WHITTED AA OUT
  local aa="-A"
  [ "$2" = 1 ] && aa="+A0.0 +AM1 +R4"
  povray -D -V +W1920 +H1080 +WT$threads +FN16 File_Gamma=1.0 +Ilecture.pov +O"$3" Declare=WHITTED="$1" $aa >/dev/null 2>&1
}
median3() { sort -n | sed -n 2p; }
wall() { local s e; s=$(date +%s.%N); "$@"; e=$(date +%s.%N); echo "$e - $s" | bc; }

for variant in 0 1; do
  scene=$root/scenes/lecture.yaml
  [ $variant = 1 ] && scene=$root/scenes/lecture-whitted.yaml
  pov $variant 0 pov.png
  "$build/bin/strahl" "$scene" -q -o strahl.pfm
  echo "== $(basename "$scene") vs lecture.pov WHITTED=$variant"
  echo -n "agreement (no AA, linear): "
  "$build/bin/strahl-diff" pov.png strahl.pfm
  tp=$(for i in 1 2 3; do wall pov $variant 1 pov_aa.png; done | median3)
  ts=$(for i in 1 2 3; do wall "$build/bin/strahl" "$scene" --supersample 4 --linear -q -o strahl_aa.png; done | median3)
  printf "4x4 supersampling, %d threads: POV-Ray %.2f s, strahl %.2f s, speed-up %.1fx\n" "$threads" "$tp" "$ts" \
    "$(echo "$tp / $ts" | bc -l)"
done
