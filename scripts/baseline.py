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

With a second file, `shapebench_benchmarks --export_case4=FILE`, it also runs case 4 (the
moving column with LuGre friction on its X and Y guides, a 10 s circle) the way a user
would in scipy: the same plant, elements, tolerances and command, solve_ivp's Radau with
the analytic Jacobian, restarted at every period with that period's acceleration held, and
with events at the guides' velocity reversals (w = 0, where abs(w) has its kink: the
integration stops there and restarts, as shapebench's CVODE does). It reports the seconds
of one run, the events and the largest difference of its X and Y deflection at the periods'
ends from shapebench's, over the deflection scale (their largest magnitude): "case4".
Needs Debian's python3-numpy and python3-scipy (run with /usr/bin/python3); without them it
prints {"error": ...} and exits 0 (the baseline is optional).
"""
import json
import sys
import time


def case4_run(case, np, scipy, repeats=1):
    A = np.array(case["A"]); Ba = np.array(case["B_accel"]); Bv = np.array(case["B_vel"])
    C = np.array(case["C_deflection"])
    n = A.shape[0]
    els = case["elements"]
    L = len(els)
    rows_x = np.array([e["row_x"] for e in els]); rows_v = np.array([e["row_v"] for e in els])
    rows = np.hstack([rows_x, rows_v])
    cols = np.array([e["column_x"] for e in els])
    Fc = np.array([e["coulomb_n"] for e in els]); Fs = np.array([e["static_n"] for e in els])
    vs = np.array([e["stribeck_velocity_m_s"] for e in els]); s2 = np.array([e["viscous_n_s_m"] for e in els])
    s0 = np.array([e["sigma0_n_m"] for e in els]); s1 = np.array([e["sigma1_n_s_m"] for e in els])
    rtol = case["rtol"]
    atol = np.concatenate([np.array(case["atol"][0]), rtol * case["atol_scale"] * Fs / s0])
    N = n + 3 + L
    dt = case["period_s"]; ticks = case["simulated_ticks"]
    acc = np.zeros((ticks, 3))
    cmd = np.array(case["accel_m_s2"])
    acc[:min(ticks, len(cmd)), :2] = cmd[:ticks]

    def rhs(t, y, a):
        x = y[:n]; v = y[n:n + 3]; z = y[n + 3:]
        w = rows_x @ x + rows_v @ v
        g = Fc + (Fs - Fc) * np.exp(-(w / vs) ** 2)
        zd = w - s0 * np.abs(w) * z / g
        F = s0 * z + s1 * zd + s2 * w
        return np.concatenate([A @ x + Ba @ a + Bv @ v + cols.T @ F, a, zd])

    J0 = np.zeros((N, N)); J0[:n, :n] = A; J0[:n, n:n + 3] = Bv
    def jac(t, y, a):
        x = y[:n]; v = y[n:n + 3]; z = y[n + 3:]
        w = rows_x @ x + rows_v @ v
        e = np.exp(-(w / vs) ** 2)
        g = Fc + (Fs - Fc) * e
        dg = -2.0 * w / vs ** 2 * (Fs - Fc) * e
        aw = np.abs(w)
        dzd_dw = 1.0 - s0 * z * (np.sign(w) * g - aw * dg) / g ** 2
        dzd_dz = -s0 * aw / g
        dF_dw = s1 * dzd_dw + s2
        dF_dz = s0 + s1 * dzd_dz
        J = J0.copy()
        J[:n, :n + 3] += cols.T @ (dF_dw[:, None] * rows)
        for i in range(L):
            J[:n, n + 3 + i] += cols[i] * dF_dz[i]
            J[n + 3 + i, :n + 3] = dzd_dw[i] * rows[i]
            J[n + 3 + i, n + 3 + i] = dzd_dz[i]
        return J

    def make_event(i):
        def ev(t, y, a):
            return rows_x[i] @ y[:n] + rows_v[i] @ y[n:n + 3]
        ev.terminal = True
        return ev
    all_events = [make_event(i) for i in range(L)]

    def run():
        y = np.zeros(N)
        out = np.zeros((ticks, 2))
        events = 0
        for k in range(ticks):
            t, t1 = k * dt, (k + 1) * dt
            a = acc[k]
            masked = set()
            while True:
                active = [i for i in range(L) if i not in masked]
                evs = [all_events[i] for i in active]
                sol = scipy.integrate.solve_ivp(rhs, (t, t1), y, method="Radau", jac=jac, rtol=rtol,
                                                atol=atol, events=evs or None, args=(a,))
                y = sol.y[:, -1]
                if sol.status != 1:
                    break
                events += 1
                # The element whose velocity reversed: masked for the rest of this tick (it is
                # 0 at the restart; CVODE likewise waits for it to move away).
                for j, te in enumerate(sol.t_events):
                    if len(te):
                        masked.add(active[j])
                t = sol.t[-1]
                if t1 - t <= 1e-13:
                    break
            out[k] = C @ y[:n]
        return out, events

    best = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        out, events = run()
        best = min(best, time.perf_counter() - start)
    ref = np.array(case["shapebench_deflection_m"])[:ticks]
    scale = np.max(np.abs(ref))
    return {"seconds_per_run": best, "events": events, "simulated_s": ticks * dt,
            "max_difference_over_deflection_scale": float(np.max(np.abs(out - ref)) / scale),
            "deflection_scale_m": float(scale)}


def main(argv):
    if len(argv) not in (2, 3):
        print("usage: baseline.py CASE1.json [CASE4.json]", file=sys.stderr)
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
    case4 = None
    if len(argv) == 3:
        with open(argv[2]) as f:
            case4 = case4_run(json.load(f), np, scipy)
    print(json.dumps({
        "python": sys.version.split()[0],
        "numpy": np.__version__,
        "scipy": scipy.__version__,
        "scipy_solve_ivp": {"seconds_per_run": scipy_s, "peak_ratio": scipy_ratio},
        "numpy_exact_loop": {"seconds_per_run": numpy_s, "peak_ratio": numpy_ratio},
        "shapebench_peak_ratio_exact": case["shapebench_peak_ratio_exact"],
        "shapebench_peak_ratio_cvode": case["shapebench_peak_ratio_cvode"],
        "case4": case4,
    }, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
