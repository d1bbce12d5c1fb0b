#!/usr/bin/python3
"""The one table of `make bench`: every figure of one run of the benchmarks, the
baselines and the memory measurement, as time per run, runs per second and the ratio to
shapebench's exact path on the same case (and, for the sweep, the same number of jobs).

usage: baseline_table.py BENCHMARKS.json BASELINE.json MEMORY.txt [--markdown]

BENCHMARKS.json: shapebench_benchmarks --benchmark_out (JSON). BASELINE.json: what
scripts/baseline.py printed (may hold {"error": ...}). MEMORY.txt: `/usr/bin/time -v` of
the 1,000,000-point sweep (may be missing). Only the standard library: it runs with any
python3. --markdown prints the table for the README.
"""
import json
import re
import sys

TARGETS = {
    "case1_exact_us": 50.0,          # at most, per run
    "case1_cvode_us": 1000.0,        # at most, per run (rtol 1e-8)
    "case1_cvode_peak": 1e-6,        # |peak_ratio - exact's|
    "case3_exact_runs_s": 20000.0,   # at least, two jobs
    "case3_cvode_runs_s": 1500.0,    # at least, two jobs
    "scipy_over_cvode": 50.0,        # at least
    "numpy_over_exact": 20.0,        # at least
    "baseline_peak": 1e-6,           # |peak_ratio - shapebench's|
    "memory_mb": 200.0,              # at most, 1,000,000-point sweep
    "case4_real_time": 50.0,         # at least: simulated seconds per CPU second
    "scipy_over_case4": 20.0,        # at least
    "case4_agreement": 1e-3,         # at most: of the deflection scale
    "case3_over_floor": 3.0,         # at most: case 3 exact per point, one job, over the floor
    "case4d_over_floor": 4.0,        # at most: case 4d exact per point, one job, over the floor
    "sweep_scaling": 1.8,            # at least: 1 -> 2 jobs (case 3 and case 4d)
    "case4d_cvode_runs_s": 1500.0,   # at least, two jobs
}


def load_benchmarks(path):
    with open(path) as f:
        data = json.load(f)
    by_name = {}
    for b in data.get("benchmarks", []):
        if b.get("run_type") == "aggregate" and b.get("aggregate_name") != "median":
            continue
        name = b.get("run_name", b["name"])
        by_name[name] = b
    return data.get("context", {}), by_name


def seconds(b, real=False):
    unit = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}[b.get("time_unit", "ns")]
    return (b["real_time"] if real else b["cpu_time"]) * unit


def find(by_name, prefix):
    for name, b in by_name.items():
        if name == prefix or name.startswith(prefix + "/"):
            return b
    return None


def fmt_time(s):
    if s is None:
        return "n/a"
    if s >= 1.0:
        return "%.2f s" % s
    if s >= 1e-3:
        return "%.2f ms" % (s * 1e3)
    return "%.1f us" % (s * 1e6)


def fmt_num(x, digits=3):
    if x is None:
        return ""
    if x == 0:
        return "0"
    if abs(x) >= 100:
        return "{:,.0f}".format(x)
    return ("%." + str(digits) + "g") % x


def case4d(bench, sweep, cpu, add, checks, floor_s):
    """Case 4d (benchmarks/cases/case4_damped_sweep.yaml; "4d", as case4_lugre_circle.yaml
    is case 4): case 3 on a 2% damped mode, every metric, so every point runs its settling
    tail. Medians of five; the ratios to the floor and 1 -> 2 jobs are the must-show ones."""
    per = {}
    for method, label in (("Exact", "exact"), ("ExactNoSync", "exact --no-sync"), ("Cvode", "CVODE"),
                          ("CvodeNoCheck", "CVODE, cross-check off")):
        for jobs in (1, 2):
            b = find(bench, "BM_Case4Damped_%s/%d" % (method, jobs))
            if not b:
                continue
            s = seconds(b, real=True) / b.get("points", 1000)
            per[(method, jobs)] = s
            note = "damped 2%, every metric (not the LuGre case 4); wall time per point, median of 5"
            if jobs == 2 and (method, 1) in per:
                note += ", %.2fx from 1 job" % (per[(method, 1)] / s)
            c = b.get("cpu_s_per_point")
            if c:
                note += "; CPU %s per point" % fmt_time(c)
            if b.get("error_vs_exact") is not None:
                note += "; ratio metrics within %.1e of exact, settling_time_s within %.1e s" % (
                    b["error_vs_exact"], b.get("settling_error_s", float("nan")))
            if b.get("steps_per_point"):
                note += "; %.0f steps, %.0f RHS a point" % (b["steps_per_point"], b.get("rhs_per_point", 0))
            add("case 4d, 1000-point damped sweep, %s, %d job%s" % (label, jobs, "s" if jobs > 1 else ""),
                s, per.get(("Exact", jobs)), b if method.startswith("Cvode") else None, None, note, per_point=True)
    if floor_s and ("Exact", 1) in sweep:
        r = sweep[("Exact", 1)] / floor_s
        checks.append(("case 3 exact within 3x of the floor (1 job)", r <= TARGETS["case3_over_floor"], "%.1fx" % r))
    if floor_s and ("Exact", 1) in per:
        r = per[("Exact", 1)] / floor_s
        checks.append(("case 4d exact within 4x of the floor (1 job)", r <= TARGETS["case4d_over_floor"], "%.1fx" % r))
    # The same from the CPU time per point (a shared machine's wall time depends on its load).
    for name, key, b in (("case 3", "case3_over_floor", find(bench, "BM_Case3_Exact/1")),
                         ("case 4d", "case4d_over_floor", find(bench, "BM_Case4Damped_Exact/1"))):
        if floor_s and b and b.get("cpu_s_per_point"):
            r = b["cpu_s_per_point"] / floor_s
            checks.append(("%s exact within %gx of the floor (1 job, CPU per point)" % (name, TARGETS[key]),
                           r <= TARGETS[key], "%.1fx" % r))
    # --no-sync: the same sweeps without their syncs of the disk, shown apart (the must-show
    # is the default, synced sweep).
    for name, table in (("case 3", sweep), ("case 4d", per)):
        for method, label in (("Exact", "exact"), ("Cvode", "CVODE"), ("ExactNoSync", "exact --no-sync")):
            if (method, 1) in table and (method, 2) in table:
                r = table[(method, 1)] / table[(method, 2)]
                checks.append(("%s %s >= 1.8x from 1 to 2 jobs" % (name, label), r >= TARGETS["sweep_scaling"],
                               "%.2fx" % r))
    if ("Cvode", 2) in per:
        r = 1.0 / per[("Cvode", 2)]
        checks.append(("case 4d CVODE >= 1,500 runs/s (2 jobs, wall)", r >= TARGETS["case4d_cvode_runs_s"],
                       fmt_num(r)))
    # From the CPU time per point (cross-check on): what two free cores reach.
    b = find(bench, "BM_Case4Damped_Cvode/2")
    if b and b.get("cpu_s_per_point"):
        r = 2.0 / b["cpu_s_per_point"]
        checks.append(("case 4d CVODE >= 1,500 runs/s (2 jobs, from CPU per point)",
                       r >= TARGETS["case4d_cvode_runs_s"], fmt_num(r)))


def main(argv):
    markdown = "--markdown" in argv
    args = [a for a in argv[1:] if a != "--markdown"]
    if len(args) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    context, bench = load_benchmarks(args[0])
    try:
        with open(args[1]) as f:
            baseline = json.load(f)
    except (OSError, ValueError) as e:
        baseline = {"error": str(e)}
    memory = None
    if len(args) > 2:
        try:
            with open(args[2]) as f:
                text = f.read()
            rss = re.search(r"Maximum resident set size \(kbytes\): (\d+)", text)
            wall = re.search(r"Elapsed \(wall clock\) time \(h:mm:ss or m:ss\): ([\d:.]+)", text)
            points = re.search(r"(\d[\d,]*) points", text)
            if rss:
                parts = [float(p) for p in wall.group(1).split(":")] if wall else []
                secs = sum(p * 60 ** i for i, p in enumerate(reversed(parts))) if parts else None
                memory = {"rss_mb": int(rss.group(1)) / 1024.0, "seconds": secs,
                          "points": int(points.group(1).replace(",", "")) if points else None}
        except OSError:
            pass

    rows = []  # (what, time per run s, runs/s, ratio, x floor, steps/sim s, rhs/sim s, peak_ratio, note)
    checks = []
    # The floor (BM_Floor): the bare exact zero-order hold of case 1's mode, the exact
    # extremum inside each tick, the command built once. A point of a sweep (a run of
    # case 1) is given as a multiple of it ("x floor").
    fl = find(bench, "BM_Floor")
    floor_s = seconds(fl) if fl else None

    def add(what, s, exact_s, b=None, peak=None, note="", runs_s=None, per_point=False):
        ratio = s / exact_s if (s is not None and exact_s) else None
        over_floor = s / floor_s if (per_point and s is not None and floor_s) else None
        steps = b.get("steps_per_sim_s") if b else None
        rhs = b.get("rhs_per_sim_s") if b else None
        if runs_s is None and s:
            runs_s = 1.0 / s
        rows.append((what, s, runs_s, ratio, over_floor, steps, rhs, peak, note))

    if fl:
        add("floor: exact ZOH of case 1's mode, exact in-tick extremum, command built once", floor_s, None,
            None, fl.get("peak_ratio"), "%d ticks; off design (31.3 Hz) exact extremum / run's sampled peak - 1: "
            "%.1e undamped, %.1e at 2%%" % (
                int(fl.get("ticks", 0)),
                fl.get("peak_ratio_31hz_zeta0", float("nan")) / fl.get("run_peak_ratio_31hz_zeta0", float("nan")) - 1,
                fl.get("peak_ratio_31hz_zeta0.02", float("nan")) /
                fl.get("run_peak_ratio_31hz_zeta0.02", float("nan")) - 1), per_point=True)

    fb = find(bench, "BM_FloorBatch")
    if fb and fb.get("lanes"):
        add("floor in %d lanes (4 frequencies through one command), per point" % int(fb["lanes"]),
            seconds(fb) / fb["lanes"], None, None, None,
            "each lane's peak the scalar floor's bit for bit: %s" %
            ("yes" if fb.get("lanes_equal_scalar_bits") == 1 else "NO"), per_point=True)
    c1e = find(bench, "BM_Case1_Exact")
    c1c = find(bench, "BM_Case1_Cvode")
    exact1 = seconds(c1e) if c1e else None
    if c1e:
        add("case 1, shapebench exact", exact1, exact1, c1e, c1e.get("peak_ratio"), per_point=True)
        checks.append(("case 1 exact <= 50 us per run", exact1 * 1e6 <= TARGETS["case1_exact_us"],
                       fmt_time(exact1)))
    if c1c:
        s = seconds(c1c)
        add("case 1, shapebench CVODE (rtol 1e-8)", s, exact1, c1c, c1c.get("peak_ratio"),
            "metrics within %.1e of exact" % c1c.get("error_vs_exact", float("nan")), per_point=True)
        checks.append(("case 1 CVODE <= 1 ms per run", s * 1e3 <= 1.0, fmt_time(s)))
        if c1e:
            d = abs(c1c["peak_ratio"] - c1e["peak_ratio"])
            checks.append(("case 1 CVODE peak_ratio within 1e-6 of exact", d <= 1e-6, "%.1e" % d))
    for key, what in (("scipy_solve_ivp", "case 1, scipy solve_ivp restarted every period"),
                      ("numpy_exact_loop", "case 1, numpy exact discretisation loop")):
        entry = baseline.get(key)
        if entry:
            add(what, entry["seconds_per_run"], exact1, None, entry["peak_ratio"])
        else:
            rows.append((what, None, None, None, None, None, None, None,
                         baseline.get("error", "not run")))
    if "scipy_solve_ivp" in baseline and c1c:
        r = baseline["scipy_solve_ivp"]["seconds_per_run"] / seconds(c1c)
        checks.append(("CVODE >= 50x faster than scipy", r >= TARGETS["scipy_over_cvode"], "%.0fx" % r))
        d = abs(baseline["scipy_solve_ivp"]["peak_ratio"] - c1c["peak_ratio"])
        checks.append(("scipy peak_ratio within 1e-6 of shapebench CVODE", d <= 1e-6, "%.1e" % d))
    if "numpy_exact_loop" in baseline and c1e:
        r = baseline["numpy_exact_loop"]["seconds_per_run"] / exact1
        checks.append(("exact >= 20x faster than the numpy loop", r >= TARGETS["numpy_over_exact"], "%.0fx" % r))
        d = abs(baseline["numpy_exact_loop"]["peak_ratio"] - c1e["peak_ratio"])
        checks.append(("numpy peak_ratio within 1e-6 of shapebench exact", d <= 1e-6, "%.1e" % d))
    for name, what in (("BM_Case1_Exact_WithTrace", "case 1, exact, trace recorded (run --out)"),
                       ("BM_Case1_CommandOnly", "case 1, the command alone (controller)")):
        b = find(bench, name)
        if b:
            add(what, seconds(b), exact1, None)

    c2e = find(bench, "BM_Case2_Exact")
    c2c = find(bench, "BM_Case2_Cvode")
    exact2 = seconds(c2e) if c2e else None
    if c2e:
        add("case 2, shapebench exact", exact2, exact2, c2e, c2e.get("peak_ratio"))
    if c2c:
        add("case 2, shapebench CVODE (rtol 1e-8)", seconds(c2c), exact2, c2c, c2c.get("peak_ratio"),
            "metrics within %.1e of exact" % c2c.get("error_vs_exact", float("nan")))

    # Case 4: a plant with nonlinear elements (LuGre guides on the moving column, 10 s circle).
    c4 = find(bench, "BM_Case4_LugreCircle")
    scipy4 = baseline.get("case4")
    if c4:
        s = seconds(c4)
        factor = c4.get("sim_s", 0.0) / s
        add("case 4, shapebench CVODE with events (LuGre, 10 s circle)", s, None, c4, c4.get("peak_ratio"),
            "%s points/s, %.1fx faster than real time, %d events" % (
                fmt_num(c4.get("points", 0.0) / s), factor, int(c4.get("events", 0))))
        checks.append(("case 4 >= 50x faster than real time", factor >= TARGETS["case4_real_time"],
                       "%.1fx" % factor))
    if scipy4:
        add("case 4, scipy solve_ivp Radau with events", scipy4["seconds_per_run"], None, None, None,
            "%d events; deflection within %.1e of the scale from shapebench's" % (
                scipy4["events"], scipy4["max_difference_over_deflection_scale"]))
        checks.append(("case 4 same answer as scipy within 1e-3 of the deflection scale",
                       scipy4["max_difference_over_deflection_scale"] <= TARGETS["case4_agreement"],
                       "%.1e" % scipy4["max_difference_over_deflection_scale"]))
        if c4:
            r = scipy4["seconds_per_run"] / seconds(c4)
            checks.append(("case 4 >= 20x faster than scipy Radau", r >= TARGETS["scipy_over_case4"], "%.0fx" % r))

    sweep = {}
    cpu = {}
    sweep_bench = {}
    # Exact10k: case 3 at 10,000 points, the sweep's fixed cost (directory, manifest, results
    # synced: about a millisecond) a tenth of its share at 1000 points.
    for method in ("Exact", "ExactNoSync", "Exact10k", "Cvode"):
        for jobs in (1, 2):
            b = find(bench, "BM_Case3_%s/%d" % (method, jobs))
            if b:
                per_run = seconds(b, real=True) / b.get("points", 1000)
                sweep[(method, jobs)] = per_run
                cpu[(method, jobs)] = b.get("cpu_s_per_point")
                sweep_bench[(method, jobs)] = b
    for method, label, points in (("Exact", "exact", "1000"), ("ExactNoSync", "exact --no-sync", "1000"),
                                  ("Exact10k", "exact", "10,000"), ("Cvode", "CVODE", "1000")):
        for jobs in (1, 2):
            s = sweep.get((method, jobs))
            if s is None:
                continue
            base = sweep.get(("Exact", jobs)) if method != "Exact10k" else None
            note = "wall time per point"
            if jobs == 2 and (method, 1) in sweep:
                note += ", %.2fx from 1 job" % (sweep[(method, 1)] / s)
            c = cpu.get((method, jobs))
            if c:
                note += "; CPU %s per point: %s runs/s on %d free core%s" % (
                    fmt_time(c), fmt_num(jobs / c), jobs, "s" if jobs > 1 else "")
            e = sweep_bench.get((method, jobs), {}).get("error_vs_exact")
            if e is not None:
                note += "; metrics within %.1e of exact" % e
            add("case 3, %s-point sweep, %s, %d job%s" % (points, label, jobs, "s" if jobs > 1 else ""),
                s, base, sweep_bench.get((method, jobs)) if method == "Cvode" else None, None, note,
                per_point=True)
    for method, label, key, target in (("Exact", "exact", "case3_exact_runs_s", "20,000"),
                                       ("Cvode", "CVODE", "case3_cvode_runs_s", "1,500")):
        if (method, 2) in sweep:
            r = 1.0 / sweep[(method, 2)]
            checks.append(("case 3 %s >= %s runs/s (2 jobs, wall)" % (label, target),
                           r >= TARGETS[key], fmt_num(r)))
            c = cpu.get((method, 2))
            if c:
                checks.append(("case 3 %s >= %s runs/s (2 jobs, from CPU per point)" % (label, target),
                               2.0 / c >= TARGETS[key], fmt_num(2.0 / c)))

    case4d(bench, sweep, cpu, add, checks, floor_s)

    # In the benchmark's order (case, then variant), not the names' alphabetical one.
    tuning = sorted(((name, b) for name, b in bench.items() if name.startswith("BM_CvodeTuning/")),
                    key=lambda item: tuple(int(arg) for arg in item[0].split("/")[1:3]))
    for name, b in tuning:
        if b.get("error_occurred"):
            rows.append(("CVODE tuning, case %s, %s" % (name.split("/")[1], b.get("label", "")), None,
                         None, None, None, None, None, None, b.get("error_message", "")))
            continue
        which = name.split("/")[1]
        if which == "3":
            # The sweep's points one after another, one job: the time per point.
            add("CVODE tuning, case 3, %s" % b.get("label", ""), seconds(b) / b.get("points", 1000),
                sweep.get(("Exact", 1)), b, None,
                "rtol %.1e, every point's metrics within %.1e of exact; one job, CPU time per point" %
                (b.get("rtol", float("nan")), b.get("error_vs_exact", float("nan"))))
            continue
        base = exact1 if which == "1" else exact2
        add("CVODE tuning, case %s, %s" % (which, b.get("label", "")), seconds(b), base, b,
            b.get("peak_ratio"), "rtol %.0e, metrics within %.1e of exact" %
            (b.get("rtol", float("nan")), b.get("error_vs_exact", float("nan"))))

    # The G-code corpus's longest programs run in full (benchmarks/corpus_benchmark.cc); a
    # refused one or one stopped by a stroke alarm shows as its error, never dropped.
    corpus = sorted(((name, b) for name, b in bench.items() if name.startswith("BM_CorpusProgram/")),
                    key=lambda item: int(item[0].split("/")[1]))
    for name, b in corpus:
        if b.get("error_occurred"):
            rows.append(("G-code corpus, %s" % b.get("label", name), None, None, None, None, None, None,
                         None, b.get("error_message", "")))
            continue
        # Real-time factors on CPU time (the shared machine's load inflates the wall time).
        factor = b.get("real_time_factor_cpu", b.get("real_time_factor", float("nan")))
        add("G-code corpus, %s, run in full" % b.get("label", ""), seconds(b), None, None,
            b.get("peak_ratio"), "%.1f s simulated, %.1fx faster than real time (CPU; wall %.1fx), %d blocks" % (
                b.get("sim_s", float("nan")), factor, b.get("real_time_factor", float("nan")),
                int(b.get("blocks", 0))))
        if b.get("sim_s", 0.0) >= 1800.0:  # issue 36: a 30-minute real job at least 100x real time
            checks.append(("%s (%.0f min simulated) >= 100x real time, CPU" % (b.get("label", ""), b["sim_s"] / 60),
                           factor >= 100.0, "%.1fx" % factor))

    # `design`'s synthesis (benchmarks/design_benchmark.cc): goal under 1 s each, on CPU
    # time (single-threaded: the wall time of an idle machine); the wall time in the note.
    for name, what in (("BM_Design_OneMode", "design, one mode (18 Hz +/-10%, 5%, 0.1 ms grid)"),
                       ("BM_Design_TwoModes", "design, two modes (18 and 47 Hz +/-10%, 5%, 0.1 ms grid)")):
        b = find(bench, name)
        if b:
            s = seconds(b)
            add(what, s, None, None, None, "%.4f s pattern, %d LP solves, wall %s" % (
                b.get("duration_s", float("nan")), int(b.get("lp_solves", 0)), fmt_time(seconds(b, real=True))))
            checks.append(("%s < 1 s" % what, s < 1.0, fmt_time(s)))

    if memory:
        rows.append(("1,000,000-point sweep (exact, 2 jobs): peak resident %.0f MB" % memory["rss_mb"],
                     memory["seconds"] / memory["points"] if memory.get("seconds") and memory.get("points") else None,
                     None, None, None, None, None, None, "/usr/bin/time -v"))
        checks.append(("1,000,000-point sweep < 200 MB resident", memory["rss_mb"] < TARGETS["memory_mb"],
                       "%.0f MB" % memory["rss_mb"]))

    header = ("figure", "time/run", "runs/s", "x exact", "x floor", "steps/sim s", "RHS/sim s", "peak_ratio",
              "note")
    table = []
    for what, s, runs, ratio, over_floor, steps, rhs, peak, note in rows:
        table.append((what, fmt_time(s), fmt_num(runs) if runs else "", fmt_num(ratio) if ratio else "",
                      fmt_num(over_floor) if over_floor else "",
                      fmt_num(steps) if steps else "", fmt_num(rhs) if rhs else "",
                      ("%.9f" % peak) if peak is not None else "", note))
    cpu = context.get("num_cpus", "?")
    mhz = context.get("mhz_per_cpu", "?")
    intro = ("shapebench benchmarks, %s, %s CPUs at %s MHz (time/run: CPU time, sweeps: wall time "
             "per point)" % (context.get("date", ""), cpu, mhz))
    if markdown:
        print(intro + "\n")
        print("| " + " | ".join(header) + " |")
        print("|" + "|".join("---" for _ in header) + "|")
        for r in table:
            print("| " + " | ".join(r) + " |")
        print("\n| target | met | measured |\n|---|---|---|")
        for what, ok, value in checks:
            print("| %s | %s | %s |" % (what, "yes" if ok else "**no**", value))
    else:
        widths = [max(len(str(r[i])) for r in [header] + table) for i in range(len(header))]
        print(intro)
        line = "  ".join(h.ljust(widths[i]) for i, h in enumerate(header))
        print(line)
        print("-" * len(line))
        for r in table:
            print("  ".join(str(c).ljust(widths[i]) for i, c in enumerate(r)))
        print()
        for what, ok, value in checks:
            print("%-4s %-52s %s" % ("ok" if ok else "MISS", what, value))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
