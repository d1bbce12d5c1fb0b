#!/usr/bin/python3
"""Design a 4-impulse shaper with scipy.optimize, then verify it in the bench.

The loop the Python module exists for (docs/python.md): design an impulse sequence, score
it, adjust; then simulate it. Here:

1. Design: four impulses at 0, t1, t2 and D (D, the duration, given: 40 ms by default,
   ZVD's and EI's at 25 Hz), amplitudes >= 0 summing to 1, chosen to minimise the
   worst residual vibration over the band 20-30 Hz of an undamped mode. The residual is
   the bench's own formula (shapebench.residual_vibration, controller/impulse.h) on a grid
   of the band; scipy's differential evolution searches, SLSQP on the epigraph
   (minimise s subject to V(f_k) <= s) polishes.
2. Verify: the shaper as `controller.pattern.method: custom` in a sweep of the undamped
   SDOF scenario (configs/scenarios/sdof_method1.yaml, its acc/dec time set to 60 ms) over
   the mode's frequency, 20 to 30 Hz, beside ZVD and EI (5%) designed for 1 / D, the
   frequency at which their duration is D, and unshaped. The bench puts each impulse
   sequence on the 1 ms interpolation grid (grid_realization.h) and simulates the move.
   The score is the vibration left in the cruise after the acceleration
   (cruise_residual_ratio) as a fraction of the unshaped move's at the same frequency: for
   a linear plant the shaped phase is the unshaped one convolved with the impulses, so the
   fraction is the shaper's residual on the grid. The acc/dec time is chosen so that the
   unshaped phase leaves vibration at every frequency of the band (f x accel_time_s is
   never a whole number there: 1.2 to 1.8) and is longer than D (a phase shorter than its
   pattern is not a plain convolution).
3. Report: a table of each shaper's worst over the band, in theory (the continuous-time
   impulses on a fine grid) and in the bench, with where it is, the worst peak_ratio and
   residual_ratio of the whole move, and the motion time (the time the shaper costs);
   DIR/design_shaper.csv with the bench's curves (percent of unshaped), and a plot,
   DIR/design_shaper.png, drawn with matplotlib if installed, else gnuplot, else none.

    /usr/bin/python3 examples/design_shaper.py [--duration-ms 40] [--band 20 30]
        [--accel-time-ms 60] [--short] [--out DIR]

--short: a quicker search and a coarser sweep (what ctest runs). The module must be
importable: PYTHONPATH=build/python after `make build`.
"""

from __future__ import annotations

import argparse
import csv
import os
import shutil
import subprocess
import sys
import time

import numpy as np
from scipy import optimize

import shapebench

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BASE = os.path.join(ROOT, "configs", "scenarios", "sdof_method1.yaml")
FREQUENCY_KEY = "machine.modes[0].frequency_hz"


def impulses_of(x: np.ndarray, duration_s: float) -> tuple[list[float], list[float]]:
    """The design vector as impulses: x = (u1, u2, a0, a1, a2) in [0, 1]^5 gives
    t1 = u1 D, t2 = t1 + u2 (D - t1) (so 0 <= t1 <= t2 <= D), amplitudes a0, a1, a2 and
    1 - a0 - a1 - a2 at 0, t1, t2, D."""
    u1, u2, a0, a1, a2 = x
    t1 = u1 * duration_s
    t2 = t1 + u2 * (duration_s - t1)
    return [0.0, t1, t2, duration_s], [a0, a1, a2, 1.0 - a0 - a1 - a2]


def band_residuals(times: list[float], amplitudes: list[float], frequencies: np.ndarray) -> np.ndarray:
    """The bench's residual vibration (fraction of an unshaped step's) at each frequency."""
    return np.array([shapebench.residual_vibration(list(zip(times, amplitudes)), f) for f in frequencies])


def design(duration_s: float, band_hz: tuple[float, float], short: bool) -> tuple[list[float], list[float]]:
    """Four impulses over duration_s minimising the worst residual over the band."""
    grid = np.linspace(band_hz[0], band_hz[1], 21 if short else 41)

    def worst(x: np.ndarray) -> float:
        times, amplitudes = impulses_of(x, duration_s)
        negative = max(0.0, -amplitudes[3])  # the last amplitude must stay >= 0 too
        return float(band_residuals(times, amplitudes, grid).max()) + 10.0 * negative

    searched = optimize.differential_evolution(
        worst, bounds=[(0.0, 1.0)] * 5, seed=20, tol=1e-10, polish=False,
        maxiter=40 if short else 400, popsize=10 if short else 25)
    # Polish: minimise s over (x, s) with V(f_k; x) <= s for every k and a3 >= 0 (SLSQP).
    def constraints(z: np.ndarray) -> np.ndarray:
        times, amplitudes = impulses_of(z[:5], duration_s)
        return np.concatenate([z[5] - band_residuals(times, amplitudes, grid), [amplitudes[3]]])

    start = np.append(searched.x, worst(searched.x))
    polished = optimize.minimize(lambda z: z[5], start, method="SLSQP",
                                 bounds=[(0.0, 1.0)] * 5 + [(0.0, 1.0)],
                                 constraints=[{"type": "ineq", "fun": constraints}],
                                 options={"maxiter": 50 if short else 300, "ftol": 1e-12})
    best = polished.x[:5] if polished.success and worst(polished.x[:5]) <= worst(searched.x) else searched.x
    return impulses_of(np.clip(best, 0.0, 1.0), duration_s)


def tidy(times: list[float], amplitudes: list[float]) -> tuple[list[float], list[float]]:
    """Impulses closer than 10 us merged (the optimum may put two at one time), amplitudes
    below 1e-9 dropped: the sequence the bench's custom method takes (times ascending)."""
    merged: list[list[float]] = []
    for t, a in zip(times, amplitudes):
        if merged and t - merged[-1][0] < 1e-5:
            merged[-1][1] += a
        elif a > 1e-9 or t in (times[0], times[-1]):
            merged.append([t, a])
    return [t for t, _ in merged], [a for _, a in merged]


def bench_sweep(pattern_set: dict, accel_time_s: float, band_hz: tuple[float, float],
                steps: int) -> shapebench.SweepResult:
    """The SDOF scenario with this pattern over the mode's frequency (the pattern fixed)."""
    return shapebench.sweep({"base": BASE,
                             "grid": {FREQUENCY_KEY: {"from": band_hz[0], "to": band_hz[1], "steps": steps}},
                             "metrics": ["cruise_residual_ratio", "residual_ratio", "peak_ratio", "motion_time_s"]},
                            set={"controller.accel_time_s": accel_time_s, **pattern_set})


def write_plot(path_png: str, csv_path: str, names: list[str], band_hz: tuple[float, float]) -> str:
    """design_shaper.png with matplotlib, else gnuplot; returns what drew it ("" none)."""
    title = f"vibration left after the acceleration, % of unshaped ({band_hz[0]:g}-{band_hz[1]:g} Hz)"
    with open(csv_path, newline="") as file:
        rows = list(csv.DictReader(file))
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        figure, axes = plt.subplots(figsize=(9, 5))
        x = [float(row["frequency_hz"]) for row in rows]
        for name in names:
            axes.plot(x, [float(row[name]) for row in rows], label=name)
        axes.set(xlabel="mode frequency (Hz)", ylabel="% of unshaped", title=title)
        axes.grid(True, alpha=0.3)
        axes.legend()
        figure.savefig(path_png, dpi=100)
        return "matplotlib"
    except ImportError:
        pass
    if shutil.which("gnuplot") is None:
        return ""
    plots = ", ".join(f"'{csv_path}' using 1:{i + 2} with lines lw 2 title '{name}'" for i, name in enumerate(names))
    script = (f"set terminal pngcairo size 900,500\nset output '{path_png}'\nset datafile separator ','\n"
              f"set key autotitle columnhead\nset grid\nset xlabel 'mode frequency (Hz)'\n"
              f"set ylabel '% of unshaped'\nset title '{title}'\nplot {plots}\n")
    done = subprocess.run(["gnuplot"], input=script, text=True, capture_output=True)
    return "gnuplot" if done.returncode == 0 else ""


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--duration-ms", type=float, default=40.0, help="the shaper's duration D (default 40)")
    parser.add_argument("--band", type=float, nargs=2, default=[20.0, 30.0], metavar=("FROM_HZ", "TO_HZ"))
    parser.add_argument("--accel-time-ms", type=float, default=60.0,
                        help="the verification move's acc/dec time (default 60; longer than D)")
    parser.add_argument("--short", action="store_true", help="a quicker search and a coarser sweep (ctest)")
    parser.add_argument("--out", default="out/design_shaper", help="directory of the CSV and the plot")
    args = parser.parse_args()
    duration_s, accel_time_s = args.duration_ms * 1e-3, args.accel_time_ms * 1e-3
    band_hz = (args.band[0], args.band[1])
    if not (0 < band_hz[0] < band_hz[1]) or duration_s <= 0:
        parser.error("--band FROM TO with 0 < FROM < TO, and --duration-ms > 0")
    if accel_time_s < duration_s or np.floor(band_hz[0] * accel_time_s) != np.floor(band_hz[1] * accel_time_s) \
            or band_hz[0] * accel_time_s == np.floor(band_hz[0] * accel_time_s):
        parser.error("--accel-time-ms: at least D, and f x accel_time_s a whole number nowhere in the band "
                     "(there the unshaped phase leaves no vibration to compare with)")

    started = time.monotonic()
    times, amplitudes = tidy(*design(duration_s, band_hz, args.short))
    print(f"optimised shaper of duration {duration_s * 1e3:g} ms ({len(times)} distinct impulses; "
          f"{time.monotonic() - started:.1f} s of scipy.optimize):")
    for t, a in zip(times, amplitudes):
        print(f"  t = {t * 1e3:9.4f} ms  amplitude {a:.6f}")

    design_hz = 1.0 / duration_s  # ZVD's and undamped EI's duration is one period
    shapers = {
        "optimised": {"controller.pattern.method": "custom", "controller.pattern.frequency_hz": sum(band_hz) / 2,
                      "controller.pattern.impulses": [{"time_s": t, "amplitude": a} for t, a in zip(times, amplitudes)]},
        f"zvd {design_hz:g} Hz": {"controller.pattern.method": "zvd", "controller.pattern.frequency_hz": design_hz},
        f"ei {design_hz:g} Hz": {"controller.pattern.method": "ei", "controller.pattern.frequency_hz": design_hz,
                                 "controller.pattern.vibration_tolerance": 0.05},
        "unshaped": {"controller.pattern.method": "none"},
    }
    fine = np.linspace(band_hz[0], band_hz[1], 1001)
    steps = 21 if args.short else 101
    results = {name: bench_sweep(pattern_set, accel_time_s, band_hz, steps) for name, pattern_set in shapers.items()}
    for name, result in results.items():
        if not result.ok.all():
            print(f"error: {name}: {result['error'][~result.ok][0]}", file=sys.stderr)
            return 1
    unshaped = results["unshaped"]["cruise_residual_ratio"]
    frequencies = results["unshaped"][FREQUENCY_KEY]
    print(f"\nworst over {band_hz[0]:g}-{band_hz[1]:g} Hz of an undamped mode: theory, the impulses' residual "
          f"(1001 frequencies); bench, {os.path.relpath(BASE)} with a {accel_time_s * 1e3:g} ms acc/dec over "
          f"{steps} frequencies: the vibration left after the acceleration, % of unshaped")
    header = ("shaper", "duration_ms", "theory_%", "bench_%", "at_hz", "peak_ratio", "residual_ratio", "motion_time_s")
    print("  " + "  ".join(f"{h:>14}" if i else f"{h:<14}" for i, h in enumerate(header)))
    curves = {}
    for name, pattern_set in shapers.items():
        p = shapebench.pattern(BASE, set=pattern_set)
        theory = band_residuals(list(p.impulse_time_s), list(p.impulse_amplitude), fine).max()
        result = results[name]
        left = 100.0 * result["cruise_residual_ratio"] / unshaped
        worst = int(np.argmax(left))
        curves[name] = left
        cells = (f"{name:<14}", f"{p.duration_s * 1e3:14.3f}", f"{100 * theory:14.3f}", f"{left[worst]:14.3f}",
                 f"{frequencies[worst]:14.2f}" if name != "unshaped" else f"{'-':>14}",
                 f"{result['peak_ratio'].max():14.5f}",
                 f"{result['residual_ratio'].max():14.5f}", f"{result['motion_time_s'].max():14.3f}")
        print("  " + "  ".join(cells))

    os.makedirs(args.out, exist_ok=True)
    csv_path = os.path.join(args.out, "design_shaper.csv")
    with open(csv_path, "w", newline="") as file:
        writer = csv.writer(file)
        writer.writerow(["frequency_hz", *curves])
        for i, f in enumerate(frequencies):
            writer.writerow([repr(float(f)), *(repr(float(c[i])) for c in curves.values())])
    print(f"\nwrote {csv_path}")
    drawn = write_plot(os.path.join(args.out, "design_shaper.png"), csv_path, [n for n in curves if n != "unshaped"],
                       band_hz)
    if drawn:
        print(f"wrote {os.path.join(args.out, 'design_shaper.png')} ({drawn})")
    else:
        print("no plot: neither matplotlib nor gnuplot is installed (the CSV has the curves)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
