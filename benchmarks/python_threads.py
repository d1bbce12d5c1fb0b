#!/usr/bin/python3
"""`make bench`: the Python module releases the GIL while it simulates.

Four runs of one scenario, done by one Python thread one after the other, then by four
Python threads at once; rounds alternate the two, and the medians of the wall times are
compared. With the GIL held the four threads would take as long as one (the interpreter
runs one at a time); released, they take 1 / min(4, cores) of it on free cores: about half
on the repository's 2-core machine. The scenario: configs/scenarios/pocket_corner.yaml
with the servo drive under CVODE (benchmarks' case 2, CVODE): a few hundred ms a run.
Also checks that every run gave the same metrics bit for bit.

    PYTHONPATH=build/python /usr/bin/python3 benchmarks/python_threads.py [--rounds 5]
"""

from __future__ import annotations

import argparse
import os
import statistics
import struct
import threading
import time

import shapebench

SCENARIO = "configs/scenarios/pocket_corner.yaml"
SETS = {"drive.type": "servo", "integrator.method": "cvode"}
RUNS = 4


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=5)
    args = parser.parse_args()
    os.chdir(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    scenario = shapebench.load(SCENARIO, set=SETS)
    reference = scenario.run().metrics  # also warms the caches
    results: list[dict[str, float]] = []

    def run() -> None:
        results.append(scenario.run().metrics)  # list.append is atomic under the GIL

    # Each returns (wall s, process CPU s): CPU above wall means threads ran at once.
    def one_thread() -> tuple[float, float]:
        start, cpu = time.perf_counter(), time.process_time()
        for _ in range(RUNS):
            run()
        return time.perf_counter() - start, time.process_time() - cpu

    def four_threads() -> tuple[float, float]:
        threads = [threading.Thread(target=run) for _ in range(RUNS)]
        start, cpu = time.perf_counter(), time.process_time()
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        return time.perf_counter() - start, time.process_time() - cpu

    load_before = os.getloadavg()[0]
    serial, parallel = [], []
    for _ in range(args.rounds):
        serial.append(one_thread())
        parallel.append(four_threads())
    def bits(metrics):  # every metric's double, whatever the table's length
        return struct.pack(f"<{len(metrics)}d", *metrics.values())

    same = all(bits(m) == bits(reference) for m in results)
    s, p = statistics.median(w for w, _ in serial), statistics.median(w for w, _ in parallel)
    s_cpu, p_cpu = statistics.median(c for _, c in serial), statistics.median(c for _, c in parallel)
    print(f"python threads: {SCENARIO} with {SETS}, {RUNS} runs, median of {args.rounds} rounds "
          f"({os.cpu_count()} cores, load average {load_before:.2f} before)")
    print(f"  1 thread, {RUNS} runs one after the other  {s:8.3f} s wall, {s_cpu:7.3f} s CPU  "
          f"({s / RUNS * 1e3:.1f} ms a run)")
    print(f"  {RUNS} threads, 1 run each, at once       {p:8.3f} s wall, {p_cpu:7.3f} s CPU  "
          f"({p / s:.2f} of 1 thread's time, {s / p:.2f}x; CPU / wall {p_cpu / p:.2f})")
    print(f"  every run's metrics the same bit for bit: {'yes' if same else 'NO'}")
    return 0 if same else 1


if __name__ == "__main__":
    raise SystemExit(main())
