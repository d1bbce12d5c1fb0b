#!/usr/bin/env python3
"""Old and new benchmark binaries in one run: case 1 exact (the median of 5 runs of 5
repeats each) and case 3 exact on 1 and 2 jobs, the two binaries interleaved round by
round so that the machine's drift hits both alike. Prints each case's medians and the
ratio new/old; exits 1 when a case is more than --tolerance slower (default 3%).

  scripts/bench_compare.py OLD/shapebench_benchmarks NEW/shapebench_benchmarks [--rounds 5]
(`make bench-compare REF=<commit>` builds REF's binary and runs this.)"""
import argparse
import json
import statistics
import subprocess
import sys

CASES = {
    "case 1 exact (us per run)": ("BM_Case1_Exact/repeats:5_median", "real_time", False),
    "case 3 exact, 1 job (points/s)": ("BM_Case3_Exact/1/min_time:1.000/repeats:5/real_time_median", "items_per_second", True),
    "case 3 exact, 2 jobs (points/s)": ("BM_Case3_Exact/2/min_time:1.000/repeats:5/real_time_median", "items_per_second", True),
}
FILTER = "BM_Case1_Exact/|BM_Case3_Exact/"


def run(binary):
    out = subprocess.run([binary, "--benchmark_filter=" + FILTER, "--benchmark_format=json"],
                         check=True, capture_output=True, text=True).stdout
    by_name = {b["name"]: b for b in json.loads(out)["benchmarks"]}
    return {case: by_name[name][field] for case, (name, field, _) in CASES.items()}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--tolerance", type=float, default=0.03)
    args = parser.parse_args()
    samples = {"old": [], "new": []}
    for r in range(args.rounds):
        order = ["old", "new"] if r % 2 == 0 else ["new", "old"]
        for which in order:
            samples[which].append(run(getattr(args, which)))
    worst = 0.0
    print(f"{'case':34s} {'old':>12s} {'new':>12s}  slower by")
    for case, (_, _, higher_is_better) in CASES.items():
        old = statistics.median(s[case] for s in samples["old"])
        new = statistics.median(s[case] for s in samples["new"])
        slower = old / new - 1.0 if higher_is_better else new / old - 1.0
        worst = max(worst, slower)
        verdict = "ok" if slower <= args.tolerance else "SLOWER"
        print(f"{case:34s} {old:12.1f} {new:12.1f}  {100 * slower:+6.1f}%  {verdict}")
    print(f"medians of {args.rounds} interleaved rounds; tolerance {100 * args.tolerance:.0f}%")
    return 0 if worst <= args.tolerance else 1


if __name__ == "__main__":
    sys.exit(main())
