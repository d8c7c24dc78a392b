# Shared by the viewer tests: the programs, a scratch folder, failures counted, a timeout on
# every run, and scenes with the viewer's printed camera in place of their own.
set -u
VIEW=$1 CLI=$2 SRC=$3
shift 3
. "$(dirname "${BASH_SOURCE[0]}")/../checks.sh"

# view_offscreen ARGS...: strahl-view on SDL's offscreen video driver (no display needed), at most 120 s.
view_offscreen() {
  SDL_VIDEODRIVER=offscreen timeout -k 5 120 "$VIEW" "$@"
}

# with_camera SCENE CAMERA_YAML OUT: SCENE with its top-level camera block replaced by CAMERA_YAML's.
with_camera() {
  awk '/^camera:/ { skip = 1; next } skip && /^[^ \t#]/ { skip = 0 } !skip { print }' "$1" > "$3"
  cat "$2" >> "$3"
}

# wait_for FILE SECONDS: until FILE exists; false after SECONDS.
wait_for() {
  local i
  for ((i = 0; i < $2 * 10; i++)); do
    [ -e "$1" ] && return 0
    sleep 0.1
  done
  return 1
}
