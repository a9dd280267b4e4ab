#!/usr/bin/env python3
"""Writes density.png, the prairie's density map (8-bit grey, 256 x 256 over 1 km x 1 km):
value noise in three octaves for thick and thin stands of grass, and a mown path (a tenth of
the density) winding across. Standard library only; the output is the same on every machine.
    samples/prairie/make_density_map.py [OUT.png]"""
import math
import random
import struct
import sys
import zlib

SIZE = 256


def lattice(cells, rng):
    return [[rng.random() for _ in range(cells + 1)] for _ in range(cells + 1)]


def smooth(t):
    return t * t * (3.0 - 2.0 * t)


def value_noise(grid, cells, x, y):
    gx, gy = x * cells, y * cells
    ix, iy = min(int(gx), cells - 1), min(int(gy), cells - 1)
    fx, fy = smooth(gx - ix), smooth(gy - iy)
    a, b = grid[iy][ix], grid[iy][ix + 1]
    c, d = grid[iy + 1][ix], grid[iy + 1][ix + 1]
    return (a * (1 - fx) + b * fx) * (1 - fy) + (c * (1 - fx) + d * fx) * fy


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "density.png"
    rng = random.Random(29)
    octaves = [(4, 0.6), (9, 0.28), (23, 0.12)]
    grids = [(lattice(cells, rng), cells, weight) for cells, weight in octaves]
    rows = []
    for r in range(SIZE):
        row = bytearray([0])  # PNG filter type 0 for the row
        y = r / (SIZE - 1)
        for c in range(SIZE):
            x = c / (SIZE - 1)
            n = sum(w * value_noise(g, cells, x, y) for g, cells, w in grids)
            density = min(1.0, max(0.15, 1.6 * (n - 0.5) + 0.7))
            # The path: a sine across the field, 3 texels (12 m) wide.
            path_y = 0.5 + 0.18 * math.sin(2.0 * math.pi * (x * 1.3 + 0.1))
            if abs(y - path_y) * SIZE < 1.5:
                density *= 0.1
            row.append(int(round(255 * density)))
        rows.append(bytes(row))
    raw = zlib.compress(b"".join(rows), 9)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", SIZE, SIZE, 8, 0, 0, 0, 0))
    png += chunk(b"IDAT", raw) + chunk(b"IEND", b"")
    with open(out, "wb") as f:
        f.write(png)


if __name__ == "__main__":
    main()
