#!/usr/bin/env bash
# POV-Ray scenes read by strahl (docs/pov-import.md) against POV-Ray 3.7 rendering the same file:
# each FILE.pov (default: scenes/lecture.pov, bench/shapes.pov, bench/csg.pov, bench/plate.pov,
# bench/pov/language.pov, bench/pov/spotlights.pov, bench/pov/imagemap.pov, bench/pov/uvmap.pov and
# bench/pov/emission.pov)
# at WIDTHxHEIGHT (default 480x270), no anti-aliasing, linear 16-bit output; prints strahl-diff's agreement line (RMSE on 0..1 values) for each.
#   bench/povray-import.sh [build-dir] [FILE.pov …]      (needs: apt-get install povray)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
shift || true
files=("$@")
[ ${#files[@]} -gt 0 ] || files=("$root/scenes/lecture.pov" "$root/bench/shapes.pov" "$root/bench/csg.pov" "$root/bench/plate.pov"
                                  "$root/bench/pov/language.pov" "$root/bench/pov/spotlights.pov" "$root/bench/pov/imagemap.pov"
                                  "$root/bench/pov/uvmap.pov" "$root/bench/pov/emission.pov")
width=${WIDTH:-480}
height=${HEIGHT:-270}
command -v povray >/dev/null || { echo "povray is not installed (apt-get install povray)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for f in "${files[@]}"; do
  name=$(basename "$f" .pov)
  (cd "$(dirname "$f")" && povray -D -V +W"$width" +H"$height" +FN16 File_Gamma=1.0 -A +I"$(basename "$f")" \
    +O"$work/$name-pov.png" >/dev/null 2>&1)
  "$build/bin/strahl" "$f" --width "$width" --height "$height" -q -o "$work/$name-strahl.pfm"
  printf '%-14s %s\n' "$name.pov" "$("$build/bin/strahl-diff" "$work/$name-pov.png" "$work/$name-strahl.pfm")"
done
