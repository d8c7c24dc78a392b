#!/usr/bin/env bash
# The solids against POV-Ray 3.7 (issue 13): bench/shapes.pov and scenes/shapes-pov.yaml — a torus,
# a box, a cylinder, a cone and an isosurface under the lecture's camera, light and finish.
# Agreement (RMSE on 0..1 values, linear output, no anti-aliasing) and wall time of the whole
# process at 1920x1080 with 4x4 regular supersampling on THREADS threads (default 2), median of
# RUNS runs (default 3).
#   bench/povray-shapes.sh [build-dir]        (needs: apt-get install povray)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
threads=${THREADS:-2}
runs=${RUNS:-3}
command -v povray >/dev/null || { echo "povray is not installed (apt-get install povray)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$root/bench/shapes.pov" "$work/shapes.pov"
scene=$root/scenes/shapes-pov.yaml
cd "$work"

pov() {  # pov AA OUT
  local aa="-A"
  [ "$1" = 1 ] && aa="+A0.0 +AM1 +R4"
  povray -D -V +W1920 +H1080 +WT$threads +FN16 File_Gamma=1.0 +Ishapes.pov +O"$2" $aa >/dev/null 2>&1
}
median() { sort -n | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'; }
wall() { local s e; s=$(date +%s.%N); "$@"; e=$(date +%s.%N); echo "$e - $s" | bc; }

pov 0 pov.png
"$build/bin/strahl" "$scene" --threads "$threads" -q -o strahl.pfm
echo "== shapes-pov.yaml vs shapes.pov"
echo -n "agreement (no AA, linear): "
"$build/bin/strahl-diff" pov.png strahl.pfm || true
tp=$(for i in $(seq "$runs"); do wall pov 1 pov_aa.png; done | median)
ts=$(for i in $(seq "$runs"); do
  wall "$build/bin/strahl" "$scene" --threads "$threads" --supersample 4 --linear -q -o strahl_aa.png
done | median)
printf "4x4 supersampling, %d threads, median of %d: POV-Ray %.2f s, strahl %.2f s, speed-up %.1fx\n" "$threads" \
  "$runs" "$tp" "$ts" "$(echo "$tp / $ts" | bc -l)"
