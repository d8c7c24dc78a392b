#!/usr/bin/env bash
# Time to quality (issue 14): how long until the lecture scene and its Whitted variant are within
# RMSE 2e-3 (0..1 linear values) of a converged reference — strahl's adaptive sampler against
# POV-Ray 3.7's adaptive anti-aliasing (+AM2), side by side in one run. The reference is strahl
# with 1024 stratified samples per pixel (the two renderers' images agree to RMSE ~1e-5 without
# anti-aliasing: bench/povray-compare.sh), written as PFM; POV-Ray writes 16-bit PNG with
# File_Gamma=1.0 so that its quantisation (~5e-6) does not count. Each setting's time is the
# median of three runs (wall time of the whole process; single runs on a shared machine vary by
# ±25 %); the table lists every setting, then the fastest one that reaches the goal for each
# renderer.
#   bench/time-to-quality.sh [build-dir] [width] [height] [goal]   (defaults: build 960 540 2e-3)
# (needs: apt-get install povray)
set -euo pipefail
default_width=960 default_height=540
# shellcheck source=bench/quality-common.sh
source "$(dirname "$0")/quality-common.sh"
cp "$pov_scene" "$work/lecture.pov"
cd "$work"

pov() {  # pov WHITTED OPTIONS…
  local variant=$1
  shift
  povray -D -V +W"$width" +H"$height" +WT"$threads" +FN16 File_Gamma=1.0 +Ilecture.pov +Opov.png \
    Declare=WHITTED="$variant" "$@" >/dev/null 2>&1
}

echo "load: $(cut -d' ' -f1-3 /proc/loadavg); ${width}x${height}, $threads threads, goal RMSE $goal"
for variant in 0 1; do
  scene=$root/scenes/lecture.yaml
  [ $variant = 1 ] && scene=$root/scenes/lecture-whitted.yaml
  name=$(basename "$scene" .yaml)
  size=(--width "$width" --height "$height")
  t=$(wall1 "$build/bin/strahl" "$scene" "${size[@]}" --sampler stratified --spp 1024 -q -o ref.pfm)
  printf "== %s: reference 1024 spp stratified in %.1f s\n" "$name" "$t"
  best_s="" best_p=""
  for thr in 0.5 0.2 0.1 0.05 0.02; do
    for min in 4 16; do
      t=$(wall "$build/bin/strahl" "$scene" "${size[@]}" --sampler adaptive --spp 1024 --adaptive-min $min \
            --adaptive-threshold $thr -q -o s.pfm)
      e=$(rmse ref.pfm s.pfm)
      printf "strahl  adaptive min %2d threshold %-5s  %7.2f s  rmse %s\n" "$min" "$thr" "$t" "$e"
      keep_best best_s "$t" "$e" "adaptive min $min threshold $thr"
    done
  done
  # One sample per pixel, then refinement where a pixel stands out from its neighbours.
  for thr in 0.5 0.3 0.2 0.1 0.07 0.05; do
    t=$(wall "$build/bin/strahl" "$scene" "${size[@]}" --sampler adaptive --spp 16 --adaptive-min 1 \
          --adaptive-threshold $thr -q -o s.pfm)
    e=$(rmse ref.pfm s.pfm)
    printf "strahl  adaptive min  1 threshold %-5s  %7.2f s  rmse %s  (spp 16)\n" "$thr" "$t" "$e"
    keep_best best_s "$t" "$e" "adaptive min 1 threshold $thr spp 16"
  done
  for spp in 4 16 64; do
    t=$(wall "$build/bin/strahl" "$scene" "${size[@]}" --sampler stratified --spp $spp -q -o s.pfm)
    e=$(rmse ref.pfm s.pfm)
    printf "strahl  stratified %3d spp              %7.2f s  rmse %s\n" "$spp" "$t" "$e"
    keep_best best_s "$t" "$e" "stratified $spp spp"
  done
  for setting in "+AM2 +A0.1 +R3" "+AM2 +A0.05 +R3" "+AM2 +A0.02 +R4" "+AM2 +A0.01 +R4" "+AM2 +A0.0 +R4"; do
    # shellcheck disable=SC2086
    t=$(wall pov $variant $setting)
    e=$(rmse ref.pfm pov.png)
    printf "POV-Ray %-30s %7.2f s  rmse %s\n" "$setting" "$t" "$e"
    keep_best best_p "$t" "$e" "$setting"
  done
  echo "fastest within $goal: strahl ${best_s:-none}; POV-Ray ${best_p:-none}"
  speed_up "time to quality" "$best_s" "$best_p"
done
echo "load: $(cut -d' ' -f1-3 /proc/loadavg)"
