#!/usr/bin/env bash
# The real window under Xvfb (SDL's X11 driver, not the offscreen one): once the still image is
# complete, a screenshot of the X screen (ImageMagick's `import`) shows, where the window sits,
# the image the viewer saves (within the display's sRGB table: 1/255), which is strahl's. So the
# window shows the scene, not black. A second screenshot with the HUD and help overlay on is
# kept when STRAHL_VIEW_SHOTS names a folder (for a person to look at). Skips (77) without
# xvfb-run or import.
. "$(dirname "$0")/common.sh"
DIFF=$1
command -v xvfb-run > /dev/null && command -v import > /dev/null || { echo "skipped: no xvfb-run or import"; exit 77; }

cp "$SRC/scenes/lecture-whitted.yaml" "$WORK/scene.yaml"
cat > "$WORK/session.txt" << 'SCRIPT'
0 wait still
0 key ctrl+s
0 wait reload 1
0 key tab
0 key h
0.5 key ctrl+s
0 wait reload 2
0 quit
SCRIPT

# Inside Xvfb: the viewer (160×90, centred on a 640×480 screen: at 240, 195) and the screenshots.
cat > "$WORK/inside.sh" << 'INSIDE'
set -u
VIEW=$1 WORK=$2
"$VIEW" "$WORK/scene.yaml" --width 160 --height 90 --supersample 2 --no-hud -o "$WORK/view.png" \
  --script "$WORK/session.txt" > "$WORK/stdout.txt" 2> "$WORK/stderr.txt" &
viewer=$!
for i in $(seq 600); do [ -e "$WORK/view-0001.png" ] && break; sleep 0.1; done
sleep 0.5  # the window has drawn the image it saved
import -window root -crop 160x90+240+195 +repage "$WORK/window.png"
import -window root "$WORK/screen-image.png"
touch "$WORK/scene.yaml"  # a reload: the script goes on (HUD and help on)
for i in $(seq 600); do [ -e "$WORK/view-0002.png" ] && break; sleep 0.1; done
sleep 0.5
import -window root "$WORK/screen-hud-help.png"
touch -d '+2 seconds' "$WORK/scene.yaml"  # ends the session
wait $viewer
echo "viewer exit $?" > "$WORK/exit.txt"
INSIDE
timeout -k 5 180 xvfb-run -a -s "-screen 0 640x480x24" bash "$WORK/inside.sh" "$VIEW" "$WORK" ||
  fail "xvfb-run failed: $(cat "$WORK/stderr.txt" 2> /dev/null)"
grep -q "viewer exit 0" "$WORK/exit.txt" 2> /dev/null || fail "the viewer failed: $(cat "$WORK/stderr.txt" 2> /dev/null)"
if [ -e "$WORK/window.png" ] && [ -e "$WORK/view-0001.png" ]; then
  "$CLI" "$WORK/scene.yaml" --width 160 --height 90 --supersample 2 -q -o "$WORK/strahl.png" || fail "strahl failed"
  cmp -s "$WORK/view-0001.png" "$WORK/strahl.png" || fail "the saved image is not strahl's"
  report=$("$DIFF" "$WORK/window.png" "$WORK/strahl.png") || fail "strahl-diff failed"
  echo "window against strahl's image: $report"
  max=$(echo "$report" | sed -n 's/.*max \([0-9.e+-]*\).*/\1/p')
  awk -v m="${max:-1}" 'BEGIN { exit !(m <= 1.5 / 255) }' || fail "the window does not show the image (max difference $max)"
else
  fail "no screenshot or no saved image"
fi
if [ -n "${STRAHL_VIEW_SHOTS:-}" ]; then
  mkdir -p "$STRAHL_VIEW_SHOTS" && cp "$WORK"/screen-*.png "$WORK/window.png" "$STRAHL_VIEW_SHOTS/"
fi
[ "$failures" = 0 ] && echo "ok: the X11 window shows the scene"
finish
