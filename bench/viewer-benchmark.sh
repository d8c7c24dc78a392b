#!/usr/bin/env bash
# strahl-view --benchmark (docs/viewer.md, "Benchmark") on the issue's three scenes at 640×360,
# one sample per pixel per frame: the lecture scene, its Whitted variant (mirror and glass) and
# the Stanford bunny on a plane (the scene of bench/cluster-efficiency.sh). Prints the load
# average first: the machine may be shared.
#   bench/viewer-benchmark.sh [build dir] [stanford-bunny.obj] [frames]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
bunny=${2:-$here/../../shared/data/stanford-bunny.obj}
frames=${3:-100}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cat > "$work/bunny.yaml" << SCENE
camera: {position: [0, 0.12, 0.32], look_at: [-0.02, 0.09, 0], up: [0, 1, 0], fov: 40}
render: {width: 1280, height: 720}
materials:
  floor: {color: 0.6, ambient: 0.1, diffuse: 0.7, specular: 0.3, shininess: 50}
  bunny: {color: [0.8, 0.7, 0.5], ambient: 0.1, diffuse: 0.7, specular: 0.6, shininess: 100}
lights: [{type: point, position: [0.5, 1, 1], intensity: 1}]
objects:
  - {type: plane, normal: [0, 1, 0], distance: 0.033, material: floor}
  - {type: mesh, file: $bunny, material: bunny}
SCENE

echo "load: $(cut -d' ' -f1-3 /proc/loadavg)"
for scene in "$here/../scenes/lecture.yaml" "$here/../scenes/lecture-whitted.yaml" "$work/bunny.yaml"; do
  "$build/bin/strahl-view" "$scene" --width 640 --height 360 --benchmark "$frames" | sed "s|$work/||"
done
echo "load: $(cut -d' ' -f1-3 /proc/loadavg)"
