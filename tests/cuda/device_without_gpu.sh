#!/bin/bash
# cuda_device_without_gpu: --device on a machine without a usable GPU (docs/gpu.md).
#   device_without_gpu.sh <strahl> cuda|none [<strahl-view>]    (cuda: built with the CUDA back end)
# --device cuda: one line "strahl: error: --device cuda: <why>", exit 2, nothing written;
# --device auto: renders on the CPU, says so on stderr, the summary names the CPU, and the image
# equals --device cpu's; --device cuda with --accel kdtree asks for the GPU as with the BVH (exit
# 2, the same reason); with --accel embree (where built): exit 1; an unknown device: exit 1.
# strahl-view (where built) the same way, through its headless --benchmark.
strahl=$1 built=$2 viewer=${3:-}
fail() { echo "FAIL: $*"; exit 1; }
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT

"$strahl" --device cuda --width 40 --height 30 -o "$work/cuda.png" > "$work/out" 2> "$work/err"; rc=$?
if [ $rc = 0 ]; then echo "a GPU is usable here: skipped"; exit 77; fi
cat "$work/err"
[ $rc = 2 ] || fail "--device cuda exited $rc, not 2"
[ "$(wc -l < "$work/err")" = 1 ] || fail "--device cuda: not one line on stderr"
if [ "$built" = cuda ]; then
  grep -Eq "^strahl: error: --device cuda: (no CUDA driver \(libcuda.so.1 cannot be loaded\)|no CUDA device found|no usable CUDA driver|CUDA is not usable)" "$work/err" \
    || fail "--device cuda (built with CUDA): unexpected message"
else
  grep -q "^strahl: error: --device cuda: strahl was built without CUDA" "$work/err" \
    || fail "--device cuda (built without CUDA): unexpected message"
fi
[ ! -e "$work/cuda.png" ] || fail "--device cuda wrote an image"

"$strahl" --device auto --width 40 --height 30 -o "$work/auto.png" > "$work/out" 2> "$work/err"; rc=$?
cat "$work/err"
[ $rc = 0 ] || fail "--device auto exited $rc"
grep -q "^strahl: --device auto: .*; rendering on the CPU$" "$work/err" || fail "--device auto did not say it used the CPU"
grep -q "^device      cpu (" "$work/out" || fail "--device auto: the summary does not name the CPU"
"$strahl" --device cpu --width 40 --height 30 -o "$work/cpu.png" -q || fail "--device cpu failed"
cmp -s "$work/auto.png" "$work/cpu.png" || fail "--device auto's image differs from --device cpu's"

"$strahl" --device cuda --width 40 --height 30 -o "$work/cuda.png" 2> "$work/bvh-err"
for accel in kdtree octree naive; do
  "$strahl" --device cuda --accel $accel --width 40 --height 30 -o "$work/kd.png" 2> "$work/err"; rc=$?
  [ $rc = 2 ] || fail "--device cuda --accel $accel exited $rc, not 2"
  cmp -s "$work/err" "$work/bvh-err" || fail "--device cuda --accel $accel: not the BVH's reason: $(cat "$work/err")"
done
embree=no
"$strahl" --help | grep -q embree && embree=yes
if [ $embree = yes ]; then
  "$strahl" --device cuda --accel embree -o "$work/em.png" 2> "$work/err"; rc=$?
  cat "$work/err"
  [ $rc = 1 ] || fail "--device cuda --accel embree exited $rc, not 1"
  grep -q "renders with --accel bvh, kdtree, octree or naive, not embree" "$work/err" || fail "--accel embree: unexpected message"
fi
"$strahl" --device gpu -o "$work/x.png" 2> /dev/null; rc=$?
[ $rc = 1 ] || fail "--device gpu exited $rc, not 1"

if [ -n "$viewer" ]; then
  small=(--width 40 --height 30 --benchmark 2)
  "$viewer" --device cuda "${small[@]}" > "$work/out" 2> "$work/err"; rc=$?
  cat "$work/err"
  [ $rc = 2 ] || fail "strahl-view --device cuda exited $rc, not 2"
  [ "$(wc -l < "$work/err")" = 1 ] || fail "strahl-view --device cuda: not one line on stderr"
  grep -q "^strahl-view: error: --device cuda: " "$work/err" || fail "strahl-view --device cuda: unexpected message"
  [ ! -s "$work/out" ] || fail "strahl-view --device cuda rendered"
  "$viewer" --device auto "${small[@]}" > "$work/out" 2> "$work/err"; rc=$?
  cat "$work/err" "$work/out"
  [ $rc = 0 ] || fail "strahl-view --device auto exited $rc"
  grep -q "^strahl-view: --device auto: .*; rendering on the CPU$" "$work/err" \
    || fail "strahl-view --device auto did not say it used the CPU"
  grep -Eq "^strahl-view benchmark: .*, [0-9]+ threads$" "$work/out" || fail "strahl-view --device auto: not on the CPU's threads"
  if [ $embree = yes ]; then
    "$viewer" --device cuda --accel embree "${small[@]}" 2> "$work/err"; rc=$?
    [ $rc = 1 ] || fail "strahl-view --device cuda --accel embree exited $rc, not 1"
    grep -q "renders with --accel bvh, kdtree, octree or naive" "$work/err" || fail "strahl-view --accel embree: unexpected message"
  fi
  "$viewer" --device gpu "${small[@]}" 2> /dev/null; rc=$?
  [ $rc = 1 ] || fail "strahl-view --device gpu exited $rc, not 1"
fi
echo "all checks passed"
