#!/usr/bin/env bash
# A lost worker is not a lost image: rank 2 raises SIGKILL after its third tile; with
# --enable-recovery the others finish its tiles, the image has the same bytes, and the summary
# names the lost rank. And a rank whose scene differs is refused before any work.
. "$(dirname "$0")/common.sh"

args=("$SRC/scenes/lecture-whitted.yaml" --width 64 --height 36 --sampler sobol --spp 16 --tile-size 8)
"$CLI" "${args[@]}" -q --threads 1 -o "$WORK/ref.pfm" || fail "strahl failed"
STRAHL_MPI_KILL_RANK=2 STRAHL_MPI_KILL_AFTER=3 \
  timeout -k 5 90 mpirun --enable-recovery -np 3 "$MPI_BIN" "${args[@]}" --threads 1 --mpi-timeout 3 \
  -o "$WORK/lost.pfm" > "$WORK/lost.txt" 2>&1
code=$?
[ "$code" = 0 ] || { cat "$WORK/lost.txt"; fail "a lost worker: exit $code, not 0"; }
cmp -s "$WORK/ref.pfm" "$WORK/lost.pfm" || fail "a lost worker: the image differs"
grep -q "rank 2 .*LOST" "$WORK/lost.txt" || { cat "$WORK/lost.txt"; fail "the summary does not name the lost rank 2"; }
grep -q "lost rank 2" "$WORK/lost.txt" || fail "no warning about the lost rank 2"
echo "ok: lost worker"

# Two ranks given different scenes (MPMD): refused, exit 2, nothing written.
timeout -k 5 60 mpirun -np 1 "$MPI_BIN" "$SRC/scenes/lecture-whitted.yaml" --width 32 --height 18 -o "$WORK/mixed.png" : \
  -np 1 "$MPI_BIN" "$SRC/scenes/lecture.yaml" --width 32 --height 18 -o "$WORK/mixed.png" > "$WORK/mixed.txt" 2>&1
code=$?
[ "$code" = 2 ] || fail "different scenes: exit $code, not 2"
grep -q "strahl-mpi: error: rank 1 compiled a different scene" "$WORK/mixed.txt" || { cat "$WORK/mixed.txt"; fail "different scenes: no clear message"; }
[ -e "$WORK/mixed.png" ] && fail "different scenes: an image was written"
[ -e "$WORK/mixed.png.journal" ] && fail "different scenes: a journal was left"
echo "ok: different scenes refused"

# A worker that cannot load its scene: its error, exit 2.
timeout -k 5 60 mpirun -np 1 "$MPI_BIN" "$SRC/scenes/lecture.yaml" --width 32 --height 18 -o "$WORK/missing.png" : \
  -np 1 "$MPI_BIN" "$WORK/no-such-scene.yaml" --width 32 --height 18 -o "$WORK/missing.png" > "$WORK/missing.txt" 2>&1
code=$?
[ "$code" = 2 ] || fail "a worker without its scene: exit $code, not 2"
grep -q "strahl-mpi: error: rank 1: .*no-such-scene.yaml" "$WORK/missing.txt" || { cat "$WORK/missing.txt"; fail "a worker without its scene: no clear message"; }
echo "ok: a worker's load error reported"
finish
