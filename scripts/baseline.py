#!/usr/bin/python3
"""Benchmark case 1 the way a user would without shapebench (`make bench`).

Input: the JSON `shapebench_benchmarks --export_case1=FILE` writes: the one mode
(frequency, damping, gain), the interpolation period, the output substeps per period, the
ticks shapebench simulated, and the commanded acceleration held over each period (the same
command shapebench's run integrates; a user would have generated it too, which this script
is given for free: only the plant simulation and the peak are timed, to shapebench's whole
run).

Two baselines, each on the same samples as shapebench (`substeps` per period):
  scipy_solve_ivp   scipy.integrate.solve_ivp (RK45, rtol as the case, atol per state
                    from the static deflection as shapebench's CVODE), restarted at every
                    period with that period's acceleration held
  numpy_exact_loop  the exact zero-order-hold discretisation (scipy.linalg.expm of the
                    augmented matrix, python-control's c2d 'zoh'), stepped in a Python loop
                    x[k+1] = Ad x[k] + Bd u[k] as python-control's forced_response does

Prints one JSON object: per baseline the best seconds per run over a few repetitions and
its peak_ratio (max |deflection| / static), with shapebench's peak_ratio for comparison.
Needs Debian's python3-numpy and python3-scipy (run with /usr/bin/python3); without them it
prints {"error": ...} and exits 0 (the baseline is optional).
"""
import json
import sys
import time


def main(argv):
    if len(argv) != 2:
        print("usage: baseline.py CASE1.json", file=sys.stderr)
        return 2
    with open(argv[1]) as f:
        case = json.load(f)
    try:
        import numpy as np
        import scipy
        import scipy.integrate
        import scipy.linalg
    except ImportError as e:
        print(json.dumps({"error": "python3-numpy/python3-scipy missing (%s); apt-get install "
                          "python3-scipy python3-numpy" % e}))
        return 0

    w = 2.0 * np.pi * case["frequency_hz"]
    zeta = case["damping_ratio"]
    gain = case["gain"]
    dt = case["period_s"]
    substeps = case["substeps"]
    ticks = case["simulated_ticks"]
    accel = np.zeros(ticks)
    commanded = np.asarray(case["accel_m_s2"], dtype=float)
    accel[: min(ticks, len(commanded))] = commanded[:ticks]
    rtol = case["rtol"]

    # q'' + 2 zeta w q' + w^2 q = -a, deflection = gain q: x = [q, q'].
    A = np.array([[0.0, 1.0], [-w * w, -2.0 * zeta * w]])
    B = np.array([0.0, -1.0])
    static = np.max(np.abs(accel)) * abs(gain) / (w * w)  # the held largest acceleration
    atol = rtol * static / abs(gain) * np.array([1.0, w])

    def scipy_run():
        x = np.zeros(2)
        peak = 0.0
        h = dt / substeps
        for k in range(ticks):
            t0 = k * dt
            a = accel[k]
            t_eval = t0 + h * np.arange(1, substeps + 1)
            t_eval[-1] = t0 + dt
            sol = scipy.integrate.solve_ivp(lambda t, y: A @ y + B * a, (t0, t0 + dt), x,
                                            method="RK45", rtol=rtol, atol=atol, t_eval=t_eval)
            peak = max(peak, np.max(np.abs(gain * sol.y[0])))
            x = sol.y[:, -1]
        return peak / static

    def numpy_run():
        h = dt / substeps
        # python-control's c2d(..., 'zoh'): expm([[A, B], [0, 0]] h).
        M = np.zeros((3, 3))
        M[:2, :2] = A * h
        M[:2, 2] = B * h
        E = scipy.linalg.expm(M)
        Ad, Bd = E[:2, :2], E[:2, 2:3]
        u = np.repeat(accel, substeps)[np.newaxis, :]  # the acceleration per substep
        steps = u.shape[1]
        xout = np.zeros((2, steps + 1))
        for i in range(1, steps + 1):  # forced_response's loop
            xout[:, i] = Ad @ xout[:, i - 1] + Bd @ u[:, i - 1]
        return np.max(np.abs(gain * xout[0])) / static

    def best_of(run, repeats):
        best = float("inf")
        ratio = None
        for _ in range(repeats):
            start = time.perf_counter()
            ratio = run()
            best = min(best, time.perf_counter() - start)
        return best, ratio

    scipy_s, scipy_ratio = best_of(scipy_run, 2)
    numpy_s, numpy_ratio = best_of(numpy_run, 3)
    print(json.dumps({
        "python": sys.version.split()[0],
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "scipy_solve_ivp": {"seconds_per_run": scipy_s, "peak_ratio": scipy_ratio},
        "numpy_exact_loop": {"seconds_per_run": numpy_s, "peak_ratio": numpy_ratio},
        "shapebench_peak_ratio_exact": case["shapebench_peak_ratio_exact"],
        "shapebench_peak_ratio_cvode": case["shapebench_peak_ratio_cvode"],
    }, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
