#!/usr/bin/env bash
# strahl-view --benchmark (docs/viewer.md, "Benchmark") on the issue's three scenes at 640×360,
# one sample per pixel per frame: the lecture scene, its Whitted variant (mirror and glass) and
# the Stanford bunny on a plane (the scene of bench/cluster-efficiency.sh). Prints the load
# average first: the machine may be shared.
#   bench/viewer-benchmark.sh [build dir] [stanford-bunny.obj] [frames]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
bunny=$(realpath -m "${2:-$here/../../shared/data/stanford-bunny.obj}")  # (the scene is written elsewhere)
frames=${3:-100}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# shellcheck source=bench/bunny-scene.sh
. "$here/bunny-scene.sh"
bunny_scene "$bunny" "{width: 1280, height: 720}" > "$work/bunny.yaml"

echo "load: $(cut -d' ' -f1-3 /proc/loadavg)"
for scene in "$here/../scenes/lecture.yaml" "$here/../scenes/lecture-whitted.yaml" "$work/bunny.yaml"; do
  "$build/bin/strahl-view" "$scene" --width 640 --height 360 --benchmark "$frames" | sed "s|$work/||"
done
echo "load: $(cut -d' ' -f1-3 /proc/loadavg)"
