#!/usr/bin/env bash
# The issue's figure for instances (docs/scene-format.md, "Instances"): the Stanford bunny
# (69,451 triangles, ../shared/data/stanford-bunny.obj) once, and 10,000 instances of it on a
# 100 x 100 grid, each turned and scaled, rendered at 640x360 (1 sample per pixel, all cores).
# Then 1,000,000 instances of it by nested groups (100 bunnies in a row, 100 rows in a field,
# 100 fields in a stack). Prints the peak resident memory and the wall time of each run, from
# /usr/bin/time -v.
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
# Nested instances: a row of 100 bunnies, a field of 100 rows, a stack of 100 fields (1,000,000
# records from a file of about 300 lines).
{
  printf '%s' "$head"
  echo 'groups:'
  echo '  bunny: [{type: mesh, file: bunny.obj, scale: 8}]'
  python3 - <<'PY'
print("  row:")
for i in range(100):
    print("    - {type: instance, of: bunny, translate: [%.1f, 0, 0], rotate: [0, %d, 0]}" % (i * 1.6 - 79.2, (i * 37) % 360))
for name, inner, axis in (("field", "row", 2), ("stack", "field", 1)):
    print("  %s:" % name)
    for k in range(100):
        t = [0, 0, 0]
        t[axis] = -1.6 * k if axis == 2 else 1.6 * k
        print("    - {type: instance, of: %s, translate: [%.1f, %.1f, %.1f]}" % (inner, t[0], t[1], t[2]))
PY
  echo 'objects:'
  echo '  - {type: plane, normal: [0, 1, 0], distance: -0.7}'
  echo '  - {type: instance, of: stack, translate: [0, 0, -40]}'
} > "$work/nested.yaml"
cd "$work"
for scene in one many nested; do
  /usr/bin/time -v "$build/bin/strahl" "$scene.yaml" -o "$scene.png" > "$scene.out" 2> "$scene.time"
  case $scene in
    one) what="one bunny" ;;
    many) what="$count bunny instances" ;;
    *) what="1000000 bunny instances by nested groups" ;;
  esac
  echo "== $scene.yaml ($what)"
  grep -E '^(scene|instances|accel|time|memory) ' "$scene.out" || true
  grep -E 'Maximum resident set size|Elapsed \(wall clock\)' "$scene.time" | sed 's/^\t*/  /'
done
