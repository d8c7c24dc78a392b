#!/usr/bin/env bash
# Soft shadows against POV-Ray: the lecture scene with its point light made a sphere light of
# radius 0.15 (scenes/lecture-distributed.yaml without the thin lens), and in POV-Ray the same
# light as an area light — a jittered n×n disk of diameter 0.3 turned towards each point
# (`circular orient`), shading from every sub-light (`area_illumination on`) and falling off as
# 1/d² (`fade_power 2` with a tiny `fade_distance`, the colour scaled to strahl's radiance). How
# long until each renderer's image is within RMSE `goal` (0..1 linear values) of its own converged
# image: strahl with 1024 stratified samples per pixel, each with 2×2 light samples; POV-Ray with
# 16×16 sub-lights and 3×3 anti-aliasing samples in every pixel (+AM1 +A0.0 +R3). The two
# converged images should agree to ~1e-3 (the disk is not exactly the sphere's silhouette); the
# script prints that too. strahl runs stratified pixel samples at 4, 16 and 64 spp with 1×1, 2×2
# and 3×3 light samples each; POV-Ray 4×4 … 12×12 sub-lights with its adaptive anti-aliasing.
# Each time is the median of three runs (wall time of the whole process); the last lines name
# the fastest setting of each within the goal.
#   bench/soft-shadows-pov.sh [build-dir] [width] [height] [goal]   (defaults: build 480 270 2e-3)
# (needs: apt-get install povray)
set -euo pipefail
default_width=480 default_height=270
# shellcheck source=bench/quality-common.sh
source "$(dirname "$0")/quality-common.sh"
cd "$work"
# The sphere light's radiance L = 150 gives E = L·π·r²/d² (small light), strahl's shading takes
# E/π; POV-Ray's fade gives I·2/(1 + (d/f)²) ≈ I·2f²/d², so I = 150·0.15² / (2·0.01²) = 16875.
grep -q '^light_source { <1, 1.5, 1> color rgb <1,1,1> }$' "$pov_scene" ||
  { echo "$pov_scene: its light_source line changed; update this script" >&2; exit 2; }
sed -e 's|^light_source { <1, 1.5, 1> color rgb <1,1,1> }$|#ifndef (AREA) #declare AREA = 8; #end\
light_source { <1, 1.5, 1> color rgb 16875 fade_distance 0.01 fade_power 2\
  area_light <0.3, 0, 0>, <0, 0, 0.3>, AREA, AREA circular orient jitter area_illumination on }|' \
  "$pov_scene" > soft.pov
sed -e '/aperture:/d' -e '/focus_point:/d' "$root/scenes/lecture-distributed.yaml" > soft-2.yaml
for k in 1 3; do sed -e "s/samples: 2}/samples: $k}/" soft-2.yaml > "soft-$k.yaml"; done
grep -q 'samples: 3}' soft-3.yaml || { echo "scenes/lecture-distributed.yaml: its light changed; update this script" >&2; exit 2; }

pov() {  # pov AREA OPTIONS…
  local area=$1
  shift
  povray -D -V +W"$width" +H"$height" +WT"$threads" +FN16 File_Gamma=1.0 +Isoft.pov +O"$out" \
    Declare=AREA="$area" "$@" >/dev/null 2>&1
}
size=(--width "$width" --height "$height")

echo "load: $(cut -d' ' -f1-3 /proc/loadavg); ${width}x${height}, $threads threads, goal RMSE $goal"
t=$(wall1 "$build/bin/strahl" soft-2.yaml "${size[@]}" --sampler stratified --spp 1024 -q -o ref-strahl.pfm)
printf "strahl reference: 1024 spp stratified, 2x2 light samples each, in %.1f s\n" "$t"
out=ref-pov.png
t=$(wall1 pov 16 +AM1 +A0.0 +R3)
printf "POV-Ray reference: 16x16 sub-lights, +AM1 +A0.0 +R3, in %.1f s\n" "$t"
echo "agreement of the references: $("$build/bin/strahl-diff" ref-strahl.pfm ref-pov.png)"
best_s="" best_p=""
for spp in 4 16 64; do
  for k in 1 2 3; do
    t=$(wall "$build/bin/strahl" "soft-$k.yaml" "${size[@]}" --sampler stratified --spp $spp -q -o s.pfm)
    e=$(rmse ref-strahl.pfm s.pfm)
    printf "strahl  stratified %2d spp, %dx%d light samples   %7.2f s  rmse %s\n" "$spp" "$k" "$k" "$t" "$e"
    keep_best best_s "$t" "$e" "stratified $spp spp, ${k}x$k light samples"
  done
done
out=pov.png
for area in 4 6 8 12; do
  for setting in "+AM2 +A0.1 +R3" "+AM2 +A0.05 +R3"; do
    # shellcheck disable=SC2086
    t=$(wall pov $area $setting)
    e=$(rmse ref-pov.png pov.png)
    printf "POV-Ray %2dx%-2d sub-lights, %-16s    %7.2f s  rmse %s\n" "$area" "$area" "$setting" "$t" "$e"
    keep_best best_p "$t" "$e" "${area}x$area sub-lights, $setting"
  done
done
echo "fastest within $goal of its own reference: strahl ${best_s:-none}; POV-Ray ${best_p:-none}"
speed_up "soft shadows, time to quality" "$best_s" "$best_p"
echo "load: $(cut -d' ' -f1-3 /proc/loadavg)"
