#!/usr/bin/python3
"""Writes UFF dataset 58 FRF files (ASCII, complex double, even spacing: 4E20.12) for the
shipped measurements (docs/measured-data.md):

  scripts/write_uff58.py synthetic OUT.uff
      configs/measurements/column_y_accelerance.uff: the accelerance of a moving column at
      its tool point along y, three modes (22 Hz 2 %, 40 Hz 3 %, 41.2 Hz 1.5 %), complex
      Gaussian noise of 2 % of each line's magnitude (seed 2551868).

  scripts/write_uff58.py text OUT.uff MEAS_POINT_1.txt [MEAS_POINT_2.txt ...]
      tests/data/uff/pyuff_beam_accelerance.uff: the measured accelerances pyuff ships as
      text (data/meas_point_N.txt, one complex number a line, 0 to 1000 Hz every 1 Hz),
      written as pyuff's showcase writes them: response node 1 +x, reference node N +x.

  scripts/write_uff58.py one OUT.uff VALUES.txt "ID LINE"
      tests/data/uff/real/pyfrf_hammer_h1_accelerance.uff: one accelerance (one complex
      number a line, 0 Hz up every 1 Hz; nan for a line not measured) as one record,
      response and reference node 1 +x, its first ID line given
      (tests/data/uff/real/README.md says how the values were made).
"""
import sys

import numpy as np


def record(func_type, rsp_node, rsp_dir, ref_node, ref_dir, f0, df, values, id1):
    lines = ["%6i" % -1, "%6i%74s" % (58, ""), "%-80s" % id1, "%-80s" % "NONE", "%-80s" % "NONE",
             "%-80s" % "NONE", "%-80s" % "NONE"]
    lines.append("%5i%10i%5i%10i %-10s%10i%4i %-10s%10i%4i" %
                 (func_type, 0, 0, 0, "NONE", rsp_node, rsp_dir, "NONE", ref_node, ref_dir))
    lines.append("%10i%10i%10i%13.5e%13.5e%13.5e" % (6, len(values), 1, f0, df, 0.0))
    lines.append("%10i%5i%5i%5i %-20s %-20s" % (18, 0, 0, 0, "Frequency", "Hz"))
    lines.append("%10i%5i%5i%5i %-20s %-20s" % (12, 0, 0, 0, "Acceleration", "m/s2"))
    lines.append("%10i%5i%5i%5i %-20s %-20s" % (13, 0, 0, 0, "Force", "N"))
    lines.append("%10i%5i%5i%5i %-20s %-20s" % (0, 0, 0, 0, "NONE", "NONE"))
    numbers = np.empty(2 * len(values))
    numbers[0::2] = values.real
    numbers[1::2] = values.imag
    for i in range(0, len(numbers), 4):
        lines.append("".join("%20.11e" % x for x in numbers[i:i + 4]))
    lines.append("%6i" % -1)
    return "\n".join(lines) + "\n"


def synthetic(out):
    f = np.arange(0, 801) * 0.125
    w = 2 * np.pi * f
    modes = [(22.0, 0.02, 5e-5), (40.0, 0.03, 3.3e-5), (41.2, 0.015, -2.7e-5)]  # Hz, zeta, R (1/kg)
    h = np.zeros_like(w, dtype=complex)
    for fr, zeta, constant in modes:
        wr = 2 * np.pi * fr
        h += constant / (wr**2 - w**2 + 2j * zeta * wr * w)
    a = -w**2 * h
    rng = np.random.default_rng(2551868)
    noise = (rng.standard_normal(len(a)) + 1j * rng.standard_normal(len(a))) * 0.02 / np.sqrt(2)
    a = a + np.abs(a) * noise
    with open(out, "w") as file:
        file.write(record(4, 1, 2, 1, 2, 0.0, 0.125, a, "column tool point y, synthetic (scripts/write_uff58.py)"))


def from_text(out, paths):
    with open(out, "w") as file:
        for n, path in enumerate(paths, start=1):
            values = np.genfromtxt(path, dtype=complex)
            file.write(record(4, 1, 1, n, 1, 0.0, 1.0, values, "pyuff data/meas_point_%d.txt" % n))


def one(out, path, id1):
    values = np.genfromtxt(path, dtype=complex)
    with open(out, "w") as file:
        file.write(record(4, 1, 1, 1, 1, 0.0, 1.0, values, id1))


if __name__ == "__main__":
    if sys.argv[1] == "synthetic":
        synthetic(sys.argv[2])
    elif sys.argv[1] == "one":
        one(sys.argv[2], sys.argv[3], sys.argv[4])
    else:
        from_text(sys.argv[2], sys.argv[3:])
