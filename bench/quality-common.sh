# What bench/time-to-quality.sh, bench/soft-shadows-pov.sh and bench/depth-of-field-pov.sh share, sourced by them: their
# arguments [build-dir] [width] [height] [goal] (the default size in default_width and
# default_height), the checks for ../shared/bench/lecture.pov and POV-Ray, a work directory
# removed at the end, and the helpers that time runs and keep the fastest setting within the goal.
# shellcheck shell=bash
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
# (width, height, threads: read by the scripts that source this)
# shellcheck disable=SC2034
width=${2:-$default_width}
# shellcheck disable=SC2034
height=${3:-$default_height}
goal=${4:-2e-3}
pov_scene=$root/../shared/bench/lecture.pov
[ -f "$pov_scene" ] || { echo "missing $pov_scene" >&2; exit 2; }
command -v povray >/dev/null || { echo "povray is not installed (apt-get install povray)" >&2; exit 2; }
# shellcheck disable=SC2034
threads=$(nproc)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

wall1() { local s e; s=$(date +%s.%N); "$@"; e=$(date +%s.%N); echo "$e - $s" | bc; }
wall() { { wall1 "$@"; wall1 "$@"; wall1 "$@"; } | sort -g | sed -n 2p; }  # the median of three
rmse() { "$build/bin/strahl-diff" "$1" "$2" | awk '{print $2}'; }
below() { awk -v a="$1" -v b="$goal" 'BEGIN { exit !(a <= b) }'; }
# keep_best VAR TIME RMSE WHAT: VAR becomes "TIME s (WHAT, rmse RMSE)" where RMSE is within the
# goal and TIME beats VAR's time (or VAR is empty).
keep_best() {
  local -n best=$1
  below "$3" || return 0
  if [ -z "$best" ] || awk -v a="$2" -v b="${best%% *}" 'BEGIN { exit !(a < b) }'; then
    best="$(printf %.3f "$2") s ($4, rmse $3)"
  fi
}
# speed_up LABEL STRAHL POV-RAY: the ratio of the two best times, where both were found.
speed_up() {
  if [ -n "$2" ] && [ -n "$3" ]; then
    printf "%s: speed-up %.1fx\n" "$1" "$(echo "${3%% *} / ${2%% *}" | bc -l)"
  fi
}
