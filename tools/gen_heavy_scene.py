#!/usr/bin/env python3
"""Writes assets/heavy/heavy.gltf: a heavy-geometry scene (1.2 M triangles) for the single-pass against
depth-peeling comparison of issue 13, where the geometry cost shows.

A floor and a 21 x 21 grid of finely tessellated spheres (64 segments x 20 rings, 2432 triangles each), one mesh
instanced by 441 nodes so the file stays small (the loader expands every instance: the renderer draws all their
triangles). Seen from a low camera, the rows hide each other: depth complexity for the second layer. The default
sun lights it (no lights in the file).
"""
import argparse
import base64
import json
import math
import os
import struct

SEGMENTS, RINGS = 64, 20  # 2 * 64 * 20 triangles per sphere, less the 128 degenerate ones at the poles
GRID = 21                 # 21 x 21 = 441 spheres -> about 1.1 M triangles with the floor
SPACING, RADIUS = 2.0, 0.8


def sphere():
    pos, nrm, idx = [], [], []
    for r in range(RINGS + 1):
        th = math.pi * r / RINGS
        for s in range(SEGMENTS + 1):
            ph = 2.0 * math.pi * s / SEGMENTS
            n = (math.sin(th) * math.cos(ph), math.cos(th), math.sin(th) * math.sin(ph))
            nrm.append(n)
            pos.append(tuple(RADIUS * c for c in n))
    row = SEGMENTS + 1
    for r in range(RINGS):
        for s in range(SEGMENTS):
            a, b = r * row + s, r * row + s + 1
            c, d = a + row, b + row
            if r != 0:
                idx += [a, b, c]
            if r != RINGS - 1:
                idx += [b, d, c]
    return pos, nrm, idx


def floor(half):
    pos = [(-half, 0.0, -half), (half, 0.0, -half), (half, 0.0, half), (-half, 0.0, half)]
    return pos, [(0.0, 1.0, 0.0)] * 4, [0, 2, 1, 0, 3, 2]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "assets", "heavy"))
    args = ap.parse_args()
    half = SPACING * GRID * 0.5 + 4.0
    meshes = [sphere(), floor(half)]
    blob = bytearray()
    accessors, views, gl_meshes = [], [], []

    def add_view(data, target):
        while len(blob) % 4:
            blob.append(0)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
        blob.extend(data)
        return len(views) - 1

    for m, (pos, nrm, idx) in enumerate(meshes):
        p = add_view(struct.pack("<%df" % (3 * len(pos)), *[c for v in pos for c in v]), 34962)
        lo = [min(v[i] for v in pos) for i in range(3)]
        hi = [max(v[i] for v in pos) for i in range(3)]
        accessors.append({"bufferView": p, "componentType": 5126, "count": len(pos), "type": "VEC3", "min": lo, "max": hi})
        n = add_view(struct.pack("<%df" % (3 * len(nrm)), *[c for v in nrm for c in v]), 34962)
        accessors.append({"bufferView": n, "componentType": 5126, "count": len(nrm), "type": "VEC3"})
        i = add_view(struct.pack("<%dI" % len(idx), *idx), 34963)
        accessors.append({"bufferView": i, "componentType": 5125, "count": len(idx), "type": "SCALAR"})
        gl_meshes.append({"name": ["sphere", "floor"][m],
                          "primitives": [{"attributes": {"POSITION": 3 * m, "NORMAL": 3 * m + 1}, "indices": 3 * m + 2,
                                          "material": m}]})
    nodes = [{"name": "floor", "mesh": 1}]
    for gz in range(GRID):
        for gx in range(GRID):
            x = (gx - (GRID - 1) * 0.5) * SPACING
            z = (gz - (GRID - 1) * 0.5) * SPACING
            nodes.append({"name": "sphere_%d_%d" % (gx, gz), "mesh": 0, "translation": [x, RADIUS, z]})
    # A low camera looking along a diagonal of the grid: most rows hide the ones behind them.
    eye, target = (half * 0.9, 3.5, half * 0.9), (0.0, 0.0, 0.0)
    f = [target[i] - eye[i] for i in range(3)]
    fl = math.sqrt(sum(c * c for c in f))
    f = [c / fl for c in f]
    yaw = math.atan2(-f[0], -f[2])
    pitch = math.asin(f[1])
    # Rotation: yaw about Y, then pitch about the local X (glTF cameras look down -Z).
    cy, sy, cp, sp = math.cos(yaw / 2), math.sin(yaw / 2), math.cos(pitch / 2), math.sin(pitch / 2)
    q = [cy * sp, sy * cp, -sy * sp, cy * cp]
    nodes.append({"name": "grove", "camera": 0, "translation": list(eye), "rotation": q})
    tris = sum(len(m[2]) // 3 for m in meshes[:1]) * GRID * GRID + 2
    doc = {
        "asset": {"version": "2.0", "generator": "deepgi tools/gen_heavy_scene.py"},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "meshes": gl_meshes,
        "materials": [{"name": "sphere", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.6, 0.5, 1.0], "metallicFactor": 0.0}},
                      {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.6, 0.6, 1.0], "metallicFactor": 0.0}}],
        "cameras": [{"name": "grove", "type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.1, "zfar": 200.0}}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode("ascii")}],
    }
    os.makedirs(args.out, exist_ok=True)
    path = os.path.join(args.out, "heavy.gltf")
    with open(path, "w", encoding="ascii", newline="\n") as fo:
        json.dump(doc, fo, separators=(",", ":"))
    print("heavy: %d triangles (%d spheres x %d + floor), wrote %s" % (tris, GRID * GRID, len(meshes[0][2]) // 3, os.path.normpath(path)))


if __name__ == "__main__":
    main()
