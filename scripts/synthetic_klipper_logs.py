#!/usr/bin/python3
"""Writes tests/data/klipper/machine_*.csv: three synthetic accelerometer logs of three
different machines that the Klipper fixtures (tests/data/klipper/README.md) are computed
on. Not measurements. Each log is a base shaken along one axis by a linear chirp of
5 to 200 Hz plus white noise; the tool's accelerometer reads the base's acceleration plus
its modes' (q'' + 2 zeta w q' + w^2 q = -a, each mode integrated exactly over a sample
with the base acceleration held: zero-order hold), sensor noise on every axis, gravity
on Z. Fixed seeds: the files are the same on every run.

    /usr/bin/python3 scripts/synthetic_klipper_logs.py tests/data/klipper
"""
import os
import sys

import numpy as np
from scipy.linalg import expm

# name: rate, seconds, driven axis, modes (frequency Hz, damping ratio, static share),
# cross-talk into the other horizontal axis, seed.
MACHINES = {
    # A bed slinger's Y: a low, well damped bed mode and a stiffer frame mode.
    "machine_bedslinger_y": (3200.0, 2.0, 1, [(42.0, 0.07, 0.85), (95.0, 0.04, 0.15)], 0.08, 11),
    # A CoreXY's X at an LIS2DW's 1600 Hz: one dominant mode and a weak high one.
    "machine_corexy_x": (1600.0, 3.0, 0, [(58.0, 0.05, 0.9), (112.0, 0.03, 0.1)], 0.15, 22),
    # A machine tool's column: low, lightly damped modes.
    "machine_column_x": (1000.0, 4.0, 0, [(16.5, 0.025, 0.7), (31.0, 0.04, 0.3)], 0.05, 33),
}


def mode_acceleration(base_accel, frequency_hz, damping, dt):
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


def write(path, rate, seconds, axis, modes, cross, seed):
    rng = np.random.default_rng(seed)
    n = int(rate * seconds)
    t = np.arange(n) / rate
    chirp = np.sin(2.0 * np.pi * (5.0 * t + (200.0 - 5.0) / (2.0 * seconds) * t * t))
    base = 2000.0 * chirp + 200.0 * rng.standard_normal(n)
    w1 = modes[0][0]
    driven = base + sum(s * (f / w1) ** 2 * mode_acceleration(base, f, z, 1.0 / rate) for f, z, s in modes)
    accel = [None, None, None]
    accel[axis] = driven + 30.0 * rng.standard_normal(n)
    accel[1 - axis] = cross * driven + 30.0 * rng.standard_normal(n)
    accel[2] = 9810.0 + 30.0 * rng.standard_normal(n)
    with open(path, "w") as out:
        out.write("#time,accel_x,accel_y,accel_z\n")
        text = ", ".join("%g Hz %g%%" % (f, 100 * z) for f, z, _ in modes)
        out.write("# synthetic, not measured: scripts/synthetic_klipper_logs.py (%s)\n" % text)
        for k in range(n):
            out.write("%.6f,%.1f,%.1f,%.1f\n" % (t[k], accel[0][k], accel[1][k], accel[2][k]))


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else "tests/data/klipper"
    for name, spec in MACHINES.items():
        write(os.path.join(folder, name + ".csv"), *spec)


if __name__ == "__main__":
    main()
