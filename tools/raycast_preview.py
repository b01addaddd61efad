#!/usr/bin/env python3
"""Tiny stdlib-only ray caster for eyeballing the generated glTF scenes (not part of the renderer).

    /usr/bin/python3 tools/raycast_preview.py assets/atrium/atrium.gltf --camera courtyard -o /tmp/view.png

Shading: albedo (factor x texture, nearest texel) x (sun irradiance x n.l x shadow / pi + a crude ambient term),
then gamma 2.2. Single-sided faces seen from behind are painted magenta (a winding bug, or a view from outside),
misses are sky blue. Supports only what tools/gen_scenes.py writes (mesh nodes without transforms, float
attributes, uint16/uint32 indices, PNG textures with any filter, RGB or RGBA 8-bit).
"""

import argparse
import json
import math
import os
import struct
import sys
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gen_scenes import write_png, quat_rotate  # noqa: E402


def read_png(path):
    with open(path, "rb") as f:
        data = f.read()
    pos, idat, w = 8, b"", 0
    while pos < len(data):
        n, tag = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if tag == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
            if depth != 8 or ctype not in (2, 6):
                raise ValueError("unsupported PNG " + path)
            ch = 3 if ctype == 2 else 4
        elif tag == b"IDAT":
            idat += body
        pos += 12 + n
    raw = zlib.decompress(idat)
    stride = w * ch
    rows, prev = [], bytearray(stride)
    for y in range(h):
        ft = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - ch] if i >= ch else 0
            b = prev[i]
            c = prev[i - ch] if i >= ch else 0
            if ft == 1:
                line[i] = (line[i] + a) & 255
            elif ft == 2:
                line[i] = (line[i] + b) & 255
            elif ft == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif ft == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    lut = [((v / 255.0 + 0.055) / 1.055) ** 2.4 if v > 10 else v / 255.0 / 12.92 for v in range(256)]
    return w, h, [[(lut[r[x * ch]], lut[r[x * ch + 1]], lut[r[x * ch + 2]]) for x in range(w)] for r in rows]


def load(path):
    doc = json.load(open(path))
    base = os.path.dirname(path)
    buf = open(os.path.join(base, doc["buffers"][0]["uri"]), "rb").read()

    def acc(i):
        a = doc["accessors"][i]
        v = doc["bufferViews"][a["bufferView"]]
        off = v.get("byteOffset", 0) + a.get("byteOffset", 0)
        n = {"SCALAR": 1, "VEC2": 2, "VEC3": 3}[a["type"]]
        fmt = {5126: "f", 5123: "H", 5125: "I"}[a["componentType"]]
        vals = struct.unpack_from("<%d%s" % (a["count"] * n, fmt), buf, off)
        return [vals[k:k + n] for k in range(0, len(vals), n)] if n > 1 else list(vals)

    images = [read_png(os.path.join(base, im["uri"])) for im in doc.get("images", [])]
    mats = []
    for m in doc["materials"]:
        pbr = m.get("pbrMetallicRoughness", {})
        tex = pbr.get("baseColorTexture")
        img = images[doc["textures"][tex["index"]]["source"]] if tex else None
        mats.append((tuple(pbr.get("baseColorFactor", [1, 1, 1, 1])[:3]), img, m.get("doubleSided", False)))
    tris = []  # (p0, p1, p2, n0, n1, n2, uv0, uv1, uv2, material)
    for node in doc["nodes"]:
        if "mesh" not in node:
            continue
        for prim in doc["meshes"][node["mesh"]]["primitives"]:
            P, N, T = (acc(prim["attributes"][k]) for k in ("POSITION", "NORMAL", "TEXCOORD_0"))
            idx = acc(prim["indices"])
            for t in range(0, len(idx), 3):
                a, b, c = idx[t:t + 3]
                tris.append((P[a], P[b], P[c], N[a], N[b], N[c], T[a], T[b], T[c], prim["material"]))
    cams = {}
    for node in doc["nodes"]:
        if "camera" in node:
            cam = doc["cameras"][node["camera"]]
            cams[cam["name"]] = (node["translation"], node["rotation"], cam["perspective"]["yfov"])
    first_cam = doc["cameras"][0]["name"]
    sun = None
    for node in doc["nodes"]:
        if "KHR_lights_punctual" in node.get("extensions", {}):
            light = doc["extensions"]["KHR_lights_punctual"]["lights"][node["extensions"]["KHR_lights_punctual"]["light"]]
            sun = (light["intensity"], quat_rotate(node["rotation"], (0.0, 0.0, -1.0)))
    return tris, mats, cams, first_cam, sun


class BVH:
    def __init__(self, tris):
        self.tris = tris
        self.nodes = []  # (lo, hi, left, right, start, count)
        cent = [tuple((t[0][k] + t[1][k] + t[2][k]) / 3.0 for k in range(3)) for t in tris]
        self.order = list(range(len(tris)))
        self._build(cent, 0, len(tris))
        self.prep = []
        for t in tris:
            p0, p1, p2 = t[0], t[1], t[2]
            e1 = (p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2])
            e2 = (p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2])
            self.prep.append((p0, e1, e2))

    def _build(self, cent, s, e):
        lo = [min(self.tris[self.order[i]][v][k] for i in range(s, e) for v in range(3)) for k in range(3)]
        hi = [max(self.tris[self.order[i]][v][k] for i in range(s, e) for v in range(3)) for k in range(3)]
        me = len(self.nodes)
        self.nodes.append(None)
        if e - s <= 4:
            self.nodes[me] = (lo, hi, -1, -1, s, e - s)
            return me
        clo = [min(cent[self.order[i]][k] for i in range(s, e)) for k in range(3)]
        chi = [max(cent[self.order[i]][k] for i in range(s, e)) for k in range(3)]
        ax = max(range(3), key=lambda k: chi[k] - clo[k])
        sub = sorted(self.order[s:e], key=lambda i: cent[i][ax])
        self.order[s:e] = sub
        m = (s + e) // 2
        l = self._build(cent, s, m)
        r = self._build(cent, m, e)
        self.nodes[me] = (lo, hi, l, r, s, 0)
        return me

    def hit(self, o, d, tmax, any_hit=False):
        inv = tuple(1.0 / c if c != 0.0 else 1e30 for c in d)
        best, bi, bu, bv = tmax, -1, 0.0, 0.0
        stack = [0]
        nodes, prep, order = self.nodes, self.prep, self.order
        ox, oy, oz = o
        dx, dy, dz = d
        while stack:
            lo, hi, l, r, s, cnt = nodes[stack.pop()]
            t0, t1 = 0.0, best
            for k in range(3):
                a = (lo[k] - o[k]) * inv[k]
                b = (hi[k] - o[k]) * inv[k]
                if a > b:
                    a, b = b, a
                if a > t0:
                    t0 = a
                if b < t1:
                    t1 = b
                if t0 > t1:
                    break
            else:
                if cnt == 0:
                    stack.append(l)
                    stack.append(r)
                    continue
                for i in order[s:s + cnt]:
                    p0, e1, e2 = prep[i]
                    px, py, pz = dy * e2[2] - dz * e2[1], dz * e2[0] - dx * e2[2], dx * e2[1] - dy * e2[0]
                    det = e1[0] * px + e1[1] * py + e1[2] * pz
                    if -1e-12 < det < 1e-12:
                        continue
                    idet = 1.0 / det
                    tx, ty, tz = ox - p0[0], oy - p0[1], oz - p0[2]
                    u = (tx * px + ty * py + tz * pz) * idet
                    if u < 0.0 or u > 1.0:
                        continue
                    qx, qy, qz = ty * e1[2] - tz * e1[1], tz * e1[0] - tx * e1[2], tx * e1[1] - ty * e1[0]
                    v = (dx * qx + dy * qy + dz * qz) * idet
                    if v < 0.0 or u + v > 1.0:
                        continue
                    t = (e2[0] * qx + e2[1] * qy + e2[2] * qz) * idet
                    if 1e-5 < t < best:
                        best, bi, bu, bv = t, i, u, v
                        if any_hit:
                            return best, bi, bu, bv
        return best, bi, bu, bv


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("gltf")
    ap.add_argument("--camera", default=None)
    ap.add_argument("--width", type=int, default=192)
    ap.add_argument("--height", type=int, default=108)
    ap.add_argument("--ambient", type=float, default=0.12)
    ap.add_argument("-o", "--output", required=True)
    args = ap.parse_args()
    tris, mats, cams, first, sun = load(args.gltf)
    bvh = BVH(tris)
    pos, rot, yfov = cams[args.camera or first]
    irr, sdir = sun
    to_sun = tuple(-c for c in sdir)
    W, H = args.width, args.height
    th = math.tan(0.5 * yfov)
    rows = []
    for y in range(H):
        row = bytearray()
        for x in range(W):
            ndc = (2.0 * (x + 0.5) / W - 1.0, 1.0 - 2.0 * (y + 0.5) / H)
            d = quat_rotate(rot, (ndc[0] * th * W / H, ndc[1] * th, -1.0))
            n_ = math.sqrt(sum(c * c for c in d))
            d = tuple(c / n_ for c in d)
            t, i, u, v = bvh.hit(pos, d, 1e30)
            if i < 0:
                col = (0.45, 0.65, 0.95)
            else:
                tri = tris[i]
                p0, e1, e2 = bvh.prep[i]
                g = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0])
                base, img, double = mats[tri[9]]
                w0 = 1.0 - u - v
                n = tuple(w0 * tri[3][k] + u * tri[4][k] + v * tri[5][k] for k in range(3))
                back = g[0] * d[0] + g[1] * d[1] + g[2] * d[2] > 0.0
                if back and not double:
                    col = (1.0, 0.0, 1.0)
                else:
                    if back:
                        n = tuple(-c for c in n)
                    nl = math.sqrt(sum(c * c for c in n))
                    n = tuple(c / nl for c in n)
                    alb = base
                    if img:
                        tu = w0 * tri[6][0] + u * tri[7][0] + v * tri[8][0]
                        tv = w0 * tri[6][1] + u * tri[7][1] + v * tri[8][1]
                        iw, ih, px = img
                        tex = px[int(math.floor(tv * ih)) % ih][int(math.floor(tu * iw)) % iw]
                        alb = tuple(base[k] * tex[k] for k in range(3))
                    ndl = sum(n[k] * to_sun[k] for k in range(3))
                    e = 0.0
                    if ndl > 0.0:
                        hp = tuple(pos[k] + t * d[k] + n[k] * 1e-3 for k in range(3))
                        if bvh.hit(hp, to_sun, 1e30, any_hit=True)[1] < 0:
                            e = irr * ndl
                    amb = args.ambient * (0.55 + 0.25 * n[1] + 0.2 * abs(sum(n[k] * d[k] for k in range(3))))
                    col = tuple(alb[k] * (e / math.pi + amb) for k in range(3))
            row += bytes(max(0, min(255, int(255.0 * max(c, 0.0) ** (1 / 2.2) + 0.5))) for c in col)
        rows.append(bytes(row))
    write_png(args.output, W, H, rows)


if __name__ == "__main__":
    main()
