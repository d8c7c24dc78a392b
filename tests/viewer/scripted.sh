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

check grid       lecture.yaml         pfm --supersample 2
check png        lecture-whitted.yaml png --supersample 2
check stratified lecture-whitted.yaml pfm --sampler stratified --spp 4 --filter mitchell --filter-radius 2
check random     soft-shadows.yaml    exr --sampler random --spp 3
check adaptive   lecture-whitted.yaml pfm --sampler adaptive --spp 16 --adaptive-min 2
check lens       depth-of-field.yaml  pfm --sampler sobol --spp 4
check mesh       mesh.yaml            pfm --max-depth 3
finish
