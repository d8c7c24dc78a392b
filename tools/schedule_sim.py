#!/usr/bin/env python3
"""Replays a strahl-mpi tile log (--tile-log) in a scheduler simulation for 1…64 ranks.

Each log line is one tile: pass index rank cpu_seconds request_bytes result_bytes samples. The
tiles' CPU times, measured on whatever ranks rendered them, are replayed on N simulated ranks of
one render thread each, with a one-way message latency (strahl-mpi's summary measures it:
"latency … µs") and a bandwidth:

  static-bands       rank r renders the r-th contiguous block of each pass's tiles (classic
                     static tiling: image regions fixed in advance)
  static-interleaved tile i goes to rank i mod N
  dynamic            strahl-mpi's scheme: rank 0 renders tiles itself and hands the others out,
                     `prefetch` in flight per worker; a result's arrival triggers the next send;
                     rank 0's MPI thread spends `overhead` seconds on every message it sends or
                     receives, one message at a time (it is the one serial part)

Passes end with a barrier (the render job plans the next pass once the last tile is back).
Efficiency = Σ tile CPU time / (N × makespan). Python 3 standard library only.

  tools/schedule_sim.py unbalanced.log --latency 25e-6
"""
import argparse
import heapq
import sys
from collections import defaultdict


def read_log(path):
    passes = defaultdict(list)
    with open(path) as f:
        for n, line in enumerate(f, 1):
            fields = line.split()
            if len(fields) != 7:
                sys.exit(f"{path}:{n}: expected 7 fields, found {len(fields)}")
            p, index, _rank, cpu, req, res, _samples = fields
            passes[int(p)].append((int(index), float(cpu), int(req), int(res)))
    return [sorted(passes[p]) for p in sorted(passes)]


def static(passes, n, interleaved):
    t = 0.0
    for tiles in passes:
        load = [0.0] * n
        count = len(tiles)
        for k, (_i, cpu, _q, _r) in enumerate(tiles):
            rank = k % n if interleaved else min(n - 1, k * n // count)
            load[rank] += cpu
        t += max(load)  # messages: one per rank and pass, negligible next to the tiles
    return t


def dynamic(passes, n, latency, bandwidth, prefetch, overhead):
    t = 0.0
    for tiles in passes:
        queue = list(tiles)
        queue.reverse()  # pop() hands them out in index order
        events = []  # (arrival time of a result at rank 0, rank)
        worker_free = [t] * n
        master_free = t  # rank 0's MPI thread handles one message at a time
        outstanding = 0

        def send(rank, now):
            nonlocal outstanding, master_free
            if not queue:
                return
            _i, cpu, req, res = queue.pop()
            master_free = max(master_free, now) + overhead  # encoding and sending the request
            arrive = master_free + latency + req / bandwidth
            start = max(arrive, worker_free[rank])
            worker_free[rank] = start + cpu
            heapq.heappush(events, (start + cpu + latency + res / bandwidth, rank))
            outstanding += 1

        def local(now):
            # Rank 0's own thread: the next tile as soon as it is free, no messages.
            nonlocal outstanding
            if not queue:
                return
            _i, cpu, _q, _r = queue.pop()
            worker_free[0] = max(now, worker_free[0]) + cpu
            heapq.heappush(events, (worker_free[0], 0))
            outstanding += 1

        for rank in range(1, n):
            for _ in range(prefetch):
                send(rank, t)
        local(t)
        end = t
        while events:
            now, rank = heapq.heappop(events)
            outstanding -= 1
            if rank != 0:
                master_free = max(master_free, now) + overhead  # receiving, decoding, delivering the result
                now = master_free
            end = max(end, now)
            if rank == 0:
                local(now)
            else:
                send(rank, now)
        t = end
    return t


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("log")
    ap.add_argument("--latency", type=float, default=25e-6, help="one-way seconds per message (default 25e-6)")
    ap.add_argument("--bandwidth", type=float, default=1.25e9, help="bytes per second (default 1.25e9: 10 Gbit/s)")
    ap.add_argument("--prefetch", type=int, default=3, help="tiles in flight per worker (default 3)")
    ap.add_argument("--overhead", type=float, default=10e-6,
                    help="rank 0's seconds of work per message, sent or received (default 10e-6)")
    ap.add_argument("--ranks", default="1,2,4,8,16,32,64")
    a = ap.parse_args()
    passes = read_log(a.log)
    work = sum(cpu for tiles in passes for (_i, cpu, _q, _r) in tiles)
    tiles = sum(len(p) for p in passes)
    print(f"{a.log}: {tiles} tiles in {len(passes)} passes, {work:.3f} CPU seconds; latency {a.latency * 1e6:.1f} µs, "
          f"{a.bandwidth / 1e9:.2f} GB/s, prefetch {a.prefetch}, rank 0 {a.overhead * 1e6:.1f} µs per message")
    print(f"{'ranks':>6} {'static-bands':>13} {'static-interleaved':>19} {'dynamic':>8}")
    for n in (int(x) for x in a.ranks.split(",")):
        eff = lambda makespan: work / (n * makespan) if makespan > 0 else 0
        print(f"{n:>6} {eff(static(passes, n, False)):>13.3f} {eff(static(passes, n, True)):>19.3f} "
              f"{eff(dynamic(passes, n, a.latency, a.bandwidth, a.prefetch, a.overhead)):>8.3f}")


if __name__ == "__main__":
    main()
