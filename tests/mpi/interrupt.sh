#!/usr/bin/env bash
# Stopping a cluster render (docs/cluster.md, "Stopping"): --time-limit ends every rank and writes
# the image so far (exit 0, as strahl); SIGINT on mpirun (Ctrl-C) ends every rank promptly, writes
# the image so far, keeps the journal, and --resume then finishes with the bytes of an
# uninterrupted run.
. "$(dirname "$0")/common.sh"

# Enough work for the render to outlast the 1 s time limit on 2 ranks of one thread, and the
# SIGINT below to reach it mid-render (~4 s of rendering on the 2-core AVX-512 VM of 2026-12-06;
# 1024 samples per pixel had become ~1 s, and a SIGINT arriving as the last tiles finished failed
# the project CI once).
args=("$SRC/scenes/lecture-distributed.yaml" --width 160 --height 90 --sampler stratified --spp 4096 --tile-size 8)

# Time limit: the run ends near the limit, on every rank, with an image.
start=$(date +%s%N)
mpirun_strahl 2 "${args[@]}" --threads 1 --time-limit 1 -o "$WORK/limited.png" > "$WORK/limited.txt" 2>&1
code=$?
elapsed_ms=$((($(date +%s%N) - start) / 1000000))
[ "$code" = 0 ] || { cat "$WORK/limited.txt"; fail "--time-limit: exit $code, not 0"; }
[ -s "$WORK/limited.png" ] || fail "--time-limit: no image written"
grep -q "stopped by the time limit" "$WORK/limited.txt" || { cat "$WORK/limited.txt"; fail "--time-limit: the summary does not say the render was cut"; }
# Start-up of two ranks takes well under a second here; 15 s means a rank did not stop.
[ "$elapsed_ms" -lt 15000 ] || fail "--time-limit 1 took ${elapsed_ms} ms"

# Ctrl-C: wait until tiles are journalled, then SIGINT to mpirun (what a terminal sends).
out="$WORK/out.pfm"
"$CLI" "${args[@]}" -q --threads 1 -o "$WORK/ref.pfm" || fail "strahl failed"
timeout -k 5 60 mpirun -np 2 "$MPI_BIN" "${args[@]}" --threads 1 -o "$out" > "$WORK/first.txt" 2>&1 &
job=$!
for _ in $(seq 1 600); do
  [ -s "$out.journal" ] && break
  sleep 0.05
done
[ -s "$out.journal" ] || fail "no tile was journalled within 30 s"
# This job's ranks: the children of its mpirun (the child of timeout, $job).
ranks=$(pgrep -d ' ' -x strahl-mpi -P "$(pgrep -d , -x mpirun -P "$job")")
[ -n "$ranks" ] || fail "no rank of the job found"
sent=$(date +%s%N)
pkill -INT -x mpirun
wait "$job"
code=$?
stop_ms=$((($(date +%s%N) - sent) / 1000000))
[ "$code" != 0 ] || fail "an interrupted run exited 0"
grep -q "interrupted; wrote the image rendered so far" "$WORK/first.txt" || { cat "$WORK/first.txt"; fail "no message for the interrupt"; }
[ -s "$out" ] || fail "the interrupted run wrote no image"
[ -s "$out.journal" ] || fail "the interrupted run removed its journal"
[ "$stop_ms" -lt 10000 ] || fail "the ranks took ${stop_ms} ms to stop after SIGINT"
# Open MPI 4.1's mpirun sends SIGTERM a second after the SIGINT and SIGKILL a second later; it may
# exit while a killed rank is still being torn down (seen on a loaded CI machine), so a rank has a
# few seconds to be gone. One still running then was left behind. (Ranks nobody has reaped yet
# show as zombies: dead, not running.)
alive() { for p in $ranks; do ps -o stat= -p "$p" | grep -qv '^Z' && return 0; done; return 1; }
for _ in $(seq 1 50); do alive || break; sleep 0.1; done
alive && { ps -o pid=,stat=,etimes=,comm= -p "${ranks// /,}"; fail "a rank outlived the interrupted job"; }

mpirun_strahl 2 "${args[@]}" --threads 1 --resume -o "$out" > "$WORK/resumed.txt" 2>&1 || { cat "$WORK/resumed.txt"; fail "--resume failed"; }
cmp -s "$WORK/ref.pfm" "$out" || fail "the resumed image differs from an uninterrupted run"
grep -q "^resumed     [1-9][0-9]* tiles" "$WORK/resumed.txt" || { cat "$WORK/resumed.txt"; fail "nothing was taken from the journal"; }
[ "$failures" = 0 ] && echo "ok: time limit after ${elapsed_ms} ms; SIGINT stopped every rank in ${stop_ms} ms; resumed to the same bytes"
finish
