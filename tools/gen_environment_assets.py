#!/usr/bin/env python3
"""Generate the environment-light test assets of assets/test/open_sky/: open scenes under a sky and an equirect map.

Python 3 standard library only; deterministic (rerunning rewrites byte-identical files).

    /usr/bin/python3 tools/gen_environment_assets.py [--out assets/test/open_sky]

writes
    open_sky.gltf    an open scene for a sky (no lights: run it with environment.sky_radiance or --environment,
                     light.sun_intensity=0 for the sky alone): a 12 x 12 m ground (albedo 0.5) facing +Y at y = 0,
                     a sphere (radius 0.5 m, albedo 0.8, flat-shaded facets so its surface is convex facet by facet)
                     at (0, 0.5, 0) and a 0.6 m cube (albedo 0.7) at (1.2, 0.3, -0.6); camera "overview".
                     Under a white sky of radiance 1 the ground far from the objects has L = 0.5 exactly and the
                     top facet of the sphere L = 0.8.
    closed_room.gltf a closed 4 x 3 x 4 m room (albedo 0.7) with walls, floor and roof 0.3 m thick (an inward box
                     inside an outward one), standing on a 12 x 12 m ground outside; camera "inside" looks across
                     the room. Under any sky the room's inside is black (L = 0), its outside lit.
    sky_test.hdr     a 64 x 32 equirectangular Radiance RGBE map (deepgi's convention, renderer/scene/
                     environment_map.h: u = 0.5 + atan2(z, x) / 2pi, top row = +Y): the upper hemisphere is a
                     sky whose colour tells the compass direction (+X red, +Z green, -X blue, -Z yellow, each
                     quadrant 0.5..1 W/m^2/sr), the lower hemisphere a grey 0.2 ground, and a 2 x 2-texel "sun" of
                     radiance 200 at 45 degrees elevation towards +X+Z (u = 0.625). Flat (not run-length) scanlines.
"""

import argparse
import math
import os
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gen_test_assets import FLOAT, UINT, Gltf  # noqa: E402


def quat_axis(axis, angle):
    s = math.sin(angle / 2)
    return [axis[0] * s, axis[1] * s, axis[2] * s, math.cos(angle / 2)]


def quat_mul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return [aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz]


def look_rotation(eye, target):
    """Quaternion turning the glTF camera (looking down -Z, +Y up) to look from eye at target."""
    d = [target[i] - eye[i] for i in range(3)]
    yaw = math.atan2(-d[0], -d[2])
    pitch = math.atan2(d[1], math.hypot(d[0], d[2]))
    return quat_mul(quat_axis((0, 1, 0), yaw), quat_axis((1, 0, 0), pitch))


class Mesh:
    def __init__(self):
        self.pos, self.nrm, self.idx = [], [], []

    def tri(self, a, b, c):
        """A flat triangle a, b, c counter-clockwise seen from its front."""
        u = [b[i] - a[i] for i in range(3)]
        v = [c[i] - a[i] for i in range(3)]
        n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
        ln = math.sqrt(sum(x * x for x in n))
        if ln == 0:
            return
        n = [x / ln for x in n]
        base = len(self.pos)
        self.pos += [tuple(a), tuple(b), tuple(c)]
        self.nrm += [tuple(n)] * 3
        self.idx += [base, base + 1, base + 2]

    def quad(self, a, b, c, d):
        self.tri(a, b, c)
        self.tri(a, c, d)


def ground(m, half):
    m.quad((-half, 0, half), (half, 0, half), (half, 0, -half), (-half, 0, -half))


def box(m, lo, hi, inward):
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    faces = [((x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)),  # +Z
             ((x1, y0, z0), (x0, y0, z0), (x0, y1, z0), (x1, y1, z0)),  # -Z
             ((x1, y0, z1), (x1, y0, z0), (x1, y1, z0), (x1, y1, z1)),  # +X
             ((x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)),  # -X
             ((x0, y1, z1), (x1, y1, z1), (x1, y1, z0), (x0, y1, z0)),  # +Y
             ((x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1))]  # -Y
    for f in faces:
        if inward:
            m.quad(f[3], f[2], f[1], f[0])
        else:
            m.quad(*f)


def sphere(m, centre, radius, rings=16, segments=32):
    def p(r, s):
        theta = math.pi * r / rings
        phi = 2 * math.pi * s / segments
        return (centre[0] + radius * math.sin(theta) * math.cos(phi), centre[1] + radius * math.cos(theta),
                centre[2] + radius * math.sin(theta) * math.sin(phi))
    for r in range(rings):
        for s in range(segments):
            a, b, c, d = p(r, s), p(r, s + 1), p(r + 1, s + 1), p(r + 1, s)
            # seen from outside b lies left of a (phi grows towards +Z) and d below it: a, b, c, d is counter-clockwise
            if r > 0:  # (at the poles one of the two triangles is degenerate)
                m.tri(a, b, c)
            if r < rings - 1:
                m.tri(a, c, d)


def add_mesh(g, name, m, material):
    lo = [min(p[c] for p in m.pos) for c in range(3)]
    hi = [max(p[c] for p in m.pos) for c in range(3)]
    pos = g.accessor("3f", m.pos, FLOAT, "VEC3", len(m.pos), minmax=(lo, hi))
    nrm = g.accessor("3f", m.nrm, FLOAT, "VEC3", len(m.nrm))
    ind = g.accessor("I", m.idx, UINT, "SCALAR", len(m.idx))
    g.j["meshes"].append({"name": name, "primitives": [
        {"attributes": {"POSITION": pos, "NORMAL": nrm}, "indices": ind, "material": material}]})
    g.j["nodes"].append({"name": name, "mesh": len(g.j["meshes"]) - 1})


def material(g, name, albedo, double_sided=False):
    m = {"name": name, "pbrMetallicRoughness": {
        "baseColorFactor": [albedo, albedo, albedo, 1.0], "metallicFactor": 0, "roughnessFactor": 1}}
    if double_sided:
        m["doubleSided"] = True
    g.j["materials"].append(m)
    return len(g.j["materials"]) - 1


def camera(g, name, eye, target, yfov=0.9):
    g.j.setdefault("cameras", []).append({"name": name, "type": "perspective",
                                          "perspective": {"yfov": yfov, "znear": 0.05}})
    g.j["nodes"].append({"name": name, "camera": len(g.j["cameras"]) - 1, "translation": list(eye),
                         "rotation": look_rotation(eye, target)})


def finish(g, path):
    g.j["scenes"].append({"nodes": list(range(len(g.j["nodes"])))})
    g.j["scene"] = 0
    g.write(path)


def open_sky(path):
    g = Gltf()
    m = Mesh()
    ground(m, 6.0)
    add_mesh(g, "ground", m, material(g, "ground", 0.5))
    m = Mesh()
    sphere(m, (0, 0.5, 0), 0.5)
    add_mesh(g, "sphere", m, material(g, "sphere", 0.8))
    m = Mesh()
    box(m, (0.9, 0.0, -0.9), (1.5, 0.6, -0.3), inward=False)
    add_mesh(g, "cube", m, material(g, "cube", 0.7))
    camera(g, "overview", (0.0, 3.2, 4.2), (0.3, 0.2, -0.3))
    finish(g, path)


def closed_room(path):
    g = Gltf()
    m = Mesh()
    ground(m, 6.0)
    add_mesh(g, "ground", m, material(g, "ground", 0.5))
    m = Mesh()
    box(m, (-2.0, 0.05, -2.0), (2.0, 3.05, 2.0), inward=True)   # the inside
    box(m, (-2.3, 0.0, -2.3), (2.3, 3.35, 2.3), inward=False)  # the outside: walls, floor and roof 0.3 m thick
    add_mesh(g, "room", m, material(g, "room", 0.7))
    camera(g, "inside", (0.0, 1.5, 1.6), (0.0, 1.2, -2.0), yfov=1.2)
    finish(g, path)


def sky_texel(x, y, w, h):
    u = (x + 0.5) / w
    t = (y + 0.5) / h
    phi = (u - 0.5) * 2 * math.pi
    theta = t * math.pi
    d = (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))
    if d[1] < 0:
        return (0.2, 0.2, 0.2)
    ramp = 0.5 + 0.5 * d[1]  # brighter towards the zenith
    if abs(d[0]) >= abs(d[2]):
        c = (1.0, 0.25, 0.25) if d[0] > 0 else (0.25, 0.25, 1.0)
    else:
        c = (0.25, 1.0, 0.25) if d[2] > 0 else (1.0, 1.0, 0.25)
    return tuple(ramp * v for v in c)


def rgbe(c):
    m = max(c)
    if m < 1e-32:
        return bytes((0, 0, 0, 0))
    e = math.frexp(m)[1]
    scale = 256.0 / (2.0 ** e)
    return bytes([min(255, int(v * scale)) for v in c] + [e + 128])


def sky_hdr(path, w=64, h=32):
    rows = []
    sun = (int(0.625 * w) - 1, int(0.25 * h) - 1)  # u = 0.625 (+X+Z), t = 0.25 (45 degrees up): 2 x 2 texels
    for y in range(h):
        row = bytearray()
        for x in range(w):
            c = sky_texel(x, y, w, h)
            if sun[0] <= x <= sun[0] + 1 and sun[1] <= y <= sun[1] + 1:
                c = (200.0, 200.0, 200.0)
            row += rgbe(c)
        rows.append(bytes(row))
    with open(path, "wb") as f:
        f.write(b"#?RADIANCE\n# deepgi tools/gen_environment_assets.py\nFORMAT=32-bit_rle_rgbe\n\n")
        f.write(("-Y %d +X %d\n" % (h, w)).encode())
        for r in rows:
            f.write(r)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "assets", "test",
                                                  "open_sky"))
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    open_sky(os.path.join(args.out, "open_sky.gltf"))
    closed_room(os.path.join(args.out, "closed_room.gltf"))
    sky_hdr(os.path.join(args.out, "sky_test.hdr"))
    print("wrote", os.path.normpath(args.out))


if __name__ == "__main__":
    main()
