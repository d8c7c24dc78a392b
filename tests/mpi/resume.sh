#!/usr/bin/env bash
# Kill the whole job mid-render (SIGKILL to every rank), then --resume: only the missing tiles are
# rendered and the image has the bytes of an uninterrupted run; a journal of other settings is
# refused and nothing is written.
. "$(dirname "$0")/common.sh"

args=("$SRC/scenes/lecture-distributed.yaml" --width 160 --height 90 --sampler adaptive --spp 64 --adaptive-min 4
      --adaptive-threshold 0.002 --tile-size 8)
"$CLI" "${args[@]}" -q --threads 1 -o "$WORK/ref.pfm" || fail "strahl failed"

out="$WORK/out.pfm"
setsid timeout -k 5 60 mpirun -np 2 "$MPI_BIN" "${args[@]}" --threads 1 -q -o "$out" > "$WORK/first.txt" 2>&1 &
pid=$!
# Wait for a good part of the journal (tiles recorded), then kill every rank at once.
for _ in $(seq 1 400); do
  [ -f "$out.journal" ] && [ "$(stat -c %s "$out.journal")" -gt 100000 ] && break
  sleep 0.05
done
pkill -KILL -s "$pid"  # every process of the job: mpirun and its ranks (setsid: a session of their own)
wait $pid 2>/dev/null
if [ -e "$out" ] || [ ! -f "$out.journal" ]; then
  fail "the render finished before it could be killed (make it slower)"
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
