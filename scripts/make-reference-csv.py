#!/usr/bin/env python3
"""Writes the reference trajectories of the IFToMM benchmark studies as CSV, computed apart from
periflex (plain Python, no periflex code):

  scenes/studies/references/a01_pendulum.csv        A01: the exact motion (Jacobi elliptic cd)
  scenes/studies/references/a02_double_four_bar.csv  A02: the one-degree-of-freedom equation
                                                      3 theta'' + 3.5 g cos(theta) = 0, RK4 at 1e-5 s

Columns t, probe.<name>.x, probe.<name>.y, every 0.005 s: what `periflex study` compares with
`reference = "csv"` (docs/work_precision.md).

  scripts/make-reference-csv.py
"""
import math
import os

G = 9.81
ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "studies", "references")
EVERY = 0.005


def jacobi_sn_cn_dn(u, m):
    """sn, cn, dn by the arithmetic-geometric mean (Abramowitz & Stegun 16.4)."""
    a, b, c = [1.0], [math.sqrt(1.0 - m)], [math.sqrt(m)]
    while abs(c[-1]) > 1e-16:
        a.append(0.5 * (a[-1] + b[-1]))
        b.append(math.sqrt(a[-2] * b[-1]))
        c.append(0.5 * (a[-2] - b[-2]))
    n = len(a) - 1
    phi = (2 ** n) * a[n] * u
    for k in range(n, 0, -1):
        phi = 0.5 * (phi + math.asin(c[k] / a[k] * math.sin(phi)))
    sn, cn = math.sin(phi), math.cos(phi)
    return sn, cn, math.sqrt(1.0 - m * sn * sn)


def write(name, probe, rows):
    os.makedirs(ROOT, exist_ok=True)
    path = os.path.join(ROOT, name)
    with open(path, "w") as out:
        out.write("t,probe.%s.x,probe.%s.y\n" % (probe, probe))
        for t, x, y in rows:
            out.write("%.6f,%.17g,%.17g\n" % (t, x, y))
    print("wrote", path, len(rows), "rows")


def a01(end=20.0):
    """Point mass on a 1 m rod from rest horizontal: sin(theta/2) = k cd(omega0 t | k^2)."""
    k, omega0 = math.sin(math.pi / 4), math.sqrt(G / 1.0)
    rows = []
    for i in range(int(round(end / EVERY)) + 1):
        t = i * EVERY
        sn, cn, dn = jacobi_sn_cn_dn(omega0 * t, k * k)
        theta = 2.0 * math.asin(k * cn / dn)
        rows.append((t, math.sin(theta), -math.cos(theta)))
    write("a01_pendulum.csv", "bob", rows)


def a02(end=10.0):
    """B0 = (cos theta, sin theta), theta(0) = pi/2, theta'(0) = -1, RK4 at h = 1e-5."""
    h = 1e-5
    stride = int(round(EVERY / h))
    f = lambda th, w: (w, -3.5 * G * math.cos(th) / 3.0)
    th, w = math.pi / 2, -1.0
    rows = []
    for i in range(int(round(end / h)) + 1):
        if i % stride == 0:
            rows.append((i * h, math.cos(th), math.sin(th)))
        k1 = f(th, w)
        k2 = f(th + h / 2 * k1[0], w + h / 2 * k1[1])
        k3 = f(th + h / 2 * k2[0], w + h / 2 * k2[1])
        k4 = f(th + h * k3[0], w + h * k3[1])
        th += h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        w += h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
    write("a02_double_four_bar.csv", "b0", rows)


if __name__ == "__main__":
    a01()
    a02()
