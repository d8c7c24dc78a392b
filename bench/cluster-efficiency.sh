#!/usr/bin/env bash
# Cluster efficiency (docs/cluster.md, "Figures"): on this machine, strahl-mpi -np 2 with one
# render thread per rank against one process with one thread, on the bunny on a plane and on the
# unbalanced scene (bench/cluster/unbalanced.yaml); efficiency = T1 / (2 · T2) from the render
# times the summaries print. Then the unbalanced scene's tile log (its tiles' CPU times and
# message sizes) replayed by tools/schedule_sim.py for 1…64 ranks, static against dynamic, with
# the latency strahl-mpi measured.
#   bench/cluster-efficiency.sh [build dir] [stanford-bunny.obj]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
bunny=$(realpath -m "${2:-$here/../../shared/data/stanford-bunny.obj}")  # (the scene is written elsewhere)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# shellcheck source=bench/bunny-scene.sh
. "$here/bunny-scene.sh"
bunny_scene "$bunny" "{width: 1280, height: 720, spp: 4, sampler: stratified}" > "$work/bunny.yaml"

render_seconds() { sed -n 's/^time .*render \([0-9.]*\) s.*/\1/p' "$1"; }
median() { sort -g | awk '{v[NR]=$1} END {print v[int((NR+1)/2)]}'; }
ratio() { echo "$1 / ($2 * $3)" | bc -l | cut -c1-5; }
reps=${REPS:-3}
echo "load: $(cut -d' ' -f1-3 /proc/loadavg); medians of $reps interleaved runs"
# Each round runs, one after another: one process with one thread (T1); one process with two
# threads (the same two cores shared in one address space); two independent one-thread processes
# at once (no MPI at all: what any two-process scheme can reach on this machine); strahl-mpi -np 2
# with one render thread per rank.
for scene in "$work/bunny.yaml" "$here/cluster/unbalanced.yaml"; do
  args=("$scene" --width 1280 --height 720 --tile-size 16)
  : > "$work/t1"; : > "$work/t2"; : > "$work/pair"; : > "$work/mpi"
  for ((i = 0; i < reps; ++i)); do
    "$build/bin/strahl" "${args[@]}" -o "$work/one.png" --threads 1 > "$work/one.txt" 2> "$work/err.txt" || { cat "$work/err.txt"; exit 2; }
    render_seconds "$work/one.txt" >> "$work/t1"
    "$build/bin/strahl" "${args[@]}" -o "$work/threads.png" --threads 2 > "$work/out.txt" 2> /dev/null
    render_seconds "$work/out.txt" >> "$work/t2"
    "$build/bin/strahl" "${args[@]}" -o "$work/p1.png" --threads 1 > "$work/p1.txt" 2> /dev/null &
    "$build/bin/strahl" "${args[@]}" -o "$work/p2.png" --threads 1 > "$work/p2.txt" 2> /dev/null
    wait
    { render_seconds "$work/p1.txt"; render_seconds "$work/p2.txt"; } | sort -g | tail -1 >> "$work/pair"
    mpirun --oversubscribe --bind-to none -np 2 "$build/bin/strahl-mpi" "${args[@]}" -o "$work/two.png" --threads 1 > "$work/two.txt" 2>/dev/null
    render_seconds "$work/two.txt" >> "$work/mpi"
  done
  cmp -s "$work/one.png" "$work/two.png" || { echo "strahl-mpi's image differs from strahl's"; exit 1; }
  t1=$(median < "$work/t1") t2=$(median < "$work/t2") pair=$(median < "$work/pair") mpi=$(median < "$work/mpi")
  echo "$(basename "$scene"): 1 process × 1 thread $t1 s; 2 threads $t2 s (efficiency $(ratio "$t1" 2 "$t2"));" \
    "2 independent processes $pair s (as if efficiency $(echo "$t1 / $pair" | bc -l | cut -c1-5));" \
    "strahl-mpi 2 ranks × 1 thread $mpi s, efficiency $(ratio "$t1" 2 "$mpi")"
  grep -E "^cluster|^  rank" "$work/two.txt"
done
latency=$(sed -n 's/^cluster .*latency \([0-9.]*\) µs/\1/p' "$work/two.txt")
mpirun --oversubscribe --bind-to none -np 2 "$build/bin/strahl-mpi" "$here/cluster/unbalanced.yaml" --width 1280 --height 720 \
  --tile-size 8 --threads 1 -q -o "$work/out.png" --tile-log "$work/tiles.log"
python3 "$here/../tools/schedule_sim.py" "$work/tiles.log" --latency "${latency:-25}e-6"
