#!/usr/bin/env bash
# The issue's figure for instances (docs/scene-format.md, "Instances"): the Stanford bunny
# (69,451 triangles, ../shared/data/stanford-bunny.obj) once, and 10,000 instances of it on a
# 100 x 100 grid, each turned and scaled, rendered at 640x360 (1 sample per pixel, all cores).
# Prints the peak resident memory and the wall time of each run, from /usr/bin/time -v.
#   bench/instances-bunny.sh [build-dir] [count]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
count=${2:-10000}
bunny=$root/../shared/data/stanford-bunny.obj
[ -f "$bunny" ] || { echo "missing $bunny" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "/usr/bin/time is not installed (apt-get install time)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$bunny" "$work/bunny.obj"
head='camera: {position: [0, 60, 120], look_at: [0, 0, 0], fov: 60}
render: {width: 640, height: 360}
lights:
  - {type: point, position: [50, 100, 80]}
  - {type: directional, direction: [-1, -2, -1], intensity: 0.4}
'
side=$(python3 -c "import math; print(math.ceil(math.sqrt($count)))")
{
  printf '%s' "$head"
  echo 'objects:'
  echo '  - {type: plane, normal: [0, 1, 0], distance: -0.7}'
  echo '  - {type: mesh, file: bunny.obj, scale: 10}'
} > "$work/one.yaml"
{
  printf '%s' "$head"
  echo 'groups:'
  echo '  bunny: [{type: mesh, file: bunny.obj, scale: 10}]'
  echo 'objects:'
  echo '  - {type: plane, normal: [0, 1, 0], distance: -0.7}'
  python3 - "$count" "$side" <<'PY'
import sys
count, side = int(sys.argv[1]), int(sys.argv[2])
for k in range(count):
    i, j = k % side, k // side
    print("  - {type: instance, of: bunny, transform: [{rotate: {axis: [0, 1, 0], angle: %d}}, {scale: %.2f}, "
          "{translate: [%.1f, 0, %.1f]}]}" % ((k * 37) % 360, 0.8 + 0.05 * (k % 9), (i - side / 2) * 2.5, (j - side / 2) * 2.5 - 60))
PY
} > "$work/many.yaml"
cd "$work"
for scene in one many; do
  /usr/bin/time -v "$build/bin/strahl" "$scene.yaml" -o "$scene.png" > "$scene.out" 2> "$scene.time"
  echo "== $scene.yaml ($( [ $scene = one ] && echo "one bunny" || echo "$count bunny instances"))"
  grep -E '^(scene|accel|time|memory) ' "$scene.out" || true
  grep -E 'Maximum resident set size|Elapsed \(wall clock\)' "$scene.time" | sed 's/^\t*/  /'
done
