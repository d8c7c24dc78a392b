#!/usr/bin/env bash
# A scripted session (--script: timed mouse and key events played into the window through SDL's
# event queue) orbits, pans, dollies, zooms and flies, stops, accumulates to the scene's samples
# per pixel and saves (Ctrl+S); P prints the camera. The saved image is `strahl`'s, bit for bit,
# of the scene with the printed camera, for several samplers and filters; and it is not the
# image of the scene's own camera (the controls moved it).
. "$(dirname "$0")/common.sh"

cat > "$WORK/moves.txt" << 'SCRIPT'
# orbit with the left button, pan with the right, dolly with the wheel, zoom with -, fly with W
0.2 mouse down left 40 30
0.02 mouse move 55 34
0.02 mouse move 70 40
0.02 mouse up left 70 40
0.05 mouse down right 60 40
0.02 mouse move 64 37
0 mouse up right 64 37
0.05 wheel 2
0.05 key -
0.05 keydown w
0.15 keyup w
0 wait still
0 key p
0 key ctrl+s
0 quit
SCRIPT

# check NAME SCENE OUTPUT_EXT ARGS...: the viewer's saved image = strahl's at the printed camera.
check() {
  local name=$1 scene=$2 ext=$3 before=$failures
  shift 3
  local args=(--width 96 --height 54 "$@")
  mkdir -p "$WORK/$name"
  ln -s "$SRC/scenes/meshes" "$WORK/$name/meshes"  # the scenes' mesh paths are relative
  if ! view_offscreen "$SRC/scenes/$scene" "${args[@]}" -o "$WORK/$name/view.$ext" --script "$WORK/moves.txt" \
      > "$WORK/$name/stdout.txt" 2> "$WORK/$name/stderr.txt"; then
    fail "$name: strahl-view failed: $(cat "$WORK/$name/stderr.txt")"
    return
  fi
  local saved="$WORK/$name/view-0001.$ext"
  [ -e "$saved" ] || { fail "$name: nothing saved: $(cat "$WORK/$name/stdout.txt")"; return; }
  grep -q "^saved .*view-0001.$ext (96x54," "$WORK/$name/stdout.txt" || fail "$name: no 'saved' line"
  sed -n '/^camera:/,/^[^ ]/p' "$WORK/$name/stdout.txt" | grep -E '^(camera:|  )' > "$WORK/$name/camera.yaml"
  grep -q "position:" "$WORK/$name/camera.yaml" || { fail "$name: no camera printed"; return; }
  with_camera "$SRC/scenes/$scene" "$WORK/$name/camera.yaml" "$WORK/$name/final.yaml"
  "$CLI" "$WORK/$name/final.yaml" "${args[@]}" -q -o "$WORK/$name/strahl.$ext" || { fail "$name: strahl failed"; return; }
  cmp -s "$saved" "$WORK/$name/strahl.$ext" || fail "$name: the viewer's image differs from strahl's at the printed camera"
  "$CLI" "$SRC/scenes/$scene" "${args[@]}" -q -o "$WORK/$name/start.$ext" || { fail "$name: strahl failed"; return; }
  cmp -s "$saved" "$WORK/$name/start.$ext" && fail "$name: the camera did not move"
  [ "$failures" = "$before" ] && echo "ok: $name"
}

# The input is looked at 60 times a second or more while frames take long: full-resolution
# moving frames (--scale 1) of a scene with meshes, 64 spp when still, a drag all the while.
{
  echo "0.1 mouse down left 10 10"
  for i in $(seq 1 40); do echo "0.03 mouse move $((10 + i)) $((10 + i / 2))"; done
  echo "0 mouse up left 50 30"
  echo "0.5 quit"
} > "$WORK/drag.txt"
if view_offscreen "$SRC/scenes/mesh.yaml" --width 480 --height 270 --spp 64 --scale 1 -o "$WORK/drag.png" \
    --script "$WORK/drag.txt" > "$WORK/drag.out" 2> "$WORK/drag.err"; then
  rate=$(sed -n 's/^input: .* (\([0-9]*\) Hz).*/\1/p' "$WORK/drag.out")
  if [ -n "$rate" ] && [ "$rate" -ge 60 ]; then echo "ok: input at $rate Hz while rendering"
  else fail "input looked at less than 60 times a second: $(cat "$WORK/drag.out")"; fi
else
  fail "the drag session failed: $(cat "$WORK/drag.err")"
fi

# Ctrl-C (SIGINT) and SIGTERM close the window and end with 130, at once, however long the
# still image would take (unlimited spp).
for signal in INT TERM; do
  printf '0 key u\n0 wait spp 2\n0 key ctrl+s\n600 quit\n' > "$WORK/long.txt"
  # Not under timeout(1), which would take the signal itself; a watchdog instead.
  SDL_VIDEODRIVER=offscreen "$VIEW" "$SRC/scenes/lecture-whitted.yaml" --width 96 --height 54 -o "$WORK/sig$signal.pfm" \
    --script "$WORK/long.txt" > /dev/null 2> "$WORK/sig.err" &
  pid=$!
  (sleep 120 && kill -KILL $pid) > /dev/null 2>&1 &
  watchdog=$!
  if wait_for "$WORK/sig$signal-0001.pfm" 60; then
    kill -$signal $pid
    started=$(date +%s%N)
    wait $pid
    rc=$?
    took=$((($(date +%s%N) - started) / 1000000))
    kill $watchdog 2> /dev/null
    if [ "$rc" = 130 ] && grep -q "strahl-view: interrupted" "$WORK/sig.err" && [ "$took" -lt 5000 ]; then
      echo "ok: SIG$signal ends the viewer with 130 in $took ms"
    else
      fail "SIG$signal: exit $rc after $took ms: $(cat "$WORK/sig.err")"
    fi
  else
    kill -KILL $pid $watchdog
    fail "SIG$signal: the viewer did not get going: $(cat "$WORK/sig.err")"
  fi
done

# Every key once (smoke): the viewer goes through all of them, rebuilds with the next
# accelerator (B), reloads (L), shows every AOV (V), saves one (Ctrl+S while showing depth),
# and ends normally; R brings back the scene's camera, so the last save is strahl's image.
cat > "$WORK/keys.txt" << 'SCRIPT'
0.1 mouse move 48 30
0 key f
0 key ]
0 key [
0 key [
0 key m
0 key .
0 key ,
0 key u
0 key u
0 key 9
0 key 0
0 key +
0 key -
0 key tab
0 key h
0 key f1
0 key tab
0 key p
0 key b
0 wait reload 1
0 key l
0 wait reload 2
0 key v
0 wait still
0 key ctrl+s
0 key v
0 key v
0 key v
0 key v
0 key m
0 key m
0 key m
0 key m
0 key ]
0 key r
0 wait still
0 key ctrl+s
0 key escape
SCRIPT
if view_offscreen "$SRC/scenes/lecture-whitted.yaml" --width 96 --height 54 -o "$WORK/keys.pfm" --script "$WORK/keys.txt" \
    > "$WORK/keys.out" 2> "$WORK/keys.err"; then
  [ "$(grep -c '^reloaded' "$WORK/keys.out")" = 2 ] || fail "keys: not two reloads (B, L): $(cat "$WORK/keys.out")"
  [ -e "$WORK/keys.depth-0001.exr" ] || fail "keys: the depth AOV was not saved: $(cat "$WORK/keys.out")"
  "$CLI" "$SRC/scenes/lecture-whitted.yaml" --width 96 --height 54 -q -o "$WORK/keys.strahl.pfm" || fail "strahl failed"
  cmp -s "$WORK/keys-0001.pfm" "$WORK/keys.strahl.pfm" || fail "keys: after R (and the settings back) the image is not strahl's"
  [ -s "$WORK/keys.err" ] && fail "keys: messages on stderr: $(cat "$WORK/keys.err")"
  [ "$failures" = 0 ] && echo "ok: every key"
else
  fail "keys: strahl-view failed: $(cat "$WORK/keys.err")"
fi

# X explains the pixel under the cursor: what `strahl --explain` prints for that pixel.
printf '0.2 mouse move 40 20\n0 wait still\n0 key x\n0 quit\n' > "$WORK/explain.txt"
if view_offscreen "$SRC/scenes/lecture-whitted.yaml" --width 96 --height 54 -q -o "$WORK/explain.png" \
    --script "$WORK/explain.txt" > "$WORK/explain.raw" 2> "$WORK/explain.err"; then
  grep -v '^input: ' "$WORK/explain.raw" > "$WORK/explain.out"
  pixel=$(sed -n 's/^pixel (\([0-9]*\), \([0-9]*\)) of 96×54 .*/\1,\2/p' "$WORK/explain.out")
  if [ -z "$pixel" ]; then
    fail "explain: nothing explained: $(cat "$WORK/explain.raw")"
  elif [ "$pixel" != 40,20 ]; then  # the window shows the image at its size: window pixel = image pixel
    fail "explain: the cursor is over pixel 40,20, the viewer explained $pixel"
  elif "$CLI" "$SRC/scenes/lecture-whitted.yaml" --width 96 --height 54 --explain "$pixel" > "$WORK/explain.strahl"; then
    if cmp -s "$WORK/explain.out" "$WORK/explain.strahl"; then echo "ok: X explains pixel $pixel as strahl --explain"
    else fail "explain: the viewer's explanation of $pixel differs from strahl's"; fi
  else
    fail "explain: strahl --explain $pixel failed"
  fi
else
  fail "explain: strahl-view failed: $(cat "$WORK/explain.err")"
fi

# G switches to path tracing (and back): the still image is `strahl --integrator path`'s, bit for
# bit, and not Whitted's; a second G gives Whitted's again. X under path tracing explains nothing.
printf '0 wait still\n0 key g\n0 wait still\n0 key ctrl+s\n0 key x\n0 key g\n0 wait still\n0 key ctrl+s\n0 quit\n' \
  > "$WORK/path.txt"
if view_offscreen "$SRC/scenes/lecture-whitted.yaml" --width 96 --height 54 --spp 4 --sampler sobol -o "$WORK/path.pfm" \
    --script "$WORK/path.txt" > "$WORK/path.out" 2> "$WORK/path.err"; then
  "$CLI" "$SRC/scenes/lecture-whitted.yaml" --width 96 --height 54 --spp 4 --sampler sobol --integrator path -q \
    -o "$WORK/path.strahl.pfm" || fail "strahl --integrator path failed"
  "$CLI" "$SRC/scenes/lecture-whitted.yaml" --width 96 --height 54 --spp 4 --sampler sobol -q \
    -o "$WORK/whitted.strahl.pfm" || fail "strahl failed"
  if ! cmp -s "$WORK/path-0001.pfm" "$WORK/path.strahl.pfm"; then fail "G: the image is not strahl --integrator path's"
  elif cmp -s "$WORK/path.strahl.pfm" "$WORK/whitted.strahl.pfm"; then fail "G: path tracing gave Whitted's image"
  elif ! cmp -s "$WORK/path-0002.pfm" "$WORK/whitted.strahl.pfm"; then fail "G twice: the image is not Whitted's"
  elif grep -q "^pixel (" "$WORK/path.out"; then fail "X explained a path-traced pixel"
  else echo "ok: G switches between path tracing and Whitted's ray tracing"; fi
else
  fail "path: strahl-view failed: $(cat "$WORK/path.err")"
fi

check grid       lecture.yaml         pfm --supersample 2
check png        lecture-whitted.yaml png --supersample 2
check stratified lecture-whitted.yaml pfm --sampler stratified --spp 4 --filter mitchell --filter-radius 2
check random     soft-shadows.yaml    exr --sampler random --spp 3
check adaptive   lecture-whitted.yaml pfm --sampler adaptive --spp 16 --adaptive-min 2
check lens       depth-of-field.yaml  pfm --sampler sobol --spp 4
check mesh       mesh.yaml            pfm --max-depth 3
finish
