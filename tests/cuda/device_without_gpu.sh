#!/bin/bash
# cuda_device_without_gpu: --device on a machine without a usable GPU (docs/gpu.md).
#   device_without_gpu.sh <strahl> cuda|none     (cuda: built with the CUDA back end)
# --device cuda: one line "strahl: error: --device cuda: <why>", exit 2, nothing written;
# --device auto: renders on the CPU, says so on stderr, the summary names the CPU, and the image
# equals --device cpu's; --device cuda with --accel kdtree: exit 1; an unknown device: exit 1.
strahl=$1 built=$2
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

"$strahl" --device cuda --accel kdtree -o "$work/kd.png" 2> "$work/err"; rc=$?
cat "$work/err"
[ $rc = 1 ] || fail "--device cuda --accel kdtree exited $rc, not 1"
grep -q "renders with --accel bvh or naive" "$work/err" || fail "--accel kdtree: unexpected message"
"$strahl" --device gpu -o "$work/x.png" 2> /dev/null; rc=$?
[ $rc = 1 ] || fail "--device gpu exited $rc, not 1"
echo "all checks passed"
