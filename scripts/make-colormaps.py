#!/usr/bin/env python3
"""Writes the colour maps the renderer loads (assets/colormaps/*.png, 256 x 1 RGB).

Run once; the PNGs are committed. Uses only the Python standard library.

  turbo    Google's Turbo map, the degree-5 polynomial approximation published with it
           (A. Mikhailov, "Turbo, an improved rainbow colormap", Google AI blog, 2019).
  viridis  matplotlib's viridis, the degree-6 polynomial fit by M. Zucker (max error ~1/255).
  grey     a linear ramp from 0.2 to 1.0, so undamaged particles stay visible on a dark background.
  ember    the default: steel grey for intact material (visible on the dark background, calm),
           then pale yellow, amber, orange and deep red as the value grows, so the first broken
           bonds already stand out and a crack reads at a glance. Piecewise linear in RGB.
"""
import os
import struct
import sys
import zlib

N = 256


def clamp01(v):
    return 0.0 if v < 0.0 else 1.0 if v > 1.0 else v


def turbo(x):
    # coefficients of 1, x, x^2, x^3, x^4, x^5 for red, green and blue
    r = (0.13572138, 4.61539260, -42.66032258, 132.13108234, -152.94239396, 59.28637943)
    g = (0.09140261, 2.19418839, 4.84296658, -14.18503333, 4.27729857, 2.82956604)
    b = (0.10667330, 12.64194608, -60.58204836, 110.36276771, -89.90310912, 27.34824973)
    return tuple(clamp01(sum(c * x ** i for i, c in enumerate(k))) for k in (r, g, b))


def viridis(x):
    # coefficients of 1, x, ..., x^6 for red, green and blue
    c = ((0.2777273272234177, 0.005407344544966578, 0.3340998053353061),
         (0.1050930431085774, 1.404613529898575, 1.384590162594685),
         (-0.3308618287255563, 0.214847559468213, 0.09509516302823659),
         (-4.634230498983486, -5.799100973351585, -19.33244095627987),
         (6.228269936347081, 14.17993336680509, 56.69055260068105),
         (4.776384997670288, -13.74514537774601, -65.35303263337234),
         (-5.435455855934631, 4.645852612178535, 26.3124352495832))
    return tuple(clamp01(sum(c[i][ch] * x ** i for i in range(7))) for ch in range(3))


EMBER_STOPS = ((0.00, (0.47, 0.53, 0.62)),
               (0.08, (0.78, 0.78, 0.55)),
               (0.30, (1.00, 0.80, 0.20)),
               (0.60, (0.96, 0.45, 0.10)),
               (1.00, (0.72, 0.06, 0.10)))


def ember(x):
    for (x0, c0), (x1, c1) in zip(EMBER_STOPS, EMBER_STOPS[1:]):
        if x <= x1:
            t = (x - x0) / (x1 - x0)
            return tuple(a + t * (b - a) for a, b in zip(c0, c1))
    return EMBER_STOPS[-1][1]


def grey(x):
    v = 0.2 + 0.8 * x
    return (v, v, v)


def png_bytes(rgb_rows, width, height):
    # minimal PNG: 8-bit RGB, filter type 0 on every row
    def chunk(tag, data):
        body = tag + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)
    raw = b"".join(b"\x00" + bytes(row) for row in rgb_rows)
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9))
            + chunk(b"IEND", b""))


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    out_dir = os.path.join(root, "assets", "colormaps")
    os.makedirs(out_dir, exist_ok=True)
    for name, fn in (("turbo", turbo), ("viridis", viridis), ("grey", grey), ("ember", ember)):
        row = []
        for i in range(N):
            row.extend(int(round(255.0 * ch)) for ch in fn(i / (N - 1)))
        path = os.path.join(out_dir, name + ".png")
        with open(path, "wb") as f:
            f.write(png_bytes([row], N, 1))
        print("wrote", path, file=sys.stderr)


if __name__ == "__main__":
    main()
