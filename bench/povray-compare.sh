#!/usr/bin/env bash
# Renders the lecture scene, its Whitted variant and the Stanford bunny on a plane
# (../shared/bench/bunny.pov, the mesh made by meshprep.py as bunny.pov says) with POV-Ray 3.7 and
# with strahl, side by side in one run: agreement (RMSE on 0..1 values, linear output, no
# anti-aliasing) and wall time of the whole process at 1920x1080 with 4x4 regular supersampling
# on all cores (median of 3).
#   bench/povray-compare.sh [build-dir] [scenes…]   scenes: lecture whitted bunny (default: all)
# (needs: apt-get install povray)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
shift || true
cases=${*:-lecture whitted bunny}
bench=$root/../shared/bench
for f in "$bench/lecture.pov" "$bench/bunny.pov" "$bench/meshprep.py" "$root/../shared/data/stanford-bunny.obj"; do
  [ -f "$f" ] || { echo "missing $f" >&2; exit 2; }
done
command -v povray >/dev/null || { echo "povray is not installed (apt-get install povray)" >&2; exit 2; }
threads=$(nproc)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$bench/lecture.pov" "$bench/bunny.pov" "$work/"
cd "$work"
python3 "$bench/meshprep.py" "$root/../shared/data/stanford-bunny.obj" --obj bunny.obj --pov bunny.inc --name BUNNY >/dev/null
# bunny.pov for strahl: its camera (horizontal angle 45, right-handed), light and finish.
cat > bunny.yaml << SCENE
camera: {position: [0, 0.9, 2.5], look_at: [0, 0.4, 0], up: [0, 1, 0], fov: 45, fov_axis: horizontal}
render: {width: 1920, height: 1080, max_depth: 8}
materials:
  floor: {color: 0.3, ambient: 0.1, diffuse: 0.7, specular: 0.6, shininess: 100}
  bunny: {color: [0.8, 0.75, 0.7], ambient: 0.1, diffuse: 0.7, specular: 0.6, shininess: 100}
lights: [{type: point, position: [2, 3, 2], color: [1, 1, 1]}]
objects:
  - {type: plane, normal: [0, 1, 0], distance: 0, material: floor}
  - {type: mesh, file: $work/bunny.obj, material: bunny}
SCENE

pov() {  # pov SCENE.pov WHITTED AA OUT
  local aa="-A"
  [ "$3" = 1 ] && aa="+A0.0 +AM1 +R4"
  povray -D -V +W1920 +H1080 +WT$threads +FN16 File_Gamma=1.0 +I"$1" +O"$4" Declare=WHITTED="$2" $aa >/dev/null 2>&1
}
median3() { sort -n | sed -n 2p; }
wall() { local s e; s=$(date +%s.%N); "$@"; e=$(date +%s.%N); echo "$e - $s" | bc; }

for case in $cases; do
  case $case in
    lecture) scene=$root/scenes/lecture.yaml pov_scene=lecture.pov variant=0 ;;
    whitted) scene=$root/scenes/lecture-whitted.yaml pov_scene=lecture.pov variant=1 ;;
    bunny) scene=$work/bunny.yaml pov_scene=bunny.pov variant=0 ;;
    *) echo "unknown scene $case (lecture, whitted, bunny)" >&2; exit 1 ;;
  esac
  pov $pov_scene $variant 0 pov.png
  "$build/bin/strahl" "$scene" -q -o strahl.pfm
  echo "== $(basename "$scene") vs $pov_scene WHITTED=$variant"
  echo -n "agreement (no AA, linear): "
  "$build/bin/strahl-diff" pov.png strahl.pfm
  tp=$(for i in 1 2 3; do wall pov $pov_scene $variant 1 pov_aa.png; done | median3)
  ts=$(for i in 1 2 3; do wall "$build/bin/strahl" "$scene" --supersample 4 --linear -q -o strahl_aa.png; done | median3)
  printf "4x4 supersampling, %d threads: POV-Ray %.2f s, strahl %.2f s, speed-up %.1fx\n" "$threads" "$tp" "$ts" \
    "$(echo "$tp / $ts" | bc -l)"
done
