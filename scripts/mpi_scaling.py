#!/usr/bin/python3
"""1 vs 2 MPI ranks on one sweep (docs/scaling.md; `make bench`): prints the figures.

  scripts/mpi_scaling.py BUILD/shapebench SWEEP.yaml OUT_DIR [ROUNDS]

Runs `mpirun -n 1` and `mpirun -n 2` (each rank --jobs 1), interleaved, ROUNDS times
(default 3), each into a fresh OUT_DIR/nK; prints the median wall time of each, the
ratio, and rank 0's SHAPEBENCH_MPI_STATS line of the last 2-rank run (points/s, rank-0
rows/s, bytes received) with results.csv's bytes per row. It reports; it does not gate
(the machine may be shared). Skipped, saying so, when mpirun is missing.
"""
import os
import re
import shutil
import statistics
import subprocess
import sys
import time


def run(binary, sweep, out, ranks):
    shutil.rmtree(out, ignore_errors=True)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               SHAPEBENCH_MPI_STATS="1")
    start = time.monotonic()
    cpu_before = os.times()
    done = subprocess.run(["mpirun", "-n", str(ranks), "--oversubscribe", binary, "sweep", sweep,
                           "--jobs", "1", "--out", out],
                          env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    seconds = time.monotonic() - start
    cpu_after = os.times()
    cpu = (cpu_after.children_user - cpu_before.children_user) + (
        cpu_after.children_system - cpu_before.children_system)
    if done.returncode != 0:
        sys.exit(f"mpirun -n {ranks} failed ({done.returncode}):\n{done.stderr}")
    stats = [line for line in done.stderr.splitlines() if line.startswith("mpi: ")]
    return seconds, cpu, stats[-1] if stats else ""


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    binary, sweep, out = sys.argv[1:4]
    rounds = int(sys.argv[4]) if len(sys.argv) > 4 else 3
    if shutil.which("mpirun") is None:
        print("mpi scaling: skipped (no mpirun; install openmpi-bin)")
        return
    times = {1: [], 2: []}
    cpus = {1: [], 2: []}
    stats = {}
    for _ in range(rounds):
        for ranks in (1, 2):
            seconds, cpu, stats[ranks] = run(binary, sweep, os.path.join(out, f"n{ranks}"), ranks)
            times[ranks].append(seconds)
            cpus[ranks].append(cpu)
    results = os.path.join(out, "n2", "results.csv")
    with open(results, "rb") as f:
        rows = f.read().count(b"\n") - 1
    one, two = statistics.median(times[1]), statistics.median(times[2])
    print(f"mpi scaling: {rows} points, --jobs 1 per rank, median of {rounds} runs (wall, mpirun included)")
    print(f"  1 rank  {one:7.2f} s  {rows / one:8.0f} points/s   runs: " + " ".join(f"{t:.2f}" for t in times[1]))
    print(f"  2 ranks {two:7.2f} s  {rows / two:8.0f} points/s   runs: " + " ".join(f"{t:.2f}" for t in times[2]))
    print(f"  speed-up 1 -> 2 ranks: {one / two:.2f}x (wall, mpirun's start included)")
    session = {r: float(re.search(r" in ([0-9.e+-]+) s ", stats[r]).group(1)) for r in (1, 2)}
    print(f"  speed-up of the distribution alone (rank 0's own clock, last runs): "
          f"{session[1] / session[2]:.2f}x")
    # CPU seconds of mpirun and the ranks: what the points cost when the machine is shared
    # (then the wall times above measure the share the scheduler gave, not the code).
    print(f"  CPU (user+sys, all processes): 1 rank {statistics.median(cpus[1]):.2f} s, "
          f"2 ranks {statistics.median(cpus[2]):.2f} s; "
          f"{rows / statistics.median(cpus[1]):.0f} points per CPU-second on 1 rank")
    print(f"  load average at the end: {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores")
    print(f"  results.csv: {os.path.getsize(results) / rows:.1f} bytes per row")
    print(f"  1 rank : {stats[1]}")
    print(f"  2 ranks: {stats[2]}")


if __name__ == "__main__":
    main()
