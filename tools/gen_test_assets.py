#!/usr/bin/env python3
"""Generate the loader test assets of assets/test/: an OBJ room with MTL, a quantized mesh, texture transforms.

Python 3 standard library only; deterministic (rerunning rewrites byte-identical files).

    /usr/bin/python3 tools/gen_test_assets.py [--out assets/test]

writes
    obj_room/room.obj + room.mtl + textures/checker.png + textures/fence_mask.png
        A 4 x 4 m floor with three walls (open top and front, so the default sun lights it), metres, +Y up:
        Kd colours, a backslash map_Kd path (textures\\checker.png, as Crytek Sponza writes them), an emissive
        panel (Ke), and a fence quad cut out by map_d (vertical stripes, half of it transparent).
    quant/plain.gltf            a UV sphere (radius 0.5, centre (0, 0.5, 0)) on a floor, float attributes, checker texture
    quant/quantized.gltf        the same with KHR_mesh_quantization: SHORT positions dequantized by the node
                                transform, normalized BYTE normals, normalized USHORT texture coordinates
    texture_transform/transformed.gltf  a quad whose UVs span (0,0)-(0.5,0.5), KHR_texture_transform
                                (offset, rotation, scale, texCoord 1) on its base-colour texture
    texture_transform/baked.gltf  the same quad with the transform applied to TEXCOORD_0 here (the rotation
                                as the sample model TextureTransformTest checks it, computed in this script), no
                                extension: the independent answer
    materials/normal_wall.gltf  a 4 x 4 m wall (z = 0, facing +Z, u along +X, v down) under a grazing directional
                                light (80 deg from the normal, from +X, irradiance 3 W/m^2 facing it) with a constant
                                normal texture tilting the normal 30 deg towards +X (tangent space (sin 30, 0, cos 30)),
                                glTF TANGENT (1, 0, 0, 1); camera 'front' 3 m in front of it
    materials/normal_wall_generated.gltf  the same without TANGENT (tangents generated at load)
    materials/metal_spheres.gltf a row of five gold spheres (metallic 1, roughness 0.1, 0.3, 0.5, 0.7, 1.0) and a
                                row of five grey dielectric ones (the same roughness) on a grey floor, one sun
The Draco and meshopt versions of quant/plain.gltf are written by the tests (tests/test_scene_formats.cpp) with
the encoders of libdraco and libmeshoptimizer, which Python cannot call.
"""

import argparse
import base64
import json
import math
import os
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gen_scenes import write_png  # noqa: E402  (the project's stdlib PNG writer)


def checker_rows(size, cells, a, b):
    rows = []
    for y in range(size):
        row = bytearray()
        for x in range(size):
            c = a if ((x * cells // size) + (y * cells // size)) % 2 == 0 else b
            row += bytes(c)
        rows.append(bytes(row))
    return rows


# ----------------------------------------------------------------------------------------------- OBJ room

OBJ_ROOM_MTL = """# deepgi loader test room (tools/gen_test_assets.py)
newmtl floor
Kd 0.7 0.7 0.7
Ka 0 0 0
Ks 0 0 0
d 1

newmtl red_wall
Kd 0.63 0.065 0.05

newmtl checker_wall
Kd 1 1 1
map_Kd textures\\checker.png

newmtl panel
Kd 0.5 0.5 0.5
Ke 4 3 2

newmtl fence
Kd 0.2 0.4 0.8
map_d textures\\fence_mask.png
"""


def obj_room():
    lines = ["# deepgi loader test room (tools/gen_test_assets.py): floor, three walls, emissive panel, masked fence",
             "mtllib room.mtl"]
    v, vt, vn = [], [], []

    def quad(name, mtl, corners, uvs, normal):
        base_v, base_t, base_n = len(v), len(vt), len(vn)
        v.extend(corners)
        vt.extend(uvs)
        vn.append(normal)
        lines.append("o " + name)
        lines.append("usemtl " + mtl)
        lines.append("f " + " ".join("%d/%d/%d" % (base_v + i + 1, base_t + i + 1, base_n + 1) for i in range(4)))

    full = [(0, 0), (1, 0), (1, 1), (0, 1)]
    # CCW seen from the side the normal points to
    quad("floor", "floor", [(-2, 0, 2), (2, 0, 2), (2, 0, -2), (-2, 0, -2)], full, (0, 1, 0))
    quad("back_wall", "floor", [(-2, 0, -2), (2, 0, -2), (2, 2, -2), (-2, 2, -2)], full, (0, 0, 1))
    quad("left_wall", "red_wall", [(-2, 0, 2), (-2, 0, -2), (-2, 2, -2), (-2, 2, 2)], full, (1, 0, 0))
    quad("right_wall", "checker_wall", [(2, 0, -2), (2, 0, 2), (2, 2, 2), (2, 2, -2)], full, (-1, 0, 0))
    quad("panel", "panel", [(-0.5, 0.8, -1.99), (0.5, 0.8, -1.99), (0.5, 1.6, -1.99), (-0.5, 1.6, -1.99)], full,
         (0, 0, 1))
    quad("fence", "fence", [(-1.5, 0, 0.5), (-0.5, 0, 0.5), (-0.5, 1, 0.5), (-1.5, 1, 0.5)], full, (0, 0, 1))
    out = lines[:2]
    out += ["v %g %g %g" % p for p in v]
    out += ["vt %g %g" % t for t in vt]
    out += ["vn %g %g %g" % n for n in vn]
    out += lines[2:]
    return "\n".join(out) + "\n"


def fence_mask_rows(size=64, stripes=8):
    """Grey PNG rows as RGB: white (opaque) in the even vertical stripes, black (cut out) in the odd ones."""
    rows = []
    for _ in range(size):
        row = bytearray()
        for x in range(size):
            g = 255 if (x * stripes // size) % 2 == 0 else 0
            row += bytes((g, g, g))
        rows.append(bytes(row))
    return rows


# ----------------------------------------------------------------------------------------------- glTF helpers


class Gltf:
    def __init__(self):
        self.j = {"asset": {"version": "2.0", "generator": "deepgi tools/gen_test_assets.py"},
                  "buffers": [], "bufferViews": [], "accessors": [], "meshes": [], "nodes": [], "scenes": [],
                  "materials": [], "textures": [], "images": [], "samplers": []}
        self.bin = bytearray()

    def accessor(self, fmt, values, comp_type, type_name, count, normalized=False, minmax=None, stride=None):
        while len(self.bin) % 4:
            self.bin.append(0)
        off = len(self.bin)
        data = b"".join(struct.pack("<" + fmt, *v) if isinstance(v, tuple) else struct.pack("<" + fmt, v)
                        for v in values)
        self.bin += data
        view = {"buffer": 0, "byteOffset": off, "byteLength": len(data)}
        self.j["bufferViews"].append(view)
        a = {"bufferView": len(self.j["bufferViews"]) - 1, "componentType": comp_type, "type": type_name,
             "count": count}
        if normalized:
            a["normalized"] = True
        if minmax:
            a["min"], a["max"] = minmax
        self.j["accessors"].append(a)
        return len(self.j["accessors"]) - 1

    def texture(self, uri):
        if not self.j["samplers"]:
            self.j["samplers"].append({"magFilter": 9729, "minFilter": 9987, "wrapS": 10497, "wrapT": 10497})
        self.j["images"].append({"uri": uri})
        self.j["textures"].append({"source": len(self.j["images"]) - 1, "sampler": 0})
        return len(self.j["textures"]) - 1

    def write(self, path):
        while len(self.bin) % 4:
            self.bin.append(0)
        j = dict(self.j)
        j["buffers"] = [{"byteLength": len(self.bin),
                         "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(self.bin)).decode()}]
        j = {k: val for k, val in j.items() if val != []}
        with open(path, "w") as f:
            json.dump(j, f, indent=1, sort_keys=True)
            f.write("\n")


FLOAT, BYTE, SHORT, USHORT, UINT = 5126, 5120, 5122, 5123, 5125


def sphere_and_floor(rings=12, segments=24):
    """Vertices (position, normal, uv) and triangle indices: a UV sphere of radius 0.5 at (0, 0.5, 0) and a
    3 x 3 m floor quad at y = 0."""
    verts, idx = [], []
    for r in range(rings + 1):
        theta = math.pi * r / rings
        for s in range(segments + 1):
            phi = 2 * math.pi * s / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))
            p = (0.5 * n[0], 0.5 + 0.5 * n[1], 0.5 * n[2])
            verts.append((p, n, (s / segments, r / rings)))
    for r in range(rings):
        for s in range(segments):
            a = r * (segments + 1) + s
            b = a + segments + 1
            # CCW seen from outside; no degenerate triangles at the poles (Draco would drop them)
            if r > 0:
                idx += [a, a + 1, b]
            if r < rings - 1:
                idx += [a + 1, b + 1, b]
    base = len(verts)
    for p, uv in (((-1.5, 0, 1.5), (0, 2)), ((1.5, 0, 1.5), (2, 2)), ((1.5, 0, -1.5), (2, 0)), ((-1.5, 0, -1.5), (0, 0))):
        verts.append((p, (0, 1, 0), uv))
    idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return verts, idx


def quant_scenes(out):
    verts, idx = sphere_and_floor()
    lo = [min(v[0][c] for v in verts) for c in range(3)]
    hi = [max(v[0][c] for v in verts) for c in range(3)]
    for quantized in (False, True):
        g = Gltf()
        tex = g.texture("checker.png")
        g.j["materials"].append({"name": "checker", "pbrMetallicRoughness": {
            "baseColorTexture": {"index": tex}, "metallicFactor": 0, "roughnessFactor": 1}})
        node = {"mesh": 0, "name": "sphere_and_floor"}
        if not quantized:
            pos = g.accessor("3f", [v[0] for v in verts], FLOAT, "VEC3", len(verts), minmax=(lo, hi))
            nrm = g.accessor("3f", [v[1] for v in verts], FLOAT, "VEC3", len(verts))
            uv = g.accessor("2f", [v[2] for v in verts], FLOAT, "VEC2", len(verts))
        else:
            # positions: SHORT in [-32767, 32767] over the bounds, the node's scale and translation map them back
            centre = [(lo[c] + hi[c]) / 2 for c in range(3)]
            half = [(hi[c] - lo[c]) / 2 for c in range(3)]
            q = [tuple(int(round((v[0][c] - centre[c]) / half[c] * 32767)) if half[c] > 0 else 0 for c in range(3))
                 for v in verts]
            pos = g.accessor("3h", q, SHORT, "VEC3", len(verts),
                             minmax=([min(p[c] for p in q) for c in range(3)], [max(p[c] for p in q) for c in range(3)]))
            node["translation"] = centre
            node["scale"] = [h / 32767 if h > 0 else 1.0 for h in half]
            # normals: normalized BYTE (x, y, z, pad), 4-byte elements. The node scale is not uniform, and normals
            # go through its inverse transpose, so the stored normal is scale * n (renormalised), which maps back to n.
            def qn(c):
                return max(-127, min(127, int(round(c * 127))))
            sc = node["scale"]
            stored = []
            for v in verts:
                m = [v[1][c] * sc[c] for c in range(3)]
                ln = math.sqrt(sum(c * c for c in m))
                stored.append(tuple(qn(c / ln) for c in m) + (0,))
            nrm = g.accessor("4b", stored, BYTE, "VEC3", len(verts), normalized=True)
            g.j["bufferViews"][-1]["byteStride"] = 4
            # texture coordinates in [0, 2]: normalized USHORT holds [0, 1], so the floor's 2 becomes 1 and a
            # KHR_texture_transform scale of 2 restores it
            uv = g.accessor("2H", [tuple(int(round(c / 2 * 65535)) for c in v[2]) for v in verts], USHORT, "VEC2",
                            len(verts), normalized=True)
            g.j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {
                "KHR_texture_transform": {"scale": [2, 2]}}
            g.j["extensionsUsed"] = ["KHR_mesh_quantization", "KHR_texture_transform"]
            g.j["extensionsRequired"] = ["KHR_mesh_quantization"]
        ind = g.accessor("H", idx, USHORT, "SCALAR", len(idx))
        g.j["meshes"].append({"name": "sphere_and_floor", "primitives": [
            {"attributes": {"POSITION": pos, "NORMAL": nrm, "TEXCOORD_0": uv}, "indices": ind, "material": 0}]})
        g.j["nodes"].append(node)
        g.j["nodes"].append({"name": "cam", "camera": 0, "translation": [0, 1.6, 2.6],
                             "rotation": quat_x(-0.45)})
        g.j["cameras"] = [{"name": "cam", "type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.05}}]
        g.j["scenes"].append({"nodes": [0, 1]})
        g.j["scene"] = 0
        g.write(os.path.join(out, "quantized.gltf" if quantized else "plain.gltf"))
    write_png(os.path.join(out, "checker.png"), 64, 64, checker_rows(64, 8, (230, 200, 60), (40, 60, 160)))


def quat_x(angle):
    return [math.sin(angle / 2), 0.0, 0.0, math.cos(angle / 2)]


# ----------------------------------------------------------------------------------------------- texture transform


def transform_matrix(offset, rotation, scale):
    """KHR_texture_transform's translation * rotation * scale as rows of a 3x3 matrix. The rotation turns the uvs
    counter-clockwise in glTF's V-down uv space, u' = cos u + sin v, v' = -sin u + cos v: what the sample model
    TextureTransformTest, Blender, Babylon.js and three.js do. The spec's GLSL listing has the opposite sign
    (KhronosGroup/glTF issue 1563)."""
    c, s = math.cos(rotation), math.sin(rotation)
    t = [[1, 0, offset[0]], [0, 1, offset[1]], [0, 0, 1]]
    r = [[c, s, 0], [-s, c, 0], [0, 0, 1]]
    k = [[scale[0], 0, 0], [0, scale[1], 0], [0, 0, 1]]

    def mm(a, b):
        return [[sum(a[i][m] * b[m][j] for m in range(3)) for j in range(3)] for i in range(3)]
    return mm(mm(t, r), k)


def texture_transform_scenes(out):
    offset, rotation, scale = (0.25, 0.125), 0.3, (1.5, 1.25)
    m = transform_matrix(offset, rotation, scale)
    corners = [(-1, 0, 1), (1, 0, 1), (1, 0, -1), (-1, 0, -1)]
    uv1 = [(0, 0.5), (0.5, 0.5), (0.5, 0), (0, 0)]
    uv0_unused = [(0.9, 0.9)] * 4  # TEXCOORD_0 of the transformed file: the texCoord override must skip it
    baked = [tuple(m[i][0] * u + m[i][1] * v + m[i][2] for i in range(2)) for u, v in uv1]
    for name in ("transformed", "baked"):
        g = Gltf()
        tex = g.texture("checker.png")
        info = {"index": tex}
        pos = g.accessor("3f", corners, FLOAT, "VEC3", 4, minmax=([-1, 0, -1], [1, 0, 1]))
        nrm = g.accessor("3f", [(0, 1, 0)] * 4, FLOAT, "VEC3", 4)
        attrs = {"POSITION": pos, "NORMAL": nrm}
        if name == "transformed":
            attrs["TEXCOORD_0"] = g.accessor("2f", uv0_unused, FLOAT, "VEC2", 4)
            attrs["TEXCOORD_1"] = g.accessor("2f", uv1, FLOAT, "VEC2", 4)
            info["extensions"] = {"KHR_texture_transform": {"offset": list(offset), "rotation": rotation,
                                                            "scale": list(scale), "texCoord": 1}}
            g.j["extensionsUsed"] = ["KHR_texture_transform"]
        else:
            attrs["TEXCOORD_0"] = g.accessor("2f", baked, FLOAT, "VEC2", 4)
        ind = g.accessor("H", [0, 1, 2, 0, 2, 3], USHORT, "SCALAR", 6)
        g.j["materials"].append({"name": "checker", "pbrMetallicRoughness": {"baseColorTexture": info, "metallicFactor": 0}})
        g.j["meshes"].append({"primitives": [{"attributes": attrs, "indices": ind, "material": 0}]})
        g.j["nodes"] = [{"mesh": 0}, {"name": "top", "camera": 0, "translation": [0, 2.2, 0], "rotation": quat_x(-math.pi / 2)}]
        g.j["cameras"] = [{"name": "top", "type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.05}}]
        g.j["scenes"] = [{"nodes": [0, 1]}]
        g.j["scene"] = 0
        g.write(os.path.join(out, name + ".gltf"))
    write_png(os.path.join(out, "checker.png"), 64, 64, checker_rows(64, 8, (250, 250, 250), (20, 20, 20)))


# ----------------------------------------------------------------------------------------------- materials

NORMAL_TILT_DEG = 30.0   # the normal texture's tilt towards +X (the tangent)
GRAZING_DEG = 80.0       # the light's angle from the wall's geometric normal


def normal_texel():
    t = math.radians(NORMAL_TILT_DEG)
    n = (math.sin(t), 0.0, math.cos(t))
    return tuple(int(round((c * 0.5 + 0.5) * 255)) for c in n)


def quat_y(angle):
    return [0.0, math.sin(angle / 2), 0.0, math.cos(angle / 2)]


def sun_node(g, direction_angle_y, intensity):
    """A KHR_lights_punctual directional light whose -Z is turned about +Y by the angle."""
    g.j.setdefault("extensions", {})["KHR_lights_punctual"] = {
        "lights": [{"name": "sun", "type": "directional", "intensity": intensity, "color": [1, 1, 1]}]}
    g.j["extensionsUsed"] = sorted(set(g.j.get("extensionsUsed", []) + ["KHR_lights_punctual"]))
    g.j["nodes"].append({"name": "sun", "rotation": quat_y(direction_angle_y), "extensions": {"KHR_lights_punctual": {"light": 0}}})
    return len(g.j["nodes"]) - 1


def normal_wall_scenes(out):
    for name, with_tangent in (("normal_wall", True), ("normal_wall_generated", False)):
        g = Gltf()
        g.j["samplers"].append({"magFilter": 9728, "minFilter": 9728, "wrapS": 10497, "wrapT": 10497})
        g.j["images"].append({"uri": "tilted_normal.png"})
        g.j["textures"].append({"source": 0, "sampler": 0})
        corners = [(-2, -2, 0), (2, -2, 0), (2, 2, 0), (-2, 2, 0)]
        uvs = [(0, 1), (1, 1), (1, 0), (0, 0)]  # u along +X, v down (glTF: (0, 0) top-left)
        attrs = {"POSITION": g.accessor("3f", corners, FLOAT, "VEC3", 4, minmax=([-2, -2, 0], [2, 2, 0])),
                 "NORMAL": g.accessor("3f", [(0, 0, 1)] * 4, FLOAT, "VEC3", 4),
                 "TEXCOORD_0": g.accessor("2f", uvs, FLOAT, "VEC2", 4)}
        if with_tangent:
            attrs["TANGENT"] = g.accessor("4f", [(1, 0, 0, 1)] * 4, FLOAT, "VEC4", 4)
        ind = g.accessor("H", [0, 1, 2, 0, 2, 3], USHORT, "SCALAR", 6)
        g.j["materials"].append({"name": "tilted", "normalTexture": {"index": 0, "scale": 1.0},
                                 "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.8, 0.8, 1], "metallicFactor": 0,
                                                          "roughnessFactor": 1}})
        g.j["meshes"].append({"name": "wall", "primitives": [{"attributes": attrs, "indices": ind, "material": 0}]})
        g.j["nodes"].append({"mesh": 0, "name": "wall"})
        g.j["nodes"].append({"name": "front", "camera": 0, "translation": [0, 0, 3]})
        g.j["cameras"] = [{"name": "front", "type": "perspective", "perspective": {"yfov": 0.9, "znear": 0.05}}]
        sun = sun_node(g, math.radians(GRAZING_DEG), 3.0)
        g.j["scenes"].append({"nodes": [0, 1, sun]})
        g.j["scene"] = 0
        g.write(os.path.join(out, name + ".gltf"))
    write_png(os.path.join(out, "tilted_normal.png"), 4, 4, [bytes(normal_texel()) * 4] * 4)


def sphere(centre, radius, rings=16, segments=32):
    verts, idx = [], []
    for r in range(rings + 1):
        theta = math.pi * r / rings
        for k in range(segments + 1):
            phi = 2 * math.pi * k / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), math.sin(theta) * math.sin(phi))
            verts.append((tuple(centre[c] + radius * n[c] for c in range(3)), n, (k / segments, r / rings)))
    for r in range(rings):
        for k in range(segments):
            a = r * (segments + 1) + k
            b = a + segments + 1
            if r > 0:
                idx += [a, a + 1, b]
            if r < rings - 1:
                idx += [a + 1, b + 1, b]
    return verts, idx


def metal_spheres_scene(out):
    g = Gltf()
    roughness = [0.1, 0.3, 0.5, 0.7, 1.0]
    prims_nodes = []

    def mesh(name, verts, idx, material):
        lo = [min(v[0][c] for v in verts) for c in range(3)]
        hi = [max(v[0][c] for v in verts) for c in range(3)]
        attrs = {"POSITION": g.accessor("3f", [v[0] for v in verts], FLOAT, "VEC3", len(verts), minmax=(lo, hi)),
                 "NORMAL": g.accessor("3f", [v[1] for v in verts], FLOAT, "VEC3", len(verts)),
                 "TEXCOORD_0": g.accessor("2f", [v[2] for v in verts], FLOAT, "VEC2", len(verts))}
        ind = g.accessor("H", idx, USHORT, "SCALAR", len(idx))
        g.j["meshes"].append({"name": name, "primitives": [{"attributes": attrs, "indices": ind, "material": material}]})
        g.j["nodes"].append({"mesh": len(g.j["meshes"]) - 1, "name": name})
        prims_nodes.append(len(g.j["nodes"]) - 1)

    for row, (kind, base, metallic) in enumerate((("gold", [1.0, 0.78, 0.34, 1], 1), ("grey", [0.5, 0.5, 0.5, 1], 0))):
        for i, r in enumerate(roughness):
            g.j["materials"].append({"name": "%s_r%.1f" % (kind, r), "pbrMetallicRoughness": {
                "baseColorFactor": base, "metallicFactor": metallic, "roughnessFactor": r}})
            v, ix = sphere(((i - 2) * 1.0, 0.4, -row * 1.0), 0.4)
            mesh("%s_sphere_%d" % (kind, i), v, ix, len(g.j["materials"]) - 1)
    g.j["materials"].append({"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.6, 0.6, 1],
                                                                       "metallicFactor": 0, "roughnessFactor": 0.8}})
    floor = [((-3.5, 0, 2), (0, 1, 0), (0, 1)), ((3.5, 0, 2), (0, 1, 0), (1, 1)), ((3.5, 0, -2.5), (0, 1, 0), (1, 0)),
             ((-3.5, 0, -2.5), (0, 1, 0), (0, 0))]
    mesh("floor", floor, [0, 1, 2, 0, 2, 3], len(g.j["materials"]) - 1)
    g.j["nodes"].append({"name": "front", "camera": 0, "translation": [0, 1.6, 3.4], "rotation": quat_x(-0.38)})
    g.j["cameras"] = [{"name": "front", "type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.05}}]
    cam = len(g.j["nodes"]) - 1
    # The sun from behind-left and above: highlights on the spheres' front faces.
    g.j.setdefault("extensions", {})["KHR_lights_punctual"] = {
        "lights": [{"name": "sun", "type": "directional", "intensity": 3.0}]}
    g.j["extensionsUsed"] = ["KHR_lights_punctual"]
    # -Z turned to (0.35, -0.6, -0.72) roughly: pitch down 37 deg, then yaw 25 deg
    qx, qy = quat_x(-0.65), quat_y(0.45)
    # q = qy * qx
    w1, x1, y1, z1 = qy[3], qy[0], qy[1], qy[2]
    w2, x2, y2, z2 = qx[3], qx[0], qx[1], qx[2]
    q = [w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2, w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
         w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2, w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2]
    g.j["nodes"].append({"name": "sun", "rotation": q, "extensions": {"KHR_lights_punctual": {"light": 0}}})
    g.j["scenes"].append({"nodes": prims_nodes + [cam, len(g.j["nodes"]) - 1]})
    g.j["scene"] = 0
    g.write(os.path.join(out, "metal_spheres.gltf"))


def materials_scenes(out):
    normal_wall_scenes(out)
    metal_spheres_scene(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "assets", "test"))
    args = ap.parse_args()
    room = os.path.join(args.out, "obj_room")
    os.makedirs(os.path.join(room, "textures"), exist_ok=True)
    with open(os.path.join(room, "room.obj"), "w") as f:
        f.write(obj_room())
    with open(os.path.join(room, "room.mtl"), "w") as f:
        f.write(OBJ_ROOM_MTL)
    write_png(os.path.join(room, "textures", "checker.png"), 64, 64, checker_rows(64, 4, (255, 255, 255), (60, 60, 60)))
    write_png(os.path.join(room, "textures", "fence_mask.png"), 64, 64, fence_mask_rows())
    for sub, fn in (("quant", quant_scenes), ("texture_transform", texture_transform_scenes),
                    ("materials", materials_scenes)):
        d = os.path.join(args.out, sub)
        os.makedirs(d, exist_ok=True)
        fn(d)
    print("wrote", os.path.normpath(args.out))


if __name__ == "__main__":
    main()
