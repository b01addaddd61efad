#!/usr/bin/env python3
"""Generate deepgi's two default glTF scenes: the Cornell-style box and the atrium.

Python 3 standard library only (Debian 12's /usr/bin/python3 is enough). The output is deterministic:
rerunning the script rewrites byte-identical files.

    /usr/bin/python3 tools/gen_scenes.py [--out assets]

writes
    <out>/cornell_box/cornell_box.gltf + .bin
    <out>/atrium/atrium.gltf + .bin + stone_floor.png + sandstone_wall.png

Conventions (shared with the rasterizer and the path tracer):
  * glTF 2.0, metres, +Y up.
  * Every triangle is counter-clockwise seen from the side its normal points to. Solids have outward normals,
    walls seen from inside face into the room. Only the banners are double-sided.
  * Solids never share a coplanar face with another solid, and where two pieces meet either their vertices
    match along the shared edge, or one piece pokes into the other whose surface is continuous across the
    intersection, so there are no T-junction cracks through which light could leak.
  * KHR_lights_punctual sun: `intensity` is the irradiance (W/m^2) on a surface facing it.

Before writing anything the script checks every triangle (the geometric normal of its CCW edges agrees with all
three vertex normals, no degenerate triangles) and that the pieces built as closed solids are watertight and
consistently oriented (every directed edge is matched by exactly one reverse edge). It exits non-zero otherwise.
"""

import argparse
import json
import math
import os
import struct
import sys
import zlib

# ----------------------------------------------------------------------------------------------- vectors


def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def mul(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def length(a):
    return math.sqrt(dot(a, a))


def normalize(a):
    n = length(a)
    if n == 0.0:
        raise ValueError("cannot normalize a zero vector")
    return (a[0] / n, a[1] / n, a[2] / n)


def clean(v, digits=6):
    """Rounds away float noise (1e-17 instead of 0, -0.0) so the output is tidy and stable."""
    return tuple(round(c, digits) + 0.0 for c in v)


def newell_normal(pts):
    """Unnormalized normal of a planar polygon whose vertices are in counter-clockwise order."""
    n = [0.0, 0.0, 0.0]
    for i, p in enumerate(pts):
        q = pts[(i + 1) % len(pts)]
        n[0] += (p[1] - q[1]) * (p[2] + q[2])
        n[1] += (p[2] - q[2]) * (p[0] + q[0])
        n[2] += (p[0] - q[0]) * (p[1] + q[1])
    return tuple(n)


def quat_from_basis(x, y, z):
    """Unit quaternion (x, y, z, w) of the rotation whose matrix columns are the orthonormal x, y, z."""
    m00, m10, m20 = x
    m01, m11, m21 = y
    m02, m12, m22 = z
    tr = m00 + m11 + m22
    if tr > 0.0:
        s = math.sqrt(tr + 1.0) * 2.0
        q = ((m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s, 0.25 * s)
    elif m00 > m11 and m00 > m22:
        s = math.sqrt(1.0 + m00 - m11 - m22) * 2.0
        q = (0.25 * s, (m01 + m10) / s, (m02 + m20) / s, (m21 - m12) / s)
    elif m11 > m22:
        s = math.sqrt(1.0 + m11 - m00 - m22) * 2.0
        q = ((m01 + m10) / s, 0.25 * s, (m12 + m21) / s, (m02 - m20) / s)
    else:
        s = math.sqrt(1.0 + m22 - m00 - m11) * 2.0
        q = ((m02 + m20) / s, (m12 + m21) / s, 0.25 * s, (m10 - m01) / s)
    n = math.sqrt(sum(c * c for c in q))
    q = tuple(c / n for c in q)
    if q[3] < 0.0:
        q = tuple(-c for c in q)
    return q


def quat_rotate(q, v):
    qx, qy, qz, qw = q
    u = (qx, qy, qz)
    t = mul(cross(u, v), 2.0)
    return add(add(v, mul(t, qw)), cross(u, t))


def look_rotation(forward, up=(0.0, 1.0, 0.0)):
    """Quaternion that turns the node's local -Z into `forward` with local +Y as close to `up` as possible."""
    f = normalize(forward)
    if abs(dot(f, normalize(up))) > 0.999:
        up = (0.0, 0.0, -1.0)
    r = normalize(cross(f, up))
    u = cross(r, f)
    return quat_from_basis(r, u, mul(f, -1.0))


def sun_travel_direction(azimuth_deg, elevation_deg):
    """Direction sunlight travels; the sun stands at `azimuth` (from +Z towards +X) and `elevation` above the
    horizon (the same convention as the renderer's light.sun_azimuth / light.sun_elevation settings)."""
    az, el = math.radians(azimuth_deg), math.radians(elevation_deg)
    to_sun = (math.cos(el) * math.sin(az), math.sin(el), math.cos(el) * math.cos(az))
    return mul(to_sun, -1.0)


# ----------------------------------------------------------------------------------------------- PNG


def write_png(path, width, height, rgb_rows):
    """8-bit RGB PNG; rgb_rows is a list of `height` bytes objects of width*3 bytes, top row first."""
    raw = bytearray()
    for row in rgb_rows:
        if len(row) != width * 3:
            raise ValueError("bad PNG row length")
        raw.append(0)  # filter: none
        raw += row

    def chunk(tag, data):
        c = struct.pack(">I", len(data)) + tag + data
        return c + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n"
    png += chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    png += chunk(b"sRGB", b"\x00")
    png += chunk(b"IDAT", zlib.compress(bytes(raw), 9))
    png += chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def hash01(x, y, seed):
    """Deterministic integer hash -> [0, 1)."""
    h = (x * 374761393 + y * 668265263 + seed * 2246822519) & 0xFFFFFFFF
    h = ((h ^ (h >> 13)) * 1274126177) & 0xFFFFFFFF
    h ^= h >> 16
    return (h & 0xFFFFFF) / float(0x1000000)


def value_noise(x, y, cell, period, seed):
    """Smooth value noise, tileable with `period` lattice cells."""
    fx, fy = x / cell, y / cell
    ix, iy = int(math.floor(fx)), int(math.floor(fy))
    tx, ty = fx - ix, fy - iy
    tx, ty = tx * tx * (3 - 2 * tx), ty * ty * (3 - 2 * ty)
    x0, x1 = ix % period, (ix + 1) % period
    y0, y1 = iy % period, (iy + 1) % period
    a = hash01(x0, y0, seed) * (1 - tx) + hash01(x1, y0, seed) * tx
    b = hash01(x0, y1, seed) * (1 - tx) + hash01(x1, y1, seed) * tx
    return a * (1 - ty) + b * ty


def to_byte(v):
    return max(0, min(255, int(round(v))))


def stone_floor_texture(size=256):
    """4 x 4 square stone tiles in a checker of two warm greys, grout lines, per-tile tint and fine noise.
    Tiles seamlessly (the grout falls on the texture border on both sides)."""
    tiles = 4
    tile = size // tiles
    light, dark, grout = (214, 202, 182), (168, 156, 140), (110, 103, 94)
    rows = []
    for y in range(size):
        row = bytearray()
        for x in range(size):
            tx, ty = x // tile, y // tile
            lx, ly = x % tile, y % tile
            edge = min(lx, ly, tile - 1 - lx, tile - 1 - ly)  # distance to the tile border in pixels
            n = 0.55 * value_noise(x, y, 8, size // 8, 11) + 0.45 * value_noise(x, y, 32, size // 32, 12)
            if edge < 2:
                base = grout
                k = 0.92 + 0.16 * n
            else:
                base = light if (tx + ty) % 2 == 0 else dark
                k = 0.90 + 0.14 * hash01(tx, ty, 3) + 0.12 * (n - 0.5)
                if edge < 4:
                    k *= 0.93  # worn, slightly darker bevel next to the grout
            row += bytes(to_byte(c * k) for c in base)
        rows.append(bytes(row))
    return size, size, rows


def sandstone_wall_texture(size=256):
    """Ashlar masonry: 4 courses of blocks (1 m x 0.5 m at 2 m per repeat), staggered, thin mortar joints."""
    courses = 4
    course_h = size // courses
    block_w = size // 2
    stone, mortar = (220, 204, 174), (172, 160, 140)
    rows = []
    for y in range(size):
        row = bytearray()
        course = y // course_h
        ly = y % course_h
        shift = (block_w // 2) * (course % 2)
        for x in range(size):
            xs = (x + shift) % size
            block = xs // block_w
            lx = xs % block_w
            n = 0.6 * value_noise(x, y, 4, size // 4, 21) + 0.4 * value_noise(x, y, 16, size // 16, 22)
            if ly < 2 or lx < 2:
                base, k = mortar, 0.95 + 0.1 * n
            else:
                base = stone
                k = 0.92 + 0.1 * hash01(block, course, 5) + 0.1 * (n - 0.5)
            row += bytes(to_byte(c * k) for c in base)
        rows.append(bytes(row))
    return size, size, rows


# ----------------------------------------------------------------------------------------------- scene builder


class Material:
    def __init__(self, name, color, texture=None, uv_scale=1.0, double_sided=False, emission=None):
        self.name = name
        self.color = color  # linear RGB
        self.texture = texture  # PNG file name next to the .gltf, or None
        self.uv_scale = uv_scale  # metres per texture repeat for planar-mapped UVs
        self.double_sided = double_sided
        self.emission = emission  # None or (linear RGB factor, strength): radiance = factor * strength


class Primitive:
    def __init__(self, material):
        self.material = material
        self.positions, self.normals, self.uvs, self.indices = [], [], [], []


class Mesh:
    def __init__(self, name):
        self.name = name
        self.prims = {}  # material name -> Primitive, in insertion order


class SceneBuilder:
    def __init__(self, name):
        self.name = name
        self.materials = {}
        self.meshes = []
        self.cameras = []  # (name, eye, target, yfov)
        self.sun = None  # (intensity, direction)
        self.solids = []  # (name, [triangle position triples]) checked for watertightness
        self.camera_path = None  # hard scenes: camera keys written to path.json
        self.clip = {}  # camera name -> (znear, zfar) where the default (0.05, infinite) is not wanted
        self._solid = None

    def material(self, name, color, **kw):
        self.materials[name] = Material(name, color, **kw)

    def mesh(self, name):
        self.meshes.append(Mesh(name))

    def begin_solid(self, name):
        self._solid = (name, [])

    def end_solid(self):
        self.solids.append(self._solid)
        self._solid = None

    def _prim(self, material):
        mesh = self.meshes[-1]
        if material not in mesh.prims:
            mesh.prims[material] = Primitive(self.materials[material])
        return mesh.prims[material]

    @staticmethod
    def planar_uv(p, n, s):
        ax, ay, az = abs(n[0]), abs(n[1]), abs(n[2])
        if ay >= ax and ay >= az:
            return (p[0] / s, p[2] / s)
        if ax >= az:
            return (p[2] / s, -p[1] / s)
        return (p[0] / s, -p[1] / s)

    def polygon(self, material, pts, hint, normals=None, uvs=None):
        """Adds a convex planar polygon (vertices in cyclic order, either direction). It is wound
        counter-clockwise as seen from the side of `hint` (the outward / visible direction). Vertex normals
        default to the flat face normal; UVs default to a planar mapping scaled by the material."""
        pts = [clean(p) for p in pts]
        n = newell_normal(pts)
        if length(n) < 1e-12:
            raise ValueError("degenerate polygon %r" % (pts,))
        if dot(n, hint) < 0.0:
            pts = pts[::-1]
            normals = normals[::-1] if normals else None
            uvs = uvs[::-1] if uvs else None
            n = mul(n, -1.0)
        n = normalize(n)
        prim = self._prim(material)
        base = len(prim.positions)
        for i, p in enumerate(pts):
            prim.positions.append(p)
            prim.normals.append(clean(normalize(normals[i])) if normals else clean(n))
            uv = uvs[i] if uvs else self.planar_uv(p, n, prim.material.uv_scale)
            prim.uvs.append(tuple(round(c, 6) + 0.0 for c in uv))
        for i in range(1, len(pts) - 1):
            prim.indices += [base, base + i, base + i + 1]
            if self._solid is not None:
                self._solid[1].append((pts[0], pts[i], pts[i + 1]))

    def grid(self, material, pts, hint, normals=None, uvs=None):
        """A quad mesh with shared vertices: pts[j][i] rows of points (rows along v, columns along u)."""
        prim = self._prim(material)
        rows, cols = len(pts), len(pts[0])
        base = len(prim.positions)
        for j in range(rows):
            for i in range(cols):
                prim.positions.append(clean(pts[j][i]))
                prim.normals.append(clean(normalize(normals[j][i])))
                prim.uvs.append(tuple(round(c, 6) + 0.0 for c in uvs[j][i]))
        for j in range(rows - 1):
            for i in range(cols - 1):
                a, b = base + j * cols + i, base + j * cols + i + 1
                c, d = b + cols, a + cols
                quad = [a, b, c, d]
                p = [prim.positions[k] for k in quad]
                if dot(newell_normal(p), hint(i, j)) < 0.0:
                    quad = quad[::-1]
                prim.indices += [quad[0], quad[1], quad[2], quad[0], quad[2], quad[3]]

    def box(self, material, lo, hi, yaw=0.0, skip=()):
        """Axis-aligned (then rotated by `yaw` radians about +Y around its centre) box with outward faces.
        skip: faces to leave out, from '+x', '-x', '+y', '-y', '+z', '-z' (faces hidden inside other solids)."""
        c = mul(add(lo, hi), 0.5)
        h = mul(sub(hi, lo), 0.5)
        cy, sy = math.cos(yaw), math.sin(yaw)
        axes = [(cy, 0.0, -sy), (0.0, 1.0, 0.0), (sy, 0.0, cy)]
        for i, name in enumerate("xyz"):
            for sign in (1.0, -1.0):
                tag = ("+" if sign > 0 else "-") + name
                if tag in skip:
                    continue
                n = mul(axes[i], sign)
                u, v = axes[(i + 1) % 3], axes[(i + 2) % 3]
                hu, hv = h[(i + 1) % 3], h[(i + 2) % 3]
                fc = add(c, mul(n, h[i]))
                pts = [add(fc, add(mul(u, su * hu), mul(v, sv * hv))) for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
                self.polygon(material, pts, n)

    def prism(self, material, center, radius, y0, y1, sides=8, skip=()):
        """Regular prism about a vertical axis (flat faces aligned with X/Z for sides=8), outward faces."""
        ring = []
        for i in range(sides):
            a = 2.0 * math.pi * (i + 0.5) / sides
            ring.append((center[0] + radius * math.cos(a), center[2] + radius * math.sin(a)))
        for i in range(sides):
            (xa, za), (xb, zb) = ring[i], ring[(i + 1) % sides]
            out = (0.5 * (xa + xb) - center[0], 0.0, 0.5 * (za + zb) - center[2])
            self.polygon(material, [(xa, y0, za), (xb, y0, zb), (xb, y1, zb), (xa, y1, za)], out)
        if "top" not in skip:
            self.polygon(material, [(x, y1, z) for x, z in ring], (0.0, 1.0, 0.0))
        if "bottom" not in skip:
            self.polygon(material, [(x, y0, z) for x, z in ring], (0.0, -1.0, 0.0))

    def camera(self, name, eye, target, yfov, clip=None):
        self.cameras.append((name, eye, target, yfov))
        if clip is not None:
            self.clip[name] = clip

    # -------------------------------------------------------------------------------------- checks

    def triangles(self):
        for mesh in self.meshes:
            for prim in mesh.prims.values():
                for t in range(0, len(prim.indices), 3):
                    yield mesh, prim, prim.indices[t:t + 3]

    def check(self):
        errors = []
        for mesh, prim, tri in self.triangles():
            p = [prim.positions[i] for i in tri]
            g = cross(sub(p[1], p[0]), sub(p[2], p[0]))
            area = 0.5 * length(g)
            if area < 1e-8:
                errors.append("%s/%s: degenerate triangle %r" % (mesh.name, prim.material.name, p))
                continue
            g = normalize(g)
            for i in tri:
                if dot(g, prim.normals[i]) <= 0.05:
                    errors.append("%s/%s: triangle %r winds against its vertex normal %r"
                                  % (mesh.name, prim.material.name, p, prim.normals[i]))
                    break
        errors += self.coplanar_overlaps()
        for name, tris in self.solids:
            edges = {}
            for t in tris:
                for k in range(3):
                    e = (t[k], t[(k + 1) % 3])
                    edges[e] = edges.get(e, 0) + 1
            bad = [e for e, n in edges.items() if n != 1 or edges.get((e[1], e[0]), 0) != 1]
            if bad:
                errors.append("solid %s is not watertight / consistently wound: %d bad edges, e.g. %r"
                              % (name, len(bad), bad[:3]))
        for name, eye, target, yfov in self.cameras:
            q = look_rotation(sub(target, eye))
            if length(sub(quat_rotate(q, (0.0, 0.0, -1.0)), normalize(sub(target, eye)))) > 1e-6:
                errors.append("camera %s: rotation does not look at its target" % name)
        if self.sun is not None:
            q = look_rotation(self.sun[1])
            if length(sub(quat_rotate(q, (0.0, 0.0, -1.0)), normalize(self.sun[1]))) > 1e-6:
                errors.append("sun: rotation does not map -Z to its direction")
        if errors:
            for e in errors[:20]:
                print("SELF-CHECK FAILED: " + e, file=sys.stderr)
            raise SystemExit("%s: %d self-check errors" % (self.name, len(errors)))

    def coplanar_overlaps(self):
        """Pairs of triangles that lie in the same plane (either facing) and overlap with non-zero area:
        z-fighting for the rasterizer, ambiguous hits for the path tracer."""
        buckets = {}
        for mesh, prim, tri in self.triangles():
            p = [prim.positions[i] for i in tri]
            n = normalize(cross(sub(p[1], p[0]), sub(p[2], p[0])))
            axis = max(range(3), key=lambda k: abs(n[k]))
            if n[axis] < 0.0:
                n = mul(n, -1.0)
            key = (round(n[0], 4) + 0.0, round(n[1], 4) + 0.0, round(n[2], 4) + 0.0, round(dot(n, p[0]), 4) + 0.0)
            u, v = [k for k in range(3) if k != axis]
            q = [(c[u], c[v]) for c in p]
            if (q[1][0] - q[0][0]) * (q[2][1] - q[0][1]) - (q[1][1] - q[0][1]) * (q[2][0] - q[0][0]) < 0.0:
                q = q[::-1]
            box = (min(c[0] for c in q), min(c[1] for c in q), max(c[0] for c in q), max(c[1] for c in q))
            buckets.setdefault(key, []).append((q, box, "%s/%s" % (mesh.name, prim.material.name)))

        def clip(poly, a, b):
            out = []
            for i, c in enumerate(poly):
                d = poly[i - 1]
                side_c = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
                side_d = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0])
                if (side_c >= 0.0) != (side_d >= 0.0):
                    t = side_d / (side_d - side_c)
                    out.append((d[0] + t * (c[0] - d[0]), d[1] + t * (c[1] - d[1])))
                if side_c >= 0.0:
                    out.append(c)
            return out

        errors = []
        for key, items in buckets.items():
            items.sort(key=lambda it: it[1][0])
            for i, (qa, ba, na) in enumerate(items):
                for qb, bb, nb in items[i + 1:]:
                    if bb[0] >= ba[2] - 1e-6:
                        break
                    if bb[1] >= ba[3] - 1e-6 or ba[1] >= bb[3] - 1e-6:
                        continue
                    poly = qa
                    for k in range(3):
                        poly = clip(poly, qb[k], qb[(k + 1) % 3])
                        if len(poly) < 3:
                            break
                    area = 0.5 * abs(sum(poly[k][0] * poly[k - 1][1] - poly[k - 1][0] * poly[k][1]
                                         for k in range(len(poly)))) if len(poly) >= 3 else 0.0
                    if area > 1e-6:
                        errors.append("coplanar overlapping triangles (%s and %s) on plane %r" % (na, nb, key))
        return errors

    def stats(self):
        lo = [float("inf")] * 3
        hi = [-float("inf")] * 3
        per_mat = {}
        total = 0
        for mesh, prim, tri in self.triangles():
            total += 1
            per_mat[prim.material.name] = per_mat.get(prim.material.name, 0) + 1
            for i in tri:
                for k in range(3):
                    lo[k] = min(lo[k], prim.positions[i][k])
                    hi[k] = max(hi[k], prim.positions[i][k])
        return total, per_mat, lo, hi

    # -------------------------------------------------------------------------------------- glTF output

    def write(self, out_dir, textures, scale=1.0):
        """Writes <out_dir>/<name>.gltf and .bin; textures: {file name: (w, h, rows)} written as PNG. `scale`
        multiplies every length (positions, camera positions and clip planes) at output, after the checks."""
        os.makedirs(out_dir, exist_ok=True)
        binary = bytearray()
        views, accessors = [], []

        def view(data, target):
            while len(binary) % 4:
                binary.append(0)
            views.append({"buffer": 0, "byteOffset": len(binary), "byteLength": len(data), "target": target})
            binary.extend(data)
            return len(views) - 1

        def f32(v):
            """Shortest decimal that reads back as the same float32 (accessor min/max must match the data)."""
            x = struct.unpack("<f", struct.pack("<f", v))[0]
            for digits in range(1, 10):
                s = float("%.*g" % (digits, x))
                if struct.unpack("<f", struct.pack("<f", s))[0] == x:
                    return s + 0.0
            return x

        def vec_accessor(values, kind, with_bounds, factor=1.0):
            if factor != 1.0:
                values = [tuple(c * factor for c in v) for v in values]
            n = len(values[0])
            data = struct.pack("<%df" % (n * len(values)), *[c for v in values for c in v])
            acc = {"bufferView": view(data, 34962), "componentType": 5126, "count": len(values), "type": kind}
            if with_bounds:
                acc["min"] = [f32(min(v[k] for v in values)) for k in range(n)]
                acc["max"] = [f32(max(v[k] for v in values)) for k in range(n)]
            accessors.append(acc)
            return len(accessors) - 1

        def index_accessor(indices, vertex_count):
            if vertex_count < 65536:
                data, ctype = struct.pack("<%dH" % len(indices), *indices), 5123
            else:
                data, ctype = struct.pack("<%dI" % len(indices), *indices), 5125
            accessors.append({"bufferView": view(data, 34963), "componentType": ctype, "count": len(indices),
                              "type": "SCALAR"})
            return len(accessors) - 1

        images, tex_index = [], {}
        for m in self.materials.values():
            if m.texture and m.texture not in tex_index:
                tex_index[m.texture] = len(images)
                images.append({"name": os.path.splitext(m.texture)[0], "uri": m.texture})
        materials, mat_index = [], {}
        for m in self.materials.values():
            pbr = {"baseColorFactor": [round(c, 4) for c in m.color] + [1.0], "metallicFactor": 0.0,
                   "roughnessFactor": 1.0}
            if m.texture:
                pbr["baseColorTexture"] = {"index": tex_index[m.texture]}
            mat_index[m.name] = len(materials)
            mat = {"name": m.name, "pbrMetallicRoughness": pbr, "doubleSided": m.double_sided}
            if m.emission is not None:
                factor, strength = m.emission
                mat["emissiveFactor"] = [round(c, 6) for c in factor]
                if strength != 1.0:
                    mat["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}
            materials.append(mat)

        meshes = []
        for mesh in self.meshes:
            prims = []
            for prim in mesh.prims.values():
                attrs = {"POSITION": vec_accessor(prim.positions, "VEC3", True, scale),
                         "NORMAL": vec_accessor(prim.normals, "VEC3", False),
                         "TEXCOORD_0": vec_accessor(prim.uvs, "VEC2", False)}
                prims.append({"attributes": attrs, "indices": index_accessor(prim.indices, len(prim.positions)),
                              "material": mat_index[prim.material.name], "mode": 4})
            meshes.append({"name": mesh.name, "primitives": prims})

        # Camera nodes come first, in camera order, so "the first camera" is the same whether a loader walks the
        # cameras array or the scene's nodes.
        nodes, cameras = [], []
        for name, eye, target, yfov in self.cameras:
            persp = {"yfov": round(yfov, 6), "znear": 0.05}
            if name in self.clip:
                persp = {"yfov": round(yfov, 6), "znear": f32(self.clip[name][0] * scale),
                         "zfar": f32(self.clip[name][1] * scale)}
            cameras.append({"name": name, "type": "perspective", "perspective": persp})
            nodes.append({"name": "camera_" + name, "camera": len(cameras) - 1,
                          "rotation": [round(c, 7) + 0.0 for c in look_rotation(sub(target, eye))],
                          "translation": [f32(c * scale) if scale != 1.0 else round(c, 6) + 0.0 for c in eye]})
        lights = []
        if self.sun is not None:
            intensity, direction = self.sun
            lights.append({"name": "sun", "type": "directional", "color": [1.0, 1.0, 1.0], "intensity": intensity})
            nodes.append({"name": "sun", "rotation": [round(c, 7) + 0.0 for c in look_rotation(direction)],
                          "extensions": {"KHR_lights_punctual": {"light": 0}}})
        for i, mesh in enumerate(meshes):
            nodes.append({"name": mesh["name"], "mesh": i})

        doc = {"asset": {"version": "2.0", "generator": "deepgi tools/gen_scenes.py",
                         "copyright": "deepgi project, original work (same license as the project)"}}
        used = (["KHR_lights_punctual"] if lights else []) + \
            (["KHR_materials_emissive_strength"] if any("extensions" in m for m in materials) else [])
        if used:
            doc["extensionsUsed"] = used
        if lights:
            doc["extensions"] = {"KHR_lights_punctual": {"lights": lights}}
        doc["scene"] = 0
        doc["scenes"] = [{"name": self.name, "nodes": list(range(len(nodes)))}]
        doc["nodes"] = nodes
        doc["cameras"] = cameras
        doc["meshes"] = meshes
        doc["materials"] = materials
        if images:
            doc["samplers"] = [{"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497}]
            doc["images"] = images
            doc["textures"] = [{"sampler": 0, "source": i} for i in range(len(images))]
        doc["accessors"] = accessors
        doc["bufferViews"] = views
        doc["buffers"] = [{"uri": self.name + ".bin", "byteLength": len(binary)}]

        with open(os.path.join(out_dir, self.name + ".bin"), "wb") as f:
            f.write(bytes(binary))
        with open(os.path.join(out_dir, self.name + ".gltf"), "w", encoding="ascii", newline="\n") as f:
            f.write(json.dumps(doc, indent=1) + "\n")
        for fname, (w, h, rows) in sorted(textures.items()):
            write_png(os.path.join(out_dir, fname), w, h, rows)


# ----------------------------------------------------------------------------------------------- Cornell box

SUN_INTENSITY = 3.5  # W/m^2: a white (0.75) surface facing the sun has radiance 0.75/pi*3.5 = 0.84


def build_cornell_box():
    """Interior x in [-1, 1], y in [0, 2], z in [-1, 1], open towards +Z (the cameras look in from there).
    The shell is 0.1 m thick (walls, floor slab, roof) with a 0.8 x 0.8 m hole through the ceiling. It is the
    boundary of a union of cells of one grid, so every face is a grid-cell face, adjacent faces share their
    vertices exactly, the whole shell is one watertight solid, and sunlight can only enter through the hole."""
    b = SceneBuilder("cornell_box")
    b.material("white", (0.75, 0.75, 0.75))
    b.material("red", (0.63, 0.065, 0.05))
    b.material("green", (0.14, 0.45, 0.091))
    b.material("exterior", (0.5, 0.5, 0.5))
    b.material("block", (0.75, 0.75, 0.75))

    X = [-1.1, -1.0, -0.4, 0.4, 1.0, 1.1]
    Y = [-0.1, 0.0, 2.0, 2.1]
    Z = [-1.1, -1.0, -0.4, 0.4, 1.0]
    nx, ny, nz = len(X) - 1, len(Y) - 1, len(Z) - 1

    def solid(i, j, k):
        if not (0 <= i < nx and 0 <= j < ny and 0 <= k < nz):
            return False
        if 1 <= i <= 3 and j == 1 and k >= 1:
            return False  # the room
        if i == 2 and j == 2 and k == 2:
            return False  # the hole in the ceiling
        return True

    def material_for(p_lo, p_hi, n):
        inner = all(-1.0 <= p_lo[a] and p_hi[a] <= (2.0 if a == 1 else 1.0) for a in (0, 2)) and \
            0.0 <= p_lo[1] and p_hi[1] <= 2.0
        if inner and n == (1, 0, 0) and p_lo[0] == -1.0:
            return "red"
        if inner and n == (-1, 0, 0) and p_lo[0] == 1.0:
            return "green"
        outer = p_lo[0] == p_hi[0] == -1.1 or p_lo[0] == p_hi[0] == 1.1 or p_lo[1] == p_hi[1] == -0.1 or \
            p_lo[1] == p_hi[1] == 2.1 or p_lo[2] == p_hi[2] == -1.1
        return "exterior" if outer else "white"

    b.mesh("shell")
    b.begin_solid("cornell shell")
    for i in range(nx):
        for j in range(ny):
            for k in range(nz):
                if not solid(i, j, k):
                    continue
                lo, hi = (X[i], Y[j], Z[k]), (X[i + 1], Y[j + 1], Z[k + 1])
                for axis in range(3):
                    for sign in (-1, 1):
                        nb = [i, j, k]
                        nb[axis] += sign
                        if solid(*nb):
                            continue
                        n = [0, 0, 0]
                        n[axis] = sign
                        plane = hi[axis] if sign > 0 else lo[axis]
                        u, v = (axis + 1) % 3, (axis + 2) % 3
                        pts = []
                        for su, sv in ((0, 0), (1, 0), (1, 1), (0, 1)):
                            p = [0.0, 0.0, 0.0]
                            p[axis] = plane
                            p[u] = hi[u] if su else lo[u]
                            p[v] = hi[v] if sv else lo[v]
                            pts.append(tuple(p))
                        flo = tuple(min(p[a] for p in pts) for a in range(3))
                        fhi = tuple(max(p[a] for p in pts) for a in range(3))
                        b.polygon(material_for(flo, fhi, tuple(n)), pts, tuple(n))
    b.end_solid()

    # Two white blocks, sunk 5 cm into the floor slab (no face coplanar with the floor).
    b.mesh("blocks")
    b.begin_solid("tall block")
    b.box("block", (-0.66, -0.05, -0.63), (-0.06, 1.2, -0.03), yaw=math.radians(18.0), skip=("-y",))
    b.end_solid()
    b.begin_solid("short block")
    b.box("block", (0.06, -0.05, 0.06), (0.66, 0.6, 0.66), yaw=math.radians(-17.0), skip=("-y",))
    b.end_solid()
    b.solids = [s for s in b.solids if s[0] == "cornell shell"]  # the blocks are open at their hidden bottom

    b.sun = (SUN_INTENSITY, sun_travel_direction(110.0, 68.0))
    b.camera("front", (0.0, 1.0, 3.9), (0.0, 1.0, 0.0), 0.72)
    b.camera("corner", (0.85, 1.65, 0.8), (-0.45, 0.5, -0.8), 1.1)
    return b, {}


# ----------------------------------------------------------------------------------------------- atrium

# Plan: courtyard x in [-8, 8], z in [-5, 5]; on each long side (z > 0 and z < 0) an arcade facade 0.6 m thick
# (|z| in [5, 5.6]), a gallery 2.4 m deep and a back wall (|z| in [8, 8.5]); end walls at |x| in [8, 8.6].
HALF_L = 8.0
FACADE_Z0, FACADE_Z1 = 5.0, 5.6
BACK_Z0, BACK_Z1 = 8.0, 8.5
END_X0, END_X1 = 8.0, 8.6
EMBED = 0.2  # how far pieces reach into the end walls
BAYS = 6
PIER_HALF = 0.3
ARCH_SEGMENTS = 12
Y_BOTTOM = -0.2  # facades and walls reach below the floor
S1 = 2.5  # lower springing
H1 = 4.1  # upper gallery floor level
P = H1 + 1.0  # parapet top
S2 = 6.2  # upper springing
HT = 8.4  # facade top
ROOF = (7.9, 8.2)
SLAB = (3.8, H1)
BACK_TOP, END_TOP = 8.6, 8.8
BAY_W = 2.0 * HALF_L / BAYS
PIERS = [-HALF_L + k * BAY_W for k in range(BAYS + 1)]  # pier centres; the first and last are engaged in the end walls


def arcade_facade(b, side):
    """The two-storey arcade on one long side as one closed solid: piers, semicircular arches (ARCH_SEGMENTS
    segments, smooth normals on the intrados), a parapet in the upper storey. The courtyard face and the gallery
    face share one 2D layout so every edge is shared by exactly two faces (checked)."""
    zf, zb = side * FACADE_Z0, side * FACADE_Z1
    n_front, n_back = (0.0, 0.0, -side), (0.0, 0.0, side)
    rows = [Y_BOTTOM, S1, H1, P, S2, HT]
    b.begin_solid("facade %+d" % side)
    for k in range(BAYS):
        left = PIERS[k] if k > 0 else -HALF_L - EMBED
        right = PIERS[k + 1] if k < BAYS - 1 else HALF_L + EMBED
        a, e = PIERS[k] + PIER_HALF, PIERS[k + 1] - PIER_HALF
        c, r = 0.5 * (a + e), 0.5 * (e - a)
        ax, ang = [], []
        for i in range(ARCH_SEGMENTS + 1):
            t = math.pi * (ARCH_SEGMENTS - i) / ARCH_SEGMENTS  # from the left springing (pi) to the right (0)
            ang.append(t)
            ax.append(a if i == 0 else e if i == ARCH_SEGMENTS else c + r * math.cos(t))
        lift = [0.0 if i in (0, ARCH_SEGMENTS) else r * math.sin(ang[i]) for i in range(ARCH_SEGMENTS + 1)]
        y1 = [S1 + h for h in lift]
        y2 = [S2 + h for h in lift]

        faces2d = []  # polygons in (x, y)
        for x0, x1 in ((left, a), (e, right)):
            for j in range(len(rows) - 1):
                faces2d.append([(x0, rows[j]), (x1, rows[j]), (x1, rows[j + 1]), (x0, rows[j + 1])])
        for i in range(ARCH_SEGMENTS):
            xl, xr = ax[i], ax[i + 1]
            faces2d.append([(xl, y1[i]), (xr, y1[i + 1]), (xr, H1), (xl, H1)])
            faces2d.append([(xl, H1), (xr, H1), (xr, P), (xl, P)])
            faces2d.append([(xl, y2[i]), (xr, y2[i + 1]), (xr, HT), (xl, HT)])
        for poly in faces2d:
            b.polygon("sandstone", [(x, y, zf) for x, y in poly], n_front)
            b.polygon("sandstone", [(x, y, zb) for x, y in poly], n_back)

        # Top (split at every column of the faces below it) and the pier bottoms.
        cols = [left] + ax + [right]
        for i in range(len(cols) - 1):
            b.polygon("sandstone", [(cols[i], HT, zf), (cols[i + 1], HT, zf), (cols[i + 1], HT, zb),
                                    (cols[i], HT, zb)], (0.0, 1.0, 0.0))
        for x0, x1 in ((left, a), (e, right)):
            b.polygon("sandstone", [(x0, Y_BOTTOM, zf), (x1, Y_BOTTOM, zf), (x1, Y_BOTTOM, zb),
                                    (x0, Y_BOTTOM, zb)], (0.0, -1.0, 0.0))
        # Pier sides facing into the openings.
        for x, nx in ((a, 1.0), (e, -1.0)):
            for y0, y1_ in ((Y_BOTTOM, S1), (P, S2)):
                b.polygon("sandstone", [(x, y0, zf), (x, y1_, zf), (x, y1_, zb), (x, y0, zb)], (nx, 0.0, 0.0))
        # Parapet top, split like the band below it.
        for i in range(ARCH_SEGMENTS):
            b.polygon("sandstone", [(ax[i], P, zf), (ax[i + 1], P, zf), (ax[i + 1], P, zb), (ax[i], P, zb)],
                      (0.0, 1.0, 0.0))
        # Arch intrados, normals towards the arch centre.
        for ys, s in ((y1, S1), (y2, S2)):
            for i in range(ARCH_SEGMENTS):
                na = (-math.cos(ang[i]), -math.sin(ang[i]), 0.0)
                nb = (-math.cos(ang[i + 1]), -math.sin(ang[i + 1]), 0.0)
                hint = normalize(add(na, nb))
                b.polygon("sandstone", [(ax[i], ys[i], zf), (ax[i + 1], ys[i + 1], zf), (ax[i + 1], ys[i + 1], zb),
                                        (ax[i], ys[i], zb)], hint, normals=[na, nb, nb, na])
        # Ends, buried in the end walls.
        if k in (0, BAYS - 1):
            x, nx = (left, -1.0) if k == 0 else (right, 1.0)
            for j in range(len(rows) - 1):
                b.polygon("sandstone", [(x, rows[j], zf), (x, rows[j + 1], zf), (x, rows[j + 1], zb),
                                        (x, rows[j], zb)], (nx, 0.0, 0.0))
    b.end_solid()


def zrange(side, z0, z1):
    """World z interval of the local interval [z0, z1] (distances from the centre line) on one side."""
    return (z0, z1) if side > 0 else (-z1, -z0)


def banner(b, material, x, side, top, length, width=1.2, cols=4, rows=10):
    """A cloth banner hanging in front of a pier, bowing gently towards the courtyard, with a V-cut bottom.
    Double-sided; its normal faces the courtyard."""
    pts, nrm, uvs = [], [], []
    z_face = side * 4.68
    for j in range(rows + 1):
        t = j / rows
        prow, nrow, urow = [], [], []
        for i in range(cols + 1):
            u = i / cols
            drop = length + 0.35 * abs(2.0 * u - 1.0)  # the edges hang lower: V-cut tail
            bow = 0.16 * t * t  # swings out towards the courtyard lower down
            px = x + (u - 0.5) * width
            py = top - t * drop
            pz = z_face - side * bow
            # Analytic normal: d/du x d/dt of the surface, oriented to the courtyard.
            du = (width, -t * 0.35 * (2.0 if u > 0.5 else -2.0 if u < 0.5 else 0.0), 0.0)
            dt = (0.0, -drop, -side * 0.32 * t)
            n = normalize(cross(du, dt))
            if n[2] * -side < 0.0:
                n = mul(n, -1.0)
            prow.append((px, py, pz))
            nrow.append(n)
            urow.append((u, t))
        pts.append(prow)
        nrm.append(nrow)
        uvs.append(urow)
    b.grid(material, pts, lambda i, j: (0.0, 0.0, -side), normals=nrm, uvs=uvs)


def build_atrium():
    b = SceneBuilder("atrium")
    b.material("stone_floor", (1.0, 1.0, 1.0), texture="stone_floor.png", uv_scale=4.0)
    b.material("sandstone", (1.0, 1.0, 1.0), texture="sandstone_wall.png", uv_scale=2.0)
    b.material("plaster", (0.7, 0.66, 0.58))
    b.material("stone_trim", (0.66, 0.62, 0.55))
    b.material("roof_tiles", (0.42, 0.2, 0.14))
    b.material("banner_red", (0.7, 0.1, 0.1), double_sided=True)
    b.material("banner_blue", (0.1, 0.15, 0.7), double_sided=True)
    b.material("banner_green", (0.1, 0.55, 0.15), double_sided=True)
    b.material("banner_yellow", (0.75, 0.6, 0.08), double_sided=True)

    # Floor: one tessellated sheet under courtyard and galleries, reaching 0.1 m into the walls.
    b.mesh("floor")
    n = 18
    ext = HALF_L + 0.1
    coords = [-ext + 2.0 * ext * i / n for i in range(n + 1)]
    pts = [[(x, 0.0, z) for x in coords] for z in coords]
    b.grid("stone_floor", pts, lambda i, j: (0.0, 1.0, 0.0),
           normals=[[(0.0, 1.0, 0.0)] * (n + 1)] * (n + 1),
           uvs=[[(p[0] / 4.0, p[2] / 4.0) for p in row] for row in pts])

    b.mesh("arcades")
    for side in (1, -1):
        arcade_facade(b, side)

    b.mesh("walls")
    for side in (1, -1):
        z0, z1 = zrange(side, BACK_Z0, BACK_Z1)
        # Back wall: its ends are buried in the end walls, its bottom under the floor.
        b.box("sandstone", (-HALF_L - 0.3, Y_BOTTOM, z0), (HALF_L + 0.3, BACK_TOP, z1), skip=("-x", "+x", "-y"))
    for sx in (1, -1):
        x0, x1 = (END_X0, END_X1) if sx > 0 else (-END_X1, -END_X0)
        b.box("sandstone", (x0, Y_BOTTOM, -BACK_Z1 - 0.1), (x1, END_TOP, BACK_Z1 + 0.1), skip=("-y",))

    b.mesh("slabs")
    for side in (1, -1):
        z0, z1 = zrange(side, FACADE_Z1 - 0.3, BACK_Z0 + 0.25)  # reaches into the facade and the back wall
        lo_x, hi_x = -HALF_L - EMBED, HALF_L + EMBED
        hidden = ("-x", "+x", "-z", "+z")
        # Upper gallery floor (its top is the floor of the upper gallery, its bottom the lower gallery ceiling).
        b.box("stone_floor", (lo_x, SLAB[0], z0), (hi_x, SLAB[1], z1), skip=hidden + ("-y",))
        b.box("plaster", (lo_x, SLAB[0], z0), (hi_x, SLAB[1], z1), skip=hidden + ("+y",))
        # Roof over the upper gallery.
        b.box("roof_tiles", (lo_x, ROOF[0], z0), (hi_x, ROOF[1], z1), skip=hidden + ("-y",))
        b.box("plaster", (lo_x, ROOF[0], z0), (hi_x, ROOF[1], z1), skip=hidden + ("+y",))

    b.mesh("trim")
    for side in (1, -1):
        # String course between the storeys and cornice under the facade top, both cut into the facade face.
        z0, z1 = zrange(side, FACADE_Z0 - 0.18, FACADE_Z0 + 0.2)
        b.box("stone_trim", (-HALF_L - EMBED, 3.8, z0), (HALF_L + EMBED, 4.05, z1),
              skip=("-x", "+x", "+z" if side > 0 else "-z"))
        z0, z1 = zrange(side, FACADE_Z0 - 0.25, FACADE_Z0 + 0.25)
        b.box("stone_trim", (-HALF_L - EMBED, 7.95, z0), (HALF_L + EMBED, 8.3, z1),
              skip=("-x", "+x", "+z" if side > 0 else "-z"))
        for k, xc in enumerate(PIERS):
            lo_x = -HALF_L - EMBED if k == 0 else xc - 0.4
            hi_x = HALF_L + EMBED if k == BAYS else xc + 0.4
            skip_end = ("-x",) if k == 0 else ("+x",) if k == BAYS else ()
            z0, z1 = zrange(side, FACADE_Z0 - 0.1, FACADE_Z1 + 0.1)
            b.box("stone_trim", (lo_x, -0.1, z0), (hi_x, 0.35, z1), skip=skip_end + ("-y",))  # plinth
            lo_x = -HALF_L - EMBED if k == 0 else xc - 0.38
            hi_x = HALF_L + EMBED if k == BAYS else xc + 0.38
            z0, z1 = zrange(side, FACADE_Z0 - 0.08, FACADE_Z1 + 0.08)
            for s in (S1, S2):
                b.box("stone_trim", (lo_x, s - 0.22, z0), (hi_x, s, z1), skip=skip_end)  # impost

    # End walls: string course and cornice continued around them (a little higher and deeper than the ones on
    # the facades, so no faces coincide where they cross), and pilasters.
    for sx in (1, -1):
        def xr(x0, x1):
            return (x0, x1) if sx > 0 else (-x1, -x0)
        z = FACADE_Z0 + 0.1  # reaches into the facades
        x0, x1 = xr(END_X0 - 0.2, END_X0 + 0.2)
        b.box("stone_trim", (x0, 3.78, -z), (x1, 4.07, z), skip=("+x" if sx > 0 else "-x", "-z", "+z"))
        x0, x1 = xr(END_X0 - 0.25, END_X0 + 0.2)
        b.box("stone_trim", (x0, 7.93, -z), (x1, 8.32, z), skip=("+x" if sx > 0 else "-x", "-z", "+z"))
        x0, x1 = xr(END_X0 - 0.18, END_X0 + 0.2)
        for zc in (-2.5, 2.5):
            b.box("sandstone", (x0, -0.1, zc - 0.35), (x1, 8.1, zc + 0.35), skip=("+x" if sx > 0 else "-x", "-y", "+y"))

    # Fountain in the middle of the courtyard.
    b.mesh("fountain")
    b.prism("stone_trim", (0.0, 0.0, 0.0), 1.5, -0.1, 0.5, skip=("bottom",))
    b.prism("stone_trim", (0.0, 0.0, 0.0), 0.3, 0.3, 1.55, skip=("bottom", "top"))
    b.prism("stone_trim", (0.0, 0.0, 0.0), 0.75, 1.5, 1.7)

    b.mesh("banners")
    colours = {1: ["banner_red", "banner_blue", "banner_green", "banner_yellow"],
               -1: ["banner_yellow", "banner_green", "banner_blue", "banner_red"]}
    for side in (1, -1):
        for slot, k in enumerate((1, 2, 4, 5)):
            banner(b, colours[side][slot], PIERS[k], side, top=7.9, length=4.2)

    # Sun from the south-west-ish (-Z, a bit -X), 67 degrees high: the -Z arcade shades the -Z part of the
    # courtyard and its own galleries; the +Z arcade and its galleries get sun through the arches.
    b.sun = (SUN_INTENSITY, sun_travel_direction(205.0, 67.0))
    b.camera("courtyard", (-6.6, 1.7, -1.2), (6.0, 3.9, 0.8), 1.1)
    b.camera("gallery", (-5.2, 1.6, 7.3), (1.2, 2.0, 1.0), 1.05)
    b.camera("overview", (-11.5, 15.5, -4.0), (1.0, 1.0, 0.5), 0.95)
    textures = {"stone_floor.png": stone_floor_texture(), "sandstone_wall.png": sandstone_wall_texture()}
    return b, textures


# ----------------------------------------------------------------------------------------------- hard GI scenes

# Small scenes where screen-space GI is known to fail (issue 9; ../shared/docs/gi-accuracy.md), written to
# assets/hard/<name>/ at scale 1 and as <name>_s0.001 / <name>_s1000 with every length multiplied (the sun's
# irradiance and the emission are unchanged, so the true images are the same). Each is the boundary of a union of
# cells of one grid, like the Cornell shell: one watertight, consistently wound solid whose faces share vertices,
# so light enters a room only through the openings made on purpose (a closed room is exactly dark).

HARD_SCALES = (1.0, 0.001, 1000.0)
HARD_SUN = 10.0  # W/m^2


def in_box(p, box):
    lo, hi = box
    return all(lo[a] < p[a] < hi[a] for a in range(3))


class CellScene:
    """A solid shell around `rooms` (boxes of air) with `solids` (boxes of matter inside rooms, e.g. a pillar)
    and `holes` (boxes of air cut through the shell, e.g. a skylight). `outer` is the shell's outer box."""

    def __init__(self, outer):
        self.outer = outer
        self.rooms, self.solids, self.holes = [], [], []

    def is_solid(self, c):
        if not in_box(c, self.outer) or any(in_box(c, h) for h in self.holes):
            return False
        if any(in_box(c, s) for s in self.solids):
            return True
        return not any(in_box(c, r) for r in self.rooms)

    def in_room(self, c):
        return any(in_box(c, r) for r in self.rooms) and not any(in_box(c, s) for s in self.solids)

    def build(self, b, material_for):
        """Emits every face between a solid cell and an air cell, facing the air. material_for(face_lo,
        face_hi, normal, into_room) names its material."""
        grid = [set(), set(), set()]
        for box in [self.outer] + self.rooms + self.solids + self.holes:
            for a in range(3):
                lo = max(box[0][a], self.outer[0][a])
                hi = min(box[1][a], self.outer[1][a])
                grid[a].update((round(lo, 6), round(hi, 6)))
        X, Y, Z = [sorted(g) for g in grid]
        coords = (X, Y, Z)
        n = (len(X) - 1, len(Y) - 1, len(Z) - 1)
        centre = lambda i, j, k: (0.5 * (X[i] + X[i + 1]), 0.5 * (Y[j] + Y[j + 1]), 0.5 * (Z[k] + Z[k + 1]))
        solid = {}
        for i in range(n[0]):
            for j in range(n[1]):
                for k in range(n[2]):
                    solid[(i, j, k)] = self.is_solid(centre(i, j, k))
        b.begin_solid(b.name + " shell")
        for (i, j, k), s in sorted(solid.items()):
            if not s:
                continue
            idx = (i, j, k)
            lo = (X[i], Y[j], Z[k])
            hi = (X[i + 1], Y[j + 1], Z[k + 1])
            for axis in range(3):
                for sign in (-1, 1):
                    nb = list(idx)
                    nb[axis] += sign
                    if solid.get(tuple(nb), False):
                        continue
                    into_room = tuple(nb) in solid and self.in_room(centre(*nb))
                    normal = [0.0, 0.0, 0.0]
                    normal[axis] = float(sign)
                    plane = hi[axis] if sign > 0 else lo[axis]
                    u, v = (axis + 1) % 3, (axis + 2) % 3
                    pts = []
                    for su, sv in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        p = [0.0, 0.0, 0.0]
                        p[axis] = plane
                        p[u] = hi[u] if su else lo[u]
                        p[v] = hi[v] if sv else lo[v]
                        pts.append(tuple(p))
                    flo = tuple(min(p[a] for p in pts) for a in range(3))
                    fhi = tuple(max(p[a] for p in pts) for a in range(3))
                    b.polygon(material_for(flo, fhi, tuple(normal), into_room), pts, tuple(normal))
        b.end_solid()


def room_material(flo, fhi, n, into_room):
    """Default interior naming: floors, ceilings and walls; everything facing out of the rooms is `exterior`."""
    if not into_room:
        return "exterior"
    return "floor" if n[1] > 0 else "ceiling" if n[1] < 0 else "wall"


def standard_materials(b, albedo=0.7):
    b.material("floor", (albedo, albedo, albedo))
    b.material("wall", (albedo, albedo, albedo))
    b.material("ceiling", (albedo, albedo, albedo))
    b.material("exterior", (0.5, 0.5, 0.5))


def build_offscreen_light():
    """6 x 3 x 6 m room (x, z in -3..3). A 3 x 1.1 m skylight (x -1.5..1.5, z 1..2.1) lets the sun (75 deg
    high, travelling towards +Z) onto the floor at z ~ 1.8..2.9, behind the camera. The camera stands near the
    centre and looks into the far (-X, -Z) corner: everything it sees is lit only by light bounced off that patch
    (its direct image is black)."""
    b = SceneBuilder("offscreen_light")
    standard_materials(b, 0.7)
    b.mesh("room")
    cs = CellScene(((-3.2, -0.2, -3.2), (3.2, 3.2, 3.2)))
    cs.rooms.append(((-3.0, 0.0, -3.0), (3.0, 3.0, 3.0)))
    cs.holes.append(((-1.5, 2.9, 1.0), (1.5, 3.3, 2.1)))
    cs.build(b, room_material)
    b.sun = (HARD_SUN, sun_travel_direction(180.0, 75.0))
    b.camera("corner", (0.6, 1.6, 0.4), (-3.0, 0.9, -3.0), 1.0, clip=(0.02, 50.0))
    return b


def build_thin_wall():
    """Two 4 x 3 x 5 m rooms side by side, x -4..-0.025 (dark) and 0.025..4 (lit), separated by a 5 cm wall
    (x -0.025..0.025, floor to ceiling). The lit room has a 1.4 x 1.6 m skylight (x 1.2..2.6, z -0.8..0.8) and a sun
    patch on its floor; the dark room is closed, so its true radiance is exactly 0. Camera `dark` stands in the
    dark room looking at the thin wall (its second layer sees the lit room behind it); `lit` is its mirror image
    in the lit room, for the lit side's indirect level."""
    b = SceneBuilder("thin_wall")
    standard_materials(b, 0.7)
    b.mesh("rooms")
    cs = CellScene(((-4.2, -0.2, -2.7), (4.2, 3.2, 2.7)))
    cs.rooms.append(((-4.0, 0.0, -2.5), (-0.025, 3.0, 2.5)))
    cs.rooms.append(((0.025, 0.0, -2.5), (4.0, 3.0, 2.5)))
    cs.holes.append(((1.2, 2.9, -0.8), (2.6, 3.3, 0.8)))
    cs.build(b, room_material)
    b.sun = (HARD_SUN, sun_travel_direction(270.0, 70.0))  # sun in the -X sky: the patch moves towards +X
    b.camera("dark", (-3.6, 1.5, 2.1), (0.0, 1.0, -1.2), 1.0, clip=(0.02, 50.0))
    b.camera("lit", (3.6, 1.5, 2.1), (0.0, 1.0, -1.2), 1.0, clip=(0.02, 50.0))
    return b


def build_hidden_emitter():
    """5 x 2.6 x 7 m closed room (x -2.5..2.5, z -2.5..4.5), no sun. A full-height pillar 1.2 x 0.8 m at the
    centre hides an emissive floor panel (1 x 1 m, 3 cm high, top emitting radiance 8, z -1.6..-0.6) behind it
    from the camera at z = 4; the panel lights the back wall, the ceiling and the pillar's back. The camera's
    second layer sees the panel; a camera path (path.json) moves sideways until the panel comes into view."""
    b = SceneBuilder("hidden_emitter")
    standard_materials(b, 0.7)
    b.material("emitter", (0.8, 0.8, 0.8), emission=((1.0, 0.9, 0.7), 8.0))
    b.mesh("room")
    cs = CellScene(((-2.7, -0.2, -2.7), (2.7, 2.8, 4.7)))
    cs.rooms.append(((-2.5, 0.0, -2.5), (2.5, 2.6, 4.5)))
    cs.solids.append(((-0.6, -1.0, -0.4), (0.6, 3.0, 0.4)))
    panel = ((-0.5, -1.0, -1.6), (0.5, 0.03, -0.6))
    cs.solids.append(panel)

    def material(flo, fhi, n, into_room):
        if into_room and n[1] > 0 and flo[1] == 0.03:
            return "emitter"
        return room_material(flo, fhi, n, into_room)
    cs.build(b, material)
    b.sun = (0.0, sun_travel_direction(0.0, 60.0))  # a light of zero intensity: the default sun stays off
    b.camera("front", (0.0, 1.6, 4.0), (0.0, 1.1, -2.5), 1.0, clip=(0.02, 50.0))
    b.camera_path = {"camera": "front", "frames": 24, "reference_frames": [12, 24],
                     "keys": [{"eye": (0.0, 1.6, 4.0), "target": (0.0, 1.1, -2.5)},
                              {"eye": (2.0, 1.6, 4.0), "target": (0.8, 1.1, -2.5)}]}
    return b


def build_sun_patch():
    """5 x 2.6 x 5 m room (x, z in -2.5..2.5). A 1.4 x 1.4 m skylight (x, z -0.7..0.7) over a red-brown rug
    (2.4 x 2.4 m, 1 cm high) on the floor; the sun, 80 deg high, lands on the rug. Walls, ceiling and floor are lit
    only by light bounced off the rug. The camera stands low in the (+X, +Z) corner looking up into the opposite
    top corner: it sees the rug, the floor, both far walls and the ceiling (the skylight shows black sky)."""
    b = SceneBuilder("sun_patch")
    standard_materials(b, 0.7)
    b.material("rug", (0.7, 0.35, 0.2))
    b.mesh("room")
    cs = CellScene(((-2.7, -0.2, -2.7), (2.7, 2.8, 2.7)))
    cs.rooms.append(((-2.5, 0.0, -2.5), (2.5, 2.6, 2.5)))
    cs.solids.append(((-1.2, -1.0, -1.2), (1.2, 0.01, 1.2)))
    cs.holes.append(((-0.7, 2.5, -0.7), (0.7, 2.9, 0.7)))

    def material(flo, fhi, n, into_room):
        if into_room and n[1] > 0 and flo[1] == 0.01:
            return "rug"
        return room_material(flo, fhi, n, into_room)
    cs.build(b, material)
    b.sun = (HARD_SUN, sun_travel_direction(200.0, 80.0))
    b.camera("corner", (2.2, 0.8, 2.2), (-2.5, 1.4, -2.5), 1.3, clip=(0.02, 50.0))
    return b


def build_occluder():
    """An open court under a black sky: an 8 x 6 m floor (x -4..4, z -3..3), a 3 m wall along its back (z = -3,
    facing +Z) and, 1 m in front of it, a black 0.8 m parapet (z -2.1..-2.0). The sun (about 31 deg high, travelling
    towards -Z) lights the floor, the wall and the parapet's front. The camera stands high in front, looking down at
    the floor before the parapet and the wall above it: the floor there sees the wall's lower part only through the
    parapet, which the camera sees over. A gather that counts what it sees on screen without asking whether the
    receiver sees it too (the visibility march) brings the wall's light onto that floor."""
    b = SceneBuilder("occluder")
    standard_materials(b, 0.8)
    b.material("black", (0.02, 0.02, 0.02))
    b.mesh("court")
    b.box("floor", (-4.0, -0.2, -3.0), (4.0, 0.0, 3.0))
    b.box("wall", (-4.0, 0.0, -3.2), (4.0, 3.0, -3.0), skip=("-y",))
    b.box("black", (-4.0, 0.0, -2.1), (4.0, 0.8, -2.0), skip=("-y",))
    b.sun = (HARD_SUN, sun_travel_direction(0.0, 31.0))
    b.camera("above", (0.0, 5.0, 3.5), (0.0, 0.0, -1.8), 0.9, clip=(0.02, 50.0))
    return b


def build_furnace():
    """Closed 4 x 3 x 4 m box (x, z in -2..2) with a 0.8 m block on the floor; every surface has albedo 0.5 and
    emission 0.1, so the radiance is exactly 0.1 / (1 - 0.5) = 0.2 everywhere. No sun (a zero-intensity light keeps
    the renderer's default sun off)."""
    b = SceneBuilder("furnace")
    b.material("grey", (0.5, 0.5, 0.5), emission=((0.1, 0.1, 0.1), 1.0))
    b.mesh("box")
    cs = CellScene(((-2.2, -0.2, -2.2), (2.2, 3.2, 2.2)))
    cs.rooms.append(((-2.0, 0.0, -2.0), (2.0, 3.0, 2.0)))
    cs.solids.append(((-0.9, -1.0, -0.9), (-0.1, 0.8, -0.1)))
    cs.build(b, lambda flo, fhi, n, into_room: "grey")
    b.sun = (0.0, sun_travel_direction(0.0, 60.0))
    b.camera("inside", (1.7, 2.4, 1.7), (-1.2, 0.4, -1.0), 1.2, clip=(0.02, 50.0))
    return b


HARD_BUILDERS = (build_offscreen_light, build_thin_wall, build_hidden_emitter, build_sun_patch, build_furnace,
                 build_occluder)


def scale_suffix(scale):
    return "" if scale == 1.0 else "_s%g" % scale


def write_camera_path(path, out_dir, scale):
    """path.json beside the scene: camera keys (eye, target) the bench interpolates linearly over `frames`."""
    doc = dict(path)
    doc["keys"] = [{"eye": [f32_round(c * scale) for c in k["eye"]],
                    "target": [f32_round(c * scale) for c in k["target"]]} for k in path["keys"]]
    with open(os.path.join(out_dir, "path.json"), "w", encoding="ascii", newline="\n") as f:
        f.write(json.dumps(doc, indent=1) + "\n")


def f32_round(v):
    return float("%.7g" % v) + 0.0


# ----------------------------------------------------------------------------------------------- main


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "assets"),
                    help="assets directory (default: the repository's assets/)")
    args = ap.parse_args()
    for build in (build_cornell_box, build_atrium):
        b, textures = build()
        b.check()
        report(b, os.path.join(args.out, b.name), textures)
    for build in HARD_BUILDERS:
        b = build()
        b.check()
        base = b.name
        for scale in HARD_SCALES:
            b.name = base + scale_suffix(scale)
            out_dir = os.path.join(args.out, "hard", b.name)
            b.write(out_dir, {}, scale)
            if b.camera_path:
                write_camera_path(b.camera_path, out_dir, scale)
            print("%s: scale %g, %d triangles, wrote %s" % (b.name, scale, sum(1 for _ in b.triangles()),
                                                           os.path.normpath(out_dir)))


def report(b, out_dir, textures):
    total, per_mat, lo, hi = b.stats()
    b.write(out_dir, textures)
    print("%s: %d triangles, bounds [%.2f %.2f %.2f] .. [%.2f %.2f %.2f], %d closed solids checked"
          % (b.name, total, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2], len(b.solids)))
    for name, count in per_mat.items():
        print("    %-14s %6d triangles" % (name, count))
    print("    cameras: " + ", ".join(c[0] for c in b.cameras))
    print("    sun: intensity %.2f W/m^2, travels along (%.4f, %.4f, %.4f)" % ((b.sun[0],) + tuple(b.sun[1])))
    print("    wrote " + os.path.normpath(out_dir))


if __name__ == "__main__":
    main()
