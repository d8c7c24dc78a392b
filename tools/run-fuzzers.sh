#!/bin/sh
# Runs each libFuzzer target (YAML scenes, POV-Ray scenes, OBJ, PLY, glTF, implicit-surface expressions) for a bounded time over its seed corpus.
#   tools/run-fuzzers.sh [BUILD_DIR] [SECONDS]     defaults: build-fuzz 20
# Build the targets first: cmake --preset fuzz && cmake --build --preset fuzz
# As many targets run at once as the machine has cores (each fuzzes on one core for SECONDS), so
# the six take 3 × SECONDS on two cores; each one's summary is printed when its batch ends.
# New interesting inputs go to BUILD_DIR/fuzz-corpus/KIND (the seeds in tests/fuzz/corpus/KIND
# are only read); a crashing input is written to BUILD_DIR/fuzz-artifacts/ and the script fails.
# Keep such an input as a regression test: copy it to tests/fuzz/regressions/KIND/.
set -eu
cd "$(dirname "$0")/.."
build=${1:-build-fuzz}
seconds=${2:-20}
jobs=$(nproc 2>/dev/null || echo 1)
mkdir -p "$build/fuzz-artifacts" "$build/fuzz-logs"

# One target, its libFuzzer output filtered to the summary lines, into fuzz-logs/KIND.log.
fuzz_one() {
  kind=$1
  mkdir -p "$build/fuzz-corpus/$kind"
  dict=""
  if [ -f "tests/fuzz/$kind.dict" ]; then dict="-dict=tests/fuzz/$kind.dict"; fi
  {
    echo "fuzz: $kind for $seconds s"
    # shellcheck disable=SC2086  # $dict is empty or one word
    "$build/fuzz/strahl_fuzz_$kind" $dict -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
      -artifact_prefix="$build/fuzz-artifacts/$kind-" "$build/fuzz-corpus/$kind" "tests/fuzz/corpus/$kind" \
      "tests/fuzz/regressions/$kind" 2>&1 | grep -E '^(#[0-9]+ +DONE|stat::number_of_executed_units|stat::peak_rss|==[0-9]+==|SUMMARY|artifact_prefix|Test unit written)' || true
  } > "$build/fuzz-logs/$kind.log"
}

# Waits for the running batch and prints its targets' summaries.
finish_batch() {
  wait
  for k in $batch; do cat "$build/fuzz-logs/$k.log"; done
  batch=""
  running=0
}

kinds="scene pov obj ply gltf expression"
# Every target must be there (the build preset `fuzz` names them all): a missing one would
# otherwise print nothing and pass.
for kind in $kinds; do
  if [ ! -x "$build/fuzz/strahl_fuzz_$kind" ]; then
    echo "fuzz: $build/fuzz/strahl_fuzz_$kind is not built (cmake --build --preset fuzz)" >&2
    exit 1
  fi
done
batch=""
running=0
for kind in $kinds; do
  fuzz_one "$kind" &
  batch="$batch $kind"
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then finish_batch; fi
done
finish_batch

for kind in $kinds; do
  if ls "$build/fuzz-artifacts/$kind-"* >/dev/null 2>&1; then
    echo "fuzz: $kind found a crash: $(ls "$build/fuzz-artifacts/$kind-"*)" >&2
    exit 1
  fi
  # (A run that ended without its final statistics did not fuzz for its time.)
  if ! grep -q '^stat::number_of_executed_units' "$build/fuzz-logs/$kind.log"; then
    echo "fuzz: $kind did not run to its end (no final statistics in $build/fuzz-logs/$kind.log)" >&2
    exit 1
  fi
done
