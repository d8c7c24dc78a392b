#!/usr/bin/env bash
# The solids against POV-Ray 3.7 (issue 13): bench/shapes.pov and scenes/shapes-pov.yaml — a torus,
# a box, a cylinder, a cone and an isosurface under the lecture's camera, light and finish; with
# NAME csg, bench/csg.pov and scenes/csg-pov.yaml — CSG (difference, intersection, merge, union,
# inverse) of those solids and spheres under the same camera, light and finish; with NAME plate,
# bench/plate.pov and scenes/plate-pov.yaml — a plate minus a grid of 54 cylinders (CSG of many
# small operands).
# Agreement (RMSE on 0..1 values, linear output, no anti-aliasing) and wall time of the whole
# process at 1920x1080 with 4x4 regular supersampling on THREADS threads (default 2), median of
# RUNS runs (default 3).
#   bench/povray-shapes.sh [build-dir] [NAME]        NAME: shapes (default), csg or plate  (needs: apt-get install povray)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
name=${2:-shapes}
if [ ! -f "$root/bench/$name.pov" ] || [ ! -f "$root/scenes/$name-pov.yaml" ]; then
  echo "no bench/$name.pov and scenes/$name-pov.yaml (NAME: shapes, csg or plate)" >&2
  exit 1
fi
threads=${THREADS:-2}
runs=${RUNS:-3}
command -v povray >/dev/null || { echo "povray is not installed (apt-get install povray)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$root/bench/$name.pov" "$work/$name.pov"
scene=$root/scenes/$name-pov.yaml
cd "$work"

pov() {  # pov AA OUT
  local aa="-A"
  [ "$1" = 1 ] && aa="+A0.0 +AM1 +R4"
  # shellcheck disable=SC2086  # $aa is one or three options
  povray -D -V +W1920 +H1080 +WT"$threads" +FN16 File_Gamma=1.0 +I"$name.pov" +O"$2" $aa >/dev/null 2>&1
}
median() { sort -n | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'; }
wall() { local s e; s=$(date +%s.%N); "$@"; e=$(date +%s.%N); echo "$e - $s" | bc; }

pov 0 pov.png
"$build/bin/strahl" "$scene" --threads "$threads" -q -o strahl.pfm
echo "== $name-pov.yaml vs $name.pov"
echo -n "agreement (no AA, linear): "
"$build/bin/strahl-diff" pov.png strahl.pfm || true
tp=$(for _ in $(seq "$runs"); do wall pov 1 pov_aa.png; done | median)
ts=$(for _ in $(seq "$runs"); do
  wall "$build/bin/strahl" "$scene" --threads "$threads" --supersample 4 --linear -q -o strahl_aa.png
done | median)
printf "4x4 supersampling, %d threads, median of %d: POV-Ray %.2f s, strahl %.2f s, speed-up %.1fx\n" "$threads" \
  "$runs" "$tp" "$ts" "$(echo "$tp / $ts" | bc -l)"
