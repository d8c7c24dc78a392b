#!/usr/bin/env bash
# Kill the whole job mid-render (rank 0 killed: every rank ends), then --resume: only the missing tiles are
# rendered and the image has the bytes of an uninterrupted run; a journal of other settings is
# refused and nothing is written.
. "$(dirname "$0")/common.sh"

args=("$SRC/scenes/lecture-distributed.yaml" --width 160 --height 90 --sampler adaptive --spp 64 --adaptive-min 4
      --adaptive-threshold 0.002 --tile-size 8)
"$CLI" "${args[@]}" -q --threads 1 -o "$WORK/ref.pfm" || fail "strahl failed"

out="$WORK/out.pfm"
# Rank 0 raises SIGKILL after 150 journalled tiles (a test hook); Open MPI then ends every rank.
STRAHL_MPI_KILL_RANK=0 STRAHL_MPI_KILL_AFTER=150 mpirun_strahl 2 "${args[@]}" --threads 1 -q -o "$out" > "$WORK/first.txt" 2>&1
if [ -e "$out" ] || [ ! -f "$out.journal" ]; then
  fail "the killed render left an image or no journal"
  finish
fi
size=$(stat -c %s "$out.journal")

# Other settings: refused, exit 2, the journal kept as it was, no image.
mpirun_strahl 2 "${args[@]}" --seed 7 --threads 1 -q --resume -o "$out" > "$WORK/other.txt" 2>&1
code=$?
[ "$code" = 2 ] || fail "a journal of other settings: exit $code, not 2"
grep -q "belongs to a different scene or different settings" "$WORK/other.txt" || { cat "$WORK/other.txt"; fail "no clear message for a mismatched journal"; }
[ -e "$out" ] && fail "a mismatched journal: an image was written"
[ "$(stat -c %s "$out.journal")" = "$size" ] || fail "a mismatched journal was changed"

mpirun_strahl 2 "${args[@]}" --threads 1 --resume -o "$out" > "$WORK/resumed.txt" 2>&1 || { cat "$WORK/resumed.txt"; fail "--resume failed"; }
cmp -s "$WORK/ref.pfm" "$out" || fail "the resumed image differs from an uninterrupted run"
grep -q "^resumed     [1-9][0-9]* tiles" "$WORK/resumed.txt" || { cat "$WORK/resumed.txt"; fail "nothing was taken from the journal"; }
[ -e "$out.journal" ] && fail "the journal is left after the resumed render finished"
[ "$failures" = 0 ] && echo "ok: killed and resumed ($(grep '^resumed' "$WORK/resumed.txt"))"
finish
