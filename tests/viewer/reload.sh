#!/usr/bin/env bash
# Live reload: while a scripted viewer runs, the test rewrites the scene file (a colour change,
# then a syntax error, then the original again) and the mesh file it uses. Each save (Ctrl+S)
# shows: the colour change changes the picture; the broken edit is reported on stderr with its
# file:line:column and the viewer keeps the last good scene and keeps running; the fix brings
# back the first picture bit for bit (= strahl's); a changed mesh changes the picture.
. "$(dirname "$0")/common.sh"

scene=$WORK/scene.yaml
cp "$SRC/scenes/meshes/icosahedron.obj" "$WORK/shape.obj"
# replace FILE TEXT-FILE: a whole new version at once (an editor's save: write, then rename).
replace() {
  cp "$2" "$1.new"
  mv "$1.new" "$1"
}
sed -e 's/width: 1920/width: 64/' -e 's/height: 1080/height: 36/' "$SRC/scenes/lecture.yaml" > "$WORK/good.yaml"
echo "  - {type: mesh, file: shape.obj, scale: 0.2, translate: [0.6, 0.3, -0.3], material: green}" >> "$WORK/good.yaml"
sed 's/red:    {color: \[0.8, 0.2, 0.2\]/red:    {color: [0.2, 0.3, 0.9]/' "$WORK/good.yaml" > "$WORK/blue.yaml"
cmp -s "$WORK/good.yaml" "$WORK/blue.yaml" && fail "the test's colour change changed nothing"
sed 's/^  - {type: sphere, center: \[0.4, 0.1, 0.1\], /  - {type: sphere, center: [0.4, 0.1, 0.1, /' "$WORK/good.yaml" > "$WORK/broken.yaml"
cp "$WORK/good.yaml" "$scene"

cat > "$WORK/session.txt" << 'SCRIPT'
0 wait still
0 key ctrl+s
0 wait reload 1
0 wait still
0 key ctrl+s
0 wait reload 2
0 wait still
0 key ctrl+s
0 wait reload 3
0 wait still
0 key ctrl+s
0 wait reload 4
0 wait still
0 key ctrl+s
0 quit
SCRIPT
view_offscreen "$scene" -o "$WORK/view.pfm" --script "$WORK/session.txt" > "$WORK/stdout.txt" 2> "$WORK/stderr.txt" &
viewer=$!
saved() { echo "$WORK/view-000$1.pfm"; }
step() {  # step N: wait for save N, then report whether the viewer still runs
  wait_for "$(saved "$1")" 60 || { fail "save $1 never came: $(cat "$WORK/stderr.txt")"; return 1; }
  kill -0 "$viewer" 2> /dev/null || { fail "the viewer is gone after save $1"; return 1; }
}
if step 1; then
  replace "$scene" "$WORK/blue.yaml"
  if step 2; then
    replace "$scene" "$WORK/broken.yaml"
    if step 3; then
      replace "$scene" "$WORK/good.yaml"
      if step 4; then
        # The mesh file changes (the icosahedron's vertices scaled by 1.5).
        awk '/^v / { printf "v %g %g %g\n", $2 * 1.5, $3 * 1.5, $4 * 1.5; next } { print }' \
          "$SRC/scenes/meshes/icosahedron.obj" > "$WORK/bigger.obj"
        replace "$WORK/shape.obj" "$WORK/bigger.obj"
      fi
    fi
  fi
fi
wait "$viewer"
rc=$?
[ "$rc" = 0 ] || fail "strahl-view exited with $rc: $(cat "$WORK/stderr.txt")"

cp "$SRC/scenes/meshes/icosahedron.obj" "$WORK/shape.obj"
"$CLI" "$WORK/good.yaml" -q -o "$WORK/strahl.pfm" || fail "strahl failed"
cmp -s "$(saved 1)" "$WORK/strahl.pfm" || fail "the first picture is not strahl's"
cmp -s "$(saved 1)" "$(saved 2)" && fail "the colour change did not change the picture"
cmp -s "$(saved 2)" "$(saved 3)" || fail "after the broken edit the picture is not the last good one"
cmp -s "$(saved 4)" "$(saved 1)" || fail "after the fix the picture is not the first one again"
cmp -s "$(saved 5)" "$(saved 4)" && fail "the changed mesh did not change the picture"
grep -q "strahl-view: error: .*scene.yaml:[0-9]*:[0-9]*:" "$WORK/stderr.txt" ||
  fail "the broken edit's error (file:line:column) is not on stderr: $(cat "$WORK/stderr.txt")"
[ "$(grep -c 'strahl-view: error:' "$WORK/stderr.txt")" = 1 ] || fail "not exactly one error reported"
[ "$(grep -c '^reloaded' "$WORK/stdout.txt")" = 3 ] || fail "not three good reloads: $(cat "$WORK/stdout.txt")"
[ "$failures" = 0 ] && echo "ok: reload (colour, syntax error, fix, mesh)"
finish
