#!/usr/bin/env bash
# Depth of field against POV-Ray: the lecture scene (point light) seen through a thin lens of
# radius 0.04 focused on the plane through the red sphere (scenes/lecture-distributed.yaml's
# camera), and in POV-Ray the same camera with focal blur. POV-Ray's lens: `aperture` A gives
# lens offsets of A/2 times points of a disc of radius 1/2 (core/render/tracepixel.cpp,
# JitterCameraRay), so A = 4 × 0.04; its plane in focus lies at |focal_point − location| along
# the view axis, which strahl is given as focus_distance. How long until each renderer's image is
# within RMSE `goal` (0..1 linear values) of its own converged image: strahl with 1024 stratified
# samples per pixel; POV-Ray with 400 blur samples in every pixel (`blur_samples 400, 400`). The
# two converged images should agree to ~1e-3 (POV-Ray jitters its lens points a little past the
# disc); the script prints that too. strahl runs its stratified, Sobol and adaptive samplers;
# POV-Ray its adaptive focal blur (`blur_samples min, max` with `confidence` and `variance`: it
# stops a pixel once the samples' variance is small enough), without anti-aliasing (-A: the blur
# samples jitter the pixel position already). Each time is the median of three runs (wall time
# of the whole process); the last lines name the fastest setting of each within the goal.
#   bench/depth-of-field-pov.sh [build-dir] [width] [height] [goal]   (defaults: build 480 270 2e-3)
# (needs: apt-get install povray)
set -euo pipefail
default_width=480 default_height=270
# shellcheck source=bench/quality-common.sh
source "$(dirname "$0")/quality-common.sh"
cd "$work"
# The lens: strahl's camera of lecture-distributed.yaml, its focus point's distance from the eye.
aperture=0.04 focus="0.05, 0.3, 0"
distance=$(echo "sqrt(0.05^2 + 0.5^2 + 2.2^2)" | bc -l)
grep -q '^  angle 50 ' "$pov_scene" || { echo "$pov_scene: its camera changed; update this script" >&2; exit 2; }
sed -e "s|^  angle 50 .*|&\\
  aperture $(echo "4 * $aperture" | bc -l) focal_point <$focus> blur_samples BMIN, BMAX confidence CONF variance VAR|" \
  -e '1i #ifndef (BMIN) #declare BMIN = 400; #declare BMAX = 400; #declare CONF = 0.9; #declare VAR = 0; #end' \
  "$pov_scene" > dof.pov
sed -e "s|^  fov_axis: horizontal$|&\\
  aperture: $aperture\\
  focus_distance: $distance|" "$root/scenes/lecture.yaml" > dof.yaml
grep -q 'focus_distance' dof.yaml || { echo "scenes/lecture.yaml: its camera changed; update this script" >&2; exit 2; }

pov() {  # pov MIN MAX CONFIDENCE VARIANCE
  povray -D -V +W"$width" +H"$height" +WT"$threads" +FN16 File_Gamma=1.0 -A +Idof.pov +O"$out" \
    Declare=BMIN="$1" Declare=BMAX="$2" Declare=CONF="$3" Declare=VAR="$4" >/dev/null 2>&1
}
size=(--width "$width" --height "$height")

echo "load: $(cut -d' ' -f1-3 /proc/loadavg); ${width}x${height}, $threads threads, goal RMSE $goal"
t=$(wall1 "$build/bin/strahl" dof.yaml "${size[@]}" --sampler stratified --spp 1024 -q -o ref-strahl.pfm)
printf "strahl reference: 1024 spp stratified in %.1f s\n" "$t"
out=ref-pov.png
t=$(wall1 pov 400 400 0.9 0)
printf "POV-Ray reference: blur_samples 400, 400 in %.1f s\n" "$t"
echo "agreement of the references: $("$build/bin/strahl-diff" ref-strahl.pfm ref-pov.png)"
best_s="" best_p=""
for sampler in stratified sobol; do
  for spp in 4 9 16 36 64; do
    t=$(wall "$build/bin/strahl" dof.yaml "${size[@]}" --sampler $sampler --spp $spp -q -o s.pfm)
    e=$(rmse ref-strahl.pfm s.pfm)
    printf "strahl  %-10s %3d spp                       %7.2f s  rmse %s\n" "$sampler" "$spp" "$t" "$e"
    keep_best best_s "$t" "$e" "$sampler $spp spp"
  done
done
for thr in 0.1 0.05 0.02; do
  for min in 4 16; do
    t=$(wall "$build/bin/strahl" dof.yaml "${size[@]}" --sampler adaptive --spp 256 --adaptive-min $min \
          --adaptive-threshold $thr -q -o s.pfm)
    e=$(rmse ref-strahl.pfm s.pfm)
    printf "strahl  adaptive min %2d threshold %-5s spp 256 %7.2f s  rmse %s\n" "$min" "$thr" "$t" "$e"
    keep_best best_s "$t" "$e" "adaptive min $min threshold $thr spp 256"
  done
done
out=pov.png
for n in 7 19 37 64; do
  t=$(wall pov $n $n 0.9 0)
  e=$(rmse ref-pov.png pov.png)
  printf "POV-Ray blur_samples %-3d %-3d                                   %7.2f s  rmse %s\n" "$n" "$n" "$t" "$e"
  keep_best best_p "$t" "$e" "blur_samples $n, $n"
done
for max in 64 256; do
  for setting in "0.9 0.0078125" "0.95 0.001953125" "0.99 0.000244140625"; do
    read -r conf var <<< "$setting"
    t=$(wall pov 7 $max "$conf" "$var")
    e=$(rmse ref-pov.png pov.png)
    printf "POV-Ray blur_samples 7   %-3d confidence %-4s variance %-14s %7.2f s  rmse %s\n" "$max" "$conf" "$var" "$t" "$e"
    keep_best best_p "$t" "$e" "blur_samples 7, $max, confidence $conf variance $var"
  done
done
echo "fastest within $goal of its own reference: strahl ${best_s:-none}; POV-Ray ${best_p:-none}"
speed_up "depth of field, time to quality" "$best_s" "$best_p"
echo "load: $(cut -d' ' -f1-3 /proc/loadavg)"
