#!/usr/bin/env python3
"""Writes samples/scenes/terrain.glb: a gently rolling square of terrain as one glTF 2.0 mesh.

Usage: tools/make_terrain.py [OUT.glb] [--size-m 12] [--cells 40] [--seed 7]
The height is a sum of a few long sine waves (amplitudes 0.15-0.4 m over wavelengths of
5-14 m), so slopes stay under about 20 degrees; positions in metres, +Y up (glTF), with
analytic normals and 32-bit indices. Standard library only.
"""
import argparse
import json
import math
import random
import struct

GLB_MAGIC = 0x46546C67
CHUNK_JSON = 0x4E4F534A
CHUNK_BIN = 0x004E4942
FLOAT = 5126
UNSIGNED_INT = 5125
ARRAY_BUFFER = 34962
ELEMENT_ARRAY_BUFFER = 34963


def waves(seed):
    rng = random.Random(seed)
    out = []
    for amplitude_m, wavelength_m in [(0.4, 14.0), (0.25, 9.0), (0.15, 5.0)]:
        angle = rng.uniform(0, 2 * math.pi)
        k = 2 * math.pi / wavelength_m
        out.append((amplitude_m, k * math.cos(angle), k * math.sin(angle), rng.uniform(0, 2 * math.pi)))
    return out


def height_and_gradient(w, x, z):
    h = dx = dz = 0.0
    for a, kx, kz, phase in w:
        s = kx * x + kz * z + phase
        h += a * math.sin(s)
        dx += a * kx * math.cos(s)
        dz += a * kz * math.cos(s)
    return h, dx, dz


def main():
    p = argparse.ArgumentParser()
    p.add_argument("out", nargs="?", default="samples/scenes/terrain.glb")
    p.add_argument("--size-m", type=float, default=12.0)
    p.add_argument("--cells", type=int, default=40)
    p.add_argument("--seed", type=int, default=7)
    args = p.parse_args()
    w = waves(args.seed)
    n = args.cells
    positions, normals, indices = [], [], []
    for j in range(n + 1):
        for i in range(n + 1):
            x = (i / n - 0.5) * args.size_m
            z = (j / n - 0.5) * args.size_m
            h, dx, dz = height_and_gradient(w, x, z)
            length = math.sqrt(dx * dx + 1 + dz * dz)
            positions += [x, h, z]
            normals += [-dx / length, 1 / length, -dz / length]
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            b, c, d = a + 1, a + n + 1, a + n + 2
            indices += [a, c, b, b, c, d]  # counter-clockwise seen from +Y
    pos = struct.pack(f"<{len(positions)}f", *positions)
    nor = struct.pack(f"<{len(normals)}f", *normals)
    idx = struct.pack(f"<{len(indices)}I", *indices)
    binary = pos + nor + idx
    xs, ys, zs = positions[0::3], positions[1::3], positions[2::3]
    gltf = {
        "asset": {"version": "2.0", "generator": "meadow tools/make_terrain.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "terrain"}],
        "meshes": [{"name": "terrain", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "mode": 4}]}],
        "buffers": [{"byteLength": len(binary)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(pos), "target": ARRAY_BUFFER},
            {"buffer": 0, "byteOffset": len(pos), "byteLength": len(nor), "target": ARRAY_BUFFER},
            {"buffer": 0, "byteOffset": len(pos) + len(nor), "byteLength": len(idx), "target": ELEMENT_ARRAY_BUFFER},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": FLOAT, "count": len(xs), "type": "VEC3",
             "min": [min(xs), min(ys), min(zs)], "max": [max(xs), max(ys), max(zs)]},
            {"bufferView": 1, "componentType": FLOAT, "count": len(xs), "type": "VEC3"},
            {"bufferView": 2, "componentType": UNSIGNED_INT, "count": len(indices), "type": "SCALAR"},
        ],
    }
    text = json.dumps(gltf, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    binary += b"\0" * (-len(binary) % 4)
    total = 12 + 8 + len(text) + 8 + len(binary)
    tmp = args.out + ".tmp"
    with open(tmp, "wb") as f:
        f.write(struct.pack("<III", GLB_MAGIC, 2, total))
        f.write(struct.pack("<II", len(text), CHUNK_JSON) + text)
        f.write(struct.pack("<II", len(binary), CHUNK_BIN) + binary)
    import os
    os.replace(tmp, args.out)  # written whole or not at all
    print(f"{args.out}: {len(indices) // 3} triangles, {total} bytes")


if __name__ == "__main__":
    main()
