#!/usr/bin/env python3
"""Writes samples/scenes/roller.glb: the bundled scene's mesh collider, a garden roller (a capsule
lying along Z: a cylinder with hemispherical ends, rolled along X), positions and triangles only
(meadow computes the normals). Run from the repository root; the output is committed."""
import json
import math
import struct
import sys

RADIUS_M = 0.18
HALF_LENGTH_M = 0.35  # of the cylinder part, along Z
RINGS = 8             # latitude bands per hemisphere
SEGMENTS = 24         # around the axis


def capsule():
    # Rings of points along the axis: one cap, the cylinder's two rims, the other cap.
    rings = []
    for i in range(RINGS + 1):  # -X pole .. equator
        a = math.pi / 2 * (1 - i / RINGS)
        rings.append((-HALF_LENGTH_M - RADIUS_M * math.sin(a), RADIUS_M * math.cos(a)))
    for i in range(RINGS + 1):  # equator .. +X pole
        a = math.pi / 2 * i / RINGS
        rings.append((HALF_LENGTH_M + RADIUS_M * math.sin(a), RADIUS_M * math.cos(a)))
    positions, indices = [], []
    for x, r in rings:
        for s in range(SEGMENTS):
            phi = 2 * math.pi * s / SEGMENTS
            # Built along X, turned to lie along Z: (x, y, z) -> (z, y, -x) keeps it right-handed.
            px, py, pz = x, r * math.cos(phi), r * math.sin(phi)
            positions.append((pz, py, -px))
    for k in range(len(rings) - 1):
        for s in range(SEGMENTS):
            a, b = k * SEGMENTS + s, k * SEGMENTS + (s + 1) % SEGMENTS
            c, d = a + SEGMENTS, b + SEGMENTS
            # Outward facing (counter-clockwise seen from outside).
            indices += [a, b, c, b, d, c]
    return positions, indices


def glb(positions, indices):
    pos = b"".join(struct.pack("<3f", *p) for p in positions)
    idx = b"".join(struct.pack("<I", i) for i in indices)
    binary = pos + idx
    lo = [min(p[k] for p in positions) for k in range(3)]
    hi = [max(p[k] for p in positions) for k in range(3)]
    doc = {
        "asset": {"version": "2.0", "generator": "meadow tools/make_roller_glb.py"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0, "name": "roller"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
        "buffers": [{"byteLength": len(binary)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(pos), "target": 34962},
            {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx), "target": 34963}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
             "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5125, "count": len(indices), "type": "SCALAR"}],
    }
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    binary += b"\0" * (-len(binary) % 4)
    chunks = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(binary), 0x004E4942) + binary
    return struct.pack("<III", 0x46546C67, 2, 12 + len(chunks)) + chunks


if __name__ == "__main__":
    out = sys.argv[1] if len(sys.argv) > 1 else "samples/scenes/roller.glb"
    with open(out, "wb") as f:
        f.write(glb(*capsule()))
    print("wrote", out)
