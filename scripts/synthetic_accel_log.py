#!/usr/bin/python3
"""Writes configs/measurements/accel_x.csv, the synthetic accelerometer log that
`shapebench recommend` ships with (docs/measured-data.md#accelerometer-logs).

Not a measurement: an X axis with two modes, 37 Hz at 5 % damping and 61 Hz at 3 %,
sharing its static deflection 80/20, on a base shaken along X by a linear chirp of 5 to
200 Hz over 3 s plus white noise. The accelerometer on the tool reads the base's
acceleration plus the modes' (model/machine.h's modal form: q_i'' + 2 zeta_i w_i q_i' +
w_i^2 q_i = -a, deflection sum g_i q_i with g_i / w_i^2 the static shares), sampled at
3200 Hz like an ADXL345 under Klipper, with sensor noise on every axis and gravity on Z.
Each mode is integrated exactly (zero-order hold, scipy's matrix exponential). Fixed
seed: the file is the same on every run.

    /usr/bin/python3 scripts/synthetic_accel_log.py > configs/measurements/accel_x.csv
"""
import numpy as np
from scipy.linalg import expm

RATE_HZ = 3200.0
SECONDS = 3.0
MODES = [(37.0, 0.05, 0.8), (61.0, 0.03, 0.2)]  # frequency, damping ratio, static share


def mode_acceleration(base_accel, frequency_hz, damping, dt):
    """q'' of q'' + 2 zeta w q' + w^2 q = -a (a held over each sample: zero-order hold)."""
    w = 2.0 * np.pi * frequency_hz
    a = np.array([[0.0, 1.0], [-w * w, -2.0 * damping * w]])
    b = np.array([0.0, -1.0])
    phi = expm(a * dt)
    gamma = np.linalg.solve(a, (phi - np.eye(2)) @ b)
    state = np.zeros(2)
    out = np.empty(len(base_accel))
    for k, f in enumerate(base_accel):
        out[k] = -f - 2.0 * damping * w * state[1] - w * w * state[0]
        state = phi @ state + gamma * f
    return out


def main():
    rng = np.random.default_rng(20240601)
    n = int(RATE_HZ * SECONDS)
    t = np.arange(n) / RATE_HZ
    f0, f1 = 5.0, 200.0
    chirp = np.sin(2.0 * np.pi * (f0 * t + (f1 - f0) / (2.0 * SECONDS) * t * t))
    base = 2000.0 * chirp + 200.0 * rng.standard_normal(n)  # mm/s^2
    # g_i = share_i w_i^2 / w_1^2: the static deflection 1 / w_1^2 per unit acceleration.
    w1 = MODES[0][0]
    x = base + sum(share * (f / w1) ** 2 * mode_acceleration(base, f, z, 1.0 / RATE_HZ) for f, z, share in MODES)
    x += 30.0 * rng.standard_normal(n)
    y = 0.05 * x + 30.0 * rng.standard_normal(n)
    z = 9810.0 + 30.0 * rng.standard_normal(n)
    print("#time,accel_x,accel_y,accel_z")
    print("# synthetic, not measured: scripts/synthetic_accel_log.py (modes 37 Hz 5%, 61 Hz 3%; shares 80/20)")
    for k in range(n):
        print("%.6f,%.1f,%.1f,%.1f" % (t[k], x[k], y[k], z[k]))


if __name__ == "__main__":
    main()
