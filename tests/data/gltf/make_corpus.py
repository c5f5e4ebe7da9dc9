#!/usr/bin/env python3
"""Writes the glTF test corpus (tests/data/gltf/valid, invalid) and its README.

Every file is tiny and exercises one case; tests/test_gltf.cpp asserts the outcome. The generated
files are committed, so CI never runs this script. Only the standard library is used.
Run: python3 tests/data/gltf/make_corpus.py
"""
import base64
import json
import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
CASES = []  # (path, outcome) for the README

BYTE, UBYTE, SHORT, USHORT, UINT, FLOAT = 5120, 5121, 5122, 5123, 5125, 5126
FMT = {BYTE: "b", UBYTE: "B", SHORT: "h", USHORT: "H", UINT: "I", FLOAT: "f"}
COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}


def png(width, height, rgba):
    """A minimal RGBA8 PNG (no filtering), `rgba` a flat list of bytes."""
    raw = b"".join(b"\0" + bytes(rgba[y * width * 4:(y + 1) * width * 4]) for y in range(height))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    ihdr = struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")


class Gltf:
    """A glTF document with one binary buffer, written as data: URI, external .bin or GLB."""

    def __init__(self):
        self.bin = bytearray()
        self.doc = {"asset": {"version": "2.0", "generator": "gblens make_corpus.py"},
                    "buffers": [], "bufferViews": [], "accessors": []}

    def view(self, data, stride=None):
        while len(self.bin) % 4:
            self.bin.append(0)
        v = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if stride:
            v["byteStride"] = stride
        self.bin += data
        self.doc["bufferViews"].append(v)
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, view, ctype, count, kind, offset=0, normalized=False, extra=None):
        a = {"componentType": ctype, "count": count, "type": kind}
        if view is not None:
            a["bufferView"] = view
        if offset:
            a["byteOffset"] = offset
        if normalized:
            a["normalized"] = True
        if extra:
            a.update(extra)
        self.doc["accessors"].append(a)
        return len(self.doc["accessors"]) - 1

    def data(self, values, ctype, kind, normalized=False, minmax=False):
        """An accessor over a new tightly packed view holding `values` (a list of tuples)."""
        flat = [c for v in values for c in (v if isinstance(v, (tuple, list)) else (v,))]
        view = self.view(struct.pack("<%d%s" % (len(flat), FMT[ctype]), *flat))
        extra = None
        if minmax:
            n = COMPONENTS[kind]
            extra = {"min": [min(v[i] for v in values) for i in range(n)],
                     "max": [max(v[i] for v in values) for i in range(n)]}
        return self.accessor(view, ctype, len(values), kind, normalized=normalized, extra=extra)

    def mesh(self, primitives, name=None):
        m = {"primitives": primitives}
        if name:
            m["name"] = name
        self.doc.setdefault("meshes", []).append(m)
        return len(self.doc["meshes"]) - 1

    def node(self, **fields):
        self.doc.setdefault("nodes", []).append(fields)
        return len(self.doc["nodes"]) - 1

    def scene(self, nodes):
        self.doc["scenes"] = [{"nodes": nodes}]
        self.doc["scene"] = 0

    def image(self, png_bytes, in_view=False):
        img = {"mimeType": "image/png"}
        if in_view:
            img["bufferView"] = self.view(png_bytes)
        else:
            img["uri"] = "data:image/png;base64," + base64.b64encode(png_bytes).decode()
        self.doc.setdefault("images", []).append(img)
        self.doc.setdefault("textures", []).append({"source": len(self.doc["images"]) - 1})
        return len(self.doc["textures"]) - 1

    def write(self, path, outcome, mode="datauri", bin_name=None, bin_uri=None, byte_length=None):
        full = os.path.join(HERE, path)
        os.makedirs(os.path.dirname(full), exist_ok=True)
        while len(self.bin) % 4:
            self.bin.append(0)
        buf = {"byteLength": byte_length if byte_length is not None else len(self.bin)}
        if mode == "datauri":
            buf["uri"] = "data:application/octet-stream;base64," + base64.b64encode(bytes(self.bin)).decode()
        elif mode == "external":
            buf["uri"] = bin_uri or bin_name
            with open(os.path.join(os.path.dirname(full), bin_name), "wb") as f:
                f.write(self.bin)
        self.doc["buffers"] = [buf] if self.bin or mode != "glb" else []
        if not self.doc["buffers"]:
            del self.doc["buffers"]
        text = json.dumps(self.doc, indent=1 if mode != "glb" else None)
        if mode == "glb":
            js = text.encode()
            js += b" " * (-len(js) % 4)
            body = struct.pack("<II", len(js), 0x4E4F534A) + js
            if self.bin:
                body += struct.pack("<II", len(self.bin), 0x004E4942) + bytes(self.bin)
            with open(full, "wb") as f:
                f.write(struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body)
        else:
            with open(full, "w") as f:
                f.write(text + "\n")
        CASES.append((path, outcome))


def raw(path, content, outcome):
    full = os.path.join(HERE, path)
    os.makedirs(os.path.dirname(full), exist_ok=True)
    with open(full, "wb" if isinstance(content, bytes) else "w") as f:
        f.write(content)
    CASES.append((path, outcome))


# ---- geometry helpers ------------------------------------------------------------------------
QUAD = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]  # counter-clockwise seen from +Z
QUAD_IDX = [0, 1, 2, 0, 2, 3]
TRI = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]


def triangle(g, material=None, normals=True, uvs=False):
    attrs = {"POSITION": g.data(TRI, FLOAT, "VEC3", minmax=True)}
    if normals:
        attrs["NORMAL"] = g.data([(0, 0, 1)] * 3, FLOAT, "VEC3")
    if uvs:  # a textured material samples TEXCOORD_0: the primitive must have it (validator)
        attrs["TEXCOORD_0"] = g.data([(0, 0), (1, 0), (0, 1)], FLOAT, "VEC2")
    prim = {"attributes": attrs, "indices": g.data([0, 1, 2], USHORT, "SCALAR")}
    if material is not None:
        prim["material"] = material
    return prim


def simple(prim=None):
    """One triangle mesh on one node: the base most invalid cases break in one place."""
    g = Gltf()
    g.mesh([prim or triangle(g)])
    g.scene([g.node(mesh=0)])
    return g


def valid():
    g = simple()
    g.write("valid/triangle.gltf", "loads: 3 vertices, indices 0 1 2, default material, auto camera, generated lights + sun")

    for ctype, name in ((UBYTE, "u8"), (UINT, "u32")):
        g = Gltf()
        g.mesh([{"attributes": {"POSITION": g.data(QUAD, FLOAT, "VEC3", minmax=True)},
                 "indices": g.data(QUAD_IDX, ctype, "SCALAR")}])
        g.scene([g.node(mesh=0)])
        g.write("valid/indices_%s.gltf" % name, "loads: quad with %s indices 0 1 2 0 2 3, flat normals" % name)

    g = Gltf()
    six = [QUAD[i] for i in QUAD_IDX]
    g.mesh([{"attributes": {"POSITION": g.data(six, FLOAT, "VEC3", minmax=True),
                            "NORMAL": g.data([(0, 0, 1)] * 6, FLOAT, "VEC3")}}])
    g.scene([g.node(mesh=0)])
    g.write("valid/non_indexed.gltf", "loads: 6 vertices, indices 0..5")

    strip = [(0, 1, 0), (0, 0, 0), (1, 1, 0), (1, 0, 0), (2, 1, 0)]
    fan = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (-1, 1, 0)]
    for mode, name, verts, expect in ((5, "strip", strip, "0 1 2, 1 3 2, 2 3 4"), (6, "fan", fan, "1 2 0, 2 3 0, 3 4 0")):
        g = Gltf()
        g.mesh([{"attributes": {"POSITION": g.data(verts, FLOAT, "VEC3", minmax=True),
                                "NORMAL": g.data([(0, 0, 1)] * 5, FLOAT, "VEC3")},
                 "indices": g.data([0, 1, 2, 3, 4], USHORT, "SCALAR"), "mode": mode}])
        g.scene([g.node(mesh=0)])
        g.write("valid/%s.gltf" % name, "loads: TRIANGLE_%s -> triangles %s, all counter-clockwise" % (name.upper(), expect))

    g = Gltf()
    pos = g.data(TRI, FLOAT, "VEC3", minmax=True)
    g.mesh([{"attributes": {"POSITION": pos}, "mode": 0}, {"attributes": {"POSITION": pos}, "mode": 1},
            {"attributes": {"POSITION": pos, "NORMAL": g.data([(0, 0, 1)] * 3, FLOAT, "VEC3")}}])
    g.scene([g.node(mesh=0)])
    g.write("valid/points_lines.gltf", "loads: POINTS and LINES skipped with one warning, 1 triangle mesh")

    # Interleaved: position, normal, uv in one view of stride 32, read through byteOffset 0/12/24.
    g = Gltf()
    uvs = [(0, 1), (1, 1), (1, 0), (0, 0)]
    data = b"".join(struct.pack("<3f3f2f", *QUAD[i], 0, 0, 1, *uvs[i]) for i in range(4))
    v = g.view(data, stride=32)
    attrs = {"POSITION": g.accessor(v, FLOAT, 4, "VEC3", extra={"min": [0, 0, 0], "max": [1, 1, 0]}),
             "NORMAL": g.accessor(v, FLOAT, 4, "VEC3", offset=12), "TEXCOORD_0": g.accessor(v, FLOAT, 4, "VEC2", offset=24)}
    g.mesh([{"attributes": attrs, "indices": g.data(QUAD_IDX, USHORT, "SCALAR")}])
    g.scene([g.node(mesh=0)])
    g.write("valid/interleaved.gltf", "loads: stride-32 interleaved view; positions, normals, uvs exact")

    # Sparse: positions with two substituted elements; uvs from a sparse accessor without a view.
    g = Gltf()
    base = g.data(QUAD, FLOAT, "VEC3")
    g.doc["accessors"][base]["sparse"] = {
        "count": 2, "indices": {"bufferView": g.view(struct.pack("<BB", 1, 3)), "componentType": UBYTE},
        "values": {"bufferView": g.view(struct.pack("<6f", 2, 0, 0, 3, 3, 0))}}
    uv = g.accessor(None, FLOAT, 4, "VEC2", extra={"sparse": {
        "count": 1, "indices": {"bufferView": g.view(struct.pack("<H", 2)), "componentType": USHORT},
        "values": {"bufferView": g.view(struct.pack("<2f", 0.5, 0.25))}}})
    g.mesh([{"attributes": {"POSITION": base, "TEXCOORD_0": uv, "NORMAL": g.data([(0, 0, 1)] * 4, FLOAT, "VEC3")},
             "indices": g.data(QUAD_IDX, USHORT, "SCALAR")}])
    g.scene([g.node(mesh=0)])
    g.write("valid/sparse.gltf", "loads: positions (0,0,0) (2,0,0) (1,1,0) (3,3,0); uvs 0 except uv[2] = (0.5, 0.25)")

    # KHR_mesh_quantization: SHORT positions (not normalized), BYTE normalized normals and tangents
    # (stride 4), USHORT normalized uvs.
    g = Gltf()
    g.doc["extensionsUsed"] = g.doc["extensionsRequired"] = ["KHR_mesh_quantization"]
    positions = g.data([(0, 0, 0), (100, 0, 0), (0, 100, 0)], SHORT, "VEC3")
    g.doc["accessors"][positions]["min"], g.doc["accessors"][positions]["max"] = [0, 0, 0], [100, 100, 0]
    nview = g.view(struct.pack("<12b", 0, 0, 127, 0, 0, 0, 127, 0, 0, 0, 127, 0), stride=4)
    tview = g.view(struct.pack("<12b", 127, 0, 0, -128, 127, 0, 0, -128, 127, 0, 0, -128), stride=4)
    attrs = {"POSITION": positions, "NORMAL": g.accessor(nview, BYTE, 3, "VEC3", normalized=True),
             "TANGENT": g.accessor(tview, BYTE, 3, "VEC4", normalized=True),
             "TEXCOORD_0": g.data([(0, 0), (65535, 0), (0, 65535)], USHORT, "VEC2", normalized=True)}
    g.mesh([{"attributes": attrs, "indices": g.data([0, 1, 2], UBYTE, "SCALAR")}])
    g.scene([g.node(mesh=0, scale=[0.01, 0.01, 0.01])])
    g.write("valid/quantized.gltf", "loads: KHR_mesh_quantization; positions 0/100, normal (0,0,1), tangent w -1, uv 0/1")

    g = Gltf()
    g.mesh([{"attributes": {"POSITION": g.data(QUAD, FLOAT, "VEC3", minmax=True)},
             "indices": g.data(QUAD_IDX, USHORT, "SCALAR")}])
    g.scene([g.node(mesh=0)])
    g.write("valid/flat_normals.gltf", "loads: no normals -> de-indexed, 6 vertices, every normal (0,0,1)")

    # Two UV sets; the normal texture samples set 1; tangents generated from it (one primitive
    # with uv1 = (x, 1-y), one mirrored in u).
    g = Gltf()
    tex = g.image(png(1, 1, [128, 128, 255, 255]))
    g.doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": tex, "texCoord": 0}},
                           "normalTexture": {"index": tex, "texCoord": 1}}]
    prims = []
    for mirror in (False, True):
        uv0 = [(0.25, 0.25)] * 4
        uv1 = [((1 - p[0]) if mirror else p[0], 1 - p[1]) for p in QUAD]
        prims.append({"attributes": {"POSITION": g.data(QUAD, FLOAT, "VEC3", minmax=True),
                                     "NORMAL": g.data([(0, 0, 1)] * 4, FLOAT, "VEC3"),
                                     "TEXCOORD_0": g.data(uv0, FLOAT, "VEC2"), "TEXCOORD_1": g.data(uv1, FLOAT, "VEC2")},
                      "indices": g.data(QUAD_IDX, USHORT, "SCALAR"), "material": 0})
    g.mesh(prims)
    g.scene([g.node(mesh=0)])
    g.write("valid/two_uv_sets.gltf", "loads: normal texture on TEXCOORD_1; generated tangents (1,0,0,+1) and (-1,0,0,-1)")

    # Hierarchy: parent TRS (translation, 90 degrees about Y, scale 2), child matrix (translate x 1).
    g = Gltf()
    g.mesh([triangle(g)])
    s = math.sqrt(0.5)
    child = 1
    g.node(translation=[1, 2, 3], rotation=[0, s, 0, s], scale=[2, 2, 2], children=[child])
    g.node(mesh=0, matrix=[1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 1])
    g.scene([0])
    g.write("valid/hierarchy.gltf", "loads: child world = columns (0,0,-2) (0,2,0) (2,0,0), origin (1,2,1)")

    g = Gltf()
    g.mesh([{"attributes": {"POSITION": g.data(QUAD, FLOAT, "VEC3", minmax=True),
                            "NORMAL": g.data([(0, 0, 1)] * 4, FLOAT, "VEC3")},
             "indices": g.data(QUAD_IDX, USHORT, "SCALAR")}])
    g.scene([g.node(mesh=0, scale=[-1, 1, 1]), g.node(mesh=0, translation=[2, 0, 0])])
    g.write("valid/mirrored.gltf", "loads: instance 0 mirrored (determinant -1), indices kept (the renderer flips front faces)")

    g = Gltf()
    g.mesh([triangle(g)])
    g.node(mesh=0, translation=[-5, 0, 0])
    g.node(mesh=0, translation=[5, 0, 0])
    g.doc["scenes"] = [{"nodes": [0]}, {"nodes": [1]}]
    g.doc["scene"] = 1
    g.write("valid/scene_index.gltf", "loads: scene 1 only -> one instance at x = +5")

    g = Gltf()
    g.mesh([triangle(g)])
    g.scene([g.node(mesh=0, translation=[i * 2.0, 0, 0]) for i in range(3)])
    g.write("valid/instancing.gltf", "loads: 1 mesh, 3 instances at x = 0, 2, 4")

    # Materials: factor, texture with KHR_texture_transform, MASK, BLEND, double-sided, normal
    # texture scale, and two specular cases of the documented mapping.
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_texture_transform"]
    tex = g.image(png(2, 2, [255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255]))
    g.doc["materials"] = [
        {"name": "masked", "doubleSided": True, "alphaMode": "MASK", "alphaCutoff": 0.3,
         "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 1, 1], "baseColorTexture": {"index": tex, "extensions": {
             "KHR_texture_transform": {"offset": [0.5, 0], "rotation": math.pi / 2, "scale": [2, 2]}}}}},
        {"name": "blended", "alphaMode": "BLEND"},
        {"name": "rough_dielectric", "normalTexture": {"index": tex, "scale": 0.5},
         "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 1}},
        {"name": "smooth_metal", "pbrMetallicRoughness": {"metallicFactor": 1, "roughnessFactor": 0}},
    ]
    g.mesh([triangle(g, material=i, uvs=True) for i in range(4)])
    g.scene([g.node(mesh=0)])
    g.write("valid/materials.gltf", "loads: 4 materials (MASK 0.3 double-sided + transform, BLEND warning, normal scale 0.5, specular 0.0127 / 1)")

    g = Gltf()
    g.doc["cameras"] = [{"type": "perspective", "name": "persp", "perspective": {"yfov": 0.5, "znear": 0.1}},
                        {"type": "orthographic", "name": "ortho",
                         "orthographic": {"xmag": 2, "ymag": 1, "znear": 0.1, "zfar": 50}}]
    g.mesh([triangle(g)])
    g.scene([g.node(mesh=0), g.node(camera=0, translation=[0, 0, 10]), g.node(camera=1, translation=[0, 0, 20])])
    g.write("valid/cameras.gltf", "loads: cameras persp (far from bounds), ortho (warning), auto")

    g = Gltf()
    g.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 100}}]
    g.mesh([triangle(g)])
    g.scene([g.node(mesh=0), g.node(camera=0, translation=[0, 0, 5], scale=[0, 0, 0]),
             g.node(camera=0, translation=[0, 0, 5], scale=[-1, 2, 1]),
             g.node(camera=0, matrix=[1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 5, 1])])
    g.write("valid/degenerate_cameras.gltf", "loads: cameras with scale 0, mirrored, sheared -> rotations (det +1)")

    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_lights_punctual"]
    g.doc["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"type": "point", "color": [1, 0.5, 0.25], "intensity": 10, "range": 3},
        {"type": "point", "intensity": 4},
        {"type": "spot", "intensity": 4, "spot": {"outerConeAngle": 0.5}},
        {"type": "directional", "intensity": 2}]}}
    floor = [(-5, 0, 5), (5, 0, 5), (5, 0, -5), (-5, 0, -5)]
    g.mesh([{"attributes": {"POSITION": g.data(floor, FLOAT, "VEC3", minmax=True),
                            "NORMAL": g.data([(0, 1, 0)] * 4, FLOAT, "VEC3")},
             "indices": g.data(QUAD_IDX, USHORT, "SCALAR")}])
    light = lambda i, **kw: g.node(extensions={"KHR_lights_punctual": {"light": i}}, **kw)
    g.scene([g.node(mesh=0), light(0, translation=[0, 2, 0]), light(1, translation=[2, 2, 0]),
             light(2, translation=[-2, 2, 0]), light(3, rotation=[-s, 0, 0, s])])
    g.write("valid/lights.gltf", "loads: 3 point lights (range 3 -> radius 3; spot warning), sun toward +Y")

    for name, uri, label in (("external", "external.bin", "separate .bin"),
                             ("with space", "with%20space.bin", "percent-encoded URI of a file name with a space"),
                             ("raw space", "raw space.bin", "a raw space in the URI")):
        g = simple()
        g.write("valid/%s.gltf" % name, "loads: " + label, mode="external", bin_name=name + ".bin", bin_uri=uri)

    g = Gltf()
    tex = g.image(png(1, 1, [10, 20, 30, 255]), in_view=True)
    g.doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": tex}}}]
    g.mesh([triangle(g, material=0, uvs=True)])
    g.scene([g.node(mesh=0)])
    g.write("valid/binary.glb", "loads: GLB with BIN chunk, image in a buffer view (1x1, rgb 10 20 30)", mode="glb")

    # GPU test scene: a 2x2 quad at z = -3 facing a camera at the origin; MASK at 0.5 with a 2x1
    # texture whose left texel has alpha 0 and right texel alpha 255 (cut-out: the left half).
    g = Gltf()
    tex = g.image(png(2, 1, [255, 255, 255, 0, 255, 255, 255, 255]))
    g.doc["samplers"] = [{"wrapS": 33071, "wrapT": 33071}]
    g.doc["textures"][tex]["sampler"] = 0
    g.doc["materials"] = [{"alphaMode": "MASK", "alphaCutoff": 0.5,
                           "pbrMetallicRoughness": {"baseColorTexture": {"index": tex}}}]
    g.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.5, "zfar": 20}}]
    quad = [(-1, -1, -3), (1, -1, -3), (1, 1, -3), (-1, 1, -3)]
    g.mesh([{"attributes": {"POSITION": g.data(quad, FLOAT, "VEC3", minmax=True),
                            "NORMAL": g.data([(0, 0, 1)] * 4, FLOAT, "VEC3"),
                            "TEXCOORD_0": g.data([(0, 1), (1, 1), (1, 0), (0, 0)], FLOAT, "VEC2")},
             "indices": g.data(QUAD_IDX, USHORT, "SCALAR"), "material": 0}])
    g.scene([g.node(mesh=0), g.node(camera=0)])
    g.write("valid/cutout_quad.gltf", "loads (GPU test): eye depth 3 on the right half, left half cut out")

    g = Gltf()
    g.mesh([{"attributes": {"POSITION": g.data(QUAD, FLOAT, "VEC3", minmax=True),
                            "NORMAL": g.data([(0, 0, 1)] * 4, FLOAT, "VEC3")},
             "indices": g.data(QUAD_IDX, USHORT, "SCALAR")}])
    g.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.5, "zfar": 20}}]
    g.scene([g.node(mesh=0, translation=[0.5, -0.5, -3], scale=[-1, 1, 1]), g.node(camera=0)])
    g.write("valid/mirrored_quad.gltf", "loads (GPU test): a mirrored single-sided quad facing the camera stays visible")


def extensions_and_ignored_parts():
    # KHR_materials_unlit (required, as the Khronos UnlitTest sample does): an orange unlit quad on
    # the left, a lit grey one on the right, facing a camera at the origin (GPU test: the unlit
    # half's hdr is its albedo, whatever the lights).
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_materials_unlit"]
    g.doc["extensionsRequired"] = ["KHR_materials_unlit"]
    g.doc["materials"] = [
        {"name": "orange unlit", "pbrMetallicRoughness": {"baseColorFactor": [1, 0.217637640824031, 0, 1]},
         "extensions": {"KHR_materials_unlit": {}}},
        {"name": "grey lit", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1]}}]
    g.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 1.0, "znear": 0.5, "zfar": 20}}]
    normals = g.data([(0, 0, 1)] * 4, FLOAT, "VEC3")
    idx = g.data(QUAD_IDX, USHORT, "SCALAR")
    left = [(-1.5, -1, -3), (0, -1, -3), (0, 1, -3), (-1.5, 1, -3)]
    right = [(0, -1, -3), (1.5, -1, -3), (1.5, 1, -3), (0, 1, -3)]
    g.mesh([{"attributes": {"POSITION": g.data(left, FLOAT, "VEC3", minmax=True), "NORMAL": normals},
             "indices": idx, "material": 0},
            {"attributes": {"POSITION": g.data(right, FLOAT, "VEC3", minmax=True), "NORMAL": normals},
             "indices": idx, "material": 1}])
    g.scene([g.node(mesh=0), g.node(camera=0)])
    g.write("valid/unlit.gltf", "loads: KHR_materials_unlit required; material 0 unlit (specular 0), material 1 lit")

    # KHR_materials_emissive_strength (required): accepted; emission is not drawn, listed as
    # ignored with its strength.
    g = Gltf()
    g.doc["extensionsUsed"] = ["KHR_materials_emissive_strength"]
    g.doc["extensionsRequired"] = ["KHR_materials_emissive_strength"]
    g.doc["materials"] = [{"name": "lamp", "emissiveFactor": [1, 0.5, 0],
                           "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}}]
    g.mesh([triangle(g, material=0)])
    g.scene([g.node(mesh=0)])
    g.write("valid/emissive_strength.gltf", "loads: KHR_materials_emissive_strength required; emission (4, 2, 0) ignored")

    # Errors in parts gblens does not draw: each a warning naming the part, the triangle drawn.
    g = simple()
    prim = g.doc["meshes"][0]["primitives"][0]
    prim["targets"] = [{"POSITION": 42}]
    prim["attributes"]["JOINTS_0"] = g.data([(0, 0, 0, 0)] * 2, UBYTE, "VEC4")
    past_end = g.accessor(0, FLOAT, 100, "VEC3")  # read by the animation only: past its view
    g.doc["animations"] = [{"name": "spin", "samplers": [{"input": 99, "output": past_end}],
                            "channels": [{"sampler": 0, "target": {"node": 7, "path": "rotation"}}]}]
    g.doc["skins"] = [{"joints": [5]}]
    g.doc["nodes"][0]["skin"] = 0
    g.doc["extensionsUsed"] = ["KHR_materials_emissive_strength"]
    g.doc["materials"] = [{"emissiveFactor": [1, 1, 1],
                           "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": -2}}}]
    prim["material"] = 0
    g.write("valid/ignored_parts.gltf", "loads with warnings: animation (input 99, target node 7), skin (joint 5), "
            "morph target (accessor 42), JOINTS_0 count, accessor past its view (animation only), emissiveStrength -2")


def invalid():
    def broken(path, outcome, change, prim=None, **write):
        g = simple(prim)
        change(g)
        g.write(path, "rejected: " + outcome, **write)

    raw("invalid/empty.gltf", "", "rejected: file: empty")
    raw("invalid/bad_json.gltf", '{"asset": {"version": "2.0"}, "meshes": [', "rejected: JSON parse error")
    raw("invalid/not_an_object.gltf", "[1, 2, 3]", "rejected: JSON root is not an object")
    raw("invalid/no_asset.gltf", '{"meshes": []}', "rejected: asset.version missing")
    raw("invalid/gltf1.gltf", json.dumps({"asset": {"version": "1.0"}, "meshes": {"m": {"primitives": []}},
                                          "scene": "defaultScene"}), "rejected: glTF 1.0")
    raw("invalid/deep_json.gltf", '{"asset": {"version": "2.0"}, "extras": ' + "[" * 100 + "]" * 100 + "}",
        "rejected: JSON nested deeper than 64 levels")
    raw("invalid/truncated.glb", struct.pack("<III", 0x46546C67, 2, 4096) + struct.pack("<II", 100, 0x4E4F534A) + b"{}  ",
        "rejected: GLB header longer than the file")
    raw("invalid/bad_magic.glb", b"glTF" + b"\x02\x00\x00\x00" + b"\xff" * 16, "rejected: GLB")

    broken("invalid/meshopt_required.gltf", "extensionsRequired EXT_meshopt_compression named",
           lambda g: g.doc.update(extensionsUsed=["EXT_meshopt_compression"],
                                  extensionsRequired=["EXT_meshopt_compression"]))
    g = simple()
    g.write("invalid/missing_bin.gltf", "rejected: buffer file 'nothere.bin' not found", mode="external",
            bin_name="unused.bin", bin_uri="nothere.bin")
    os.remove(os.path.join(HERE, "invalid/unused.bin"))
    g = simple()
    g.write("invalid/short_bin.gltf", "rejected: buffer file shorter than byteLength", mode="external",
            bin_name="short_bin.bin", byte_length=len(g.bin) + 64)
    broken("invalid/short_data_uri.gltf", "buffer data: URI shorter than byteLength",
           lambda g: None, byte_length=1000)
    broken("invalid/missing_image.gltf", "image 0 file 'missing.png' not found",
           lambda g: g.doc.update(images=[{"uri": "missing.png"}], textures=[{"source": 0}]))
    broken("invalid/corrupt_image.gltf", "image 0 cannot decode (truncated PNG)",
           lambda g: g.doc.update(images=[{"uri": "data:image/png;base64," + base64.b64encode(
               png(4, 4, [1] * 64)[:40]).decode()}], textures=[{"source": 0}],
               materials=[{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]))
    huge = b"\x89PNG\r\n\x1a\n" + struct.pack(">I", 13) + b"IHDR" + struct.pack(">IIBBBBB", 100000, 100000, 8, 6, 0, 0, 0)
    huge += struct.pack(">I", zlib.crc32(huge[12:]) & 0xFFFFFFFF)
    idat = zlib.compress(b"\0" * 64)  # a start of pixel data: the header is all a reader needs
    huge += struct.pack(">I", len(idat)) + b"IDAT" + idat + struct.pack(">I", zlib.crc32(b"IDAT" + idat) & 0xFFFFFFFF)
    broken("invalid/absurd_image.gltf", "image 0 100000x100000 refused before decoding",
           lambda g: g.doc.update(images=[{"uri": "data:image/png;base64," + base64.b64encode(huge).decode()}],
                                  textures=[{"source": 0}],
                                  materials=[{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]))
    broken("invalid/not_png.gltf", "image 0 is not PNG or JPEG",
           lambda g: g.doc.update(images=[{"uri": "data:image/gif;base64," + base64.b64encode(b"GIF89a....").decode()}],
                                  textures=[{"source": 0}],
                                  materials=[{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]))
    broken("invalid/accessor_out_of_range.gltf", "accessor 0 runs past the end of its bufferView",
           lambda g: g.doc["accessors"][0].update(count=100))
    broken("invalid/accessor_offset.gltf", "accessor 1 byteOffset runs past the end of its bufferView",
           lambda g: g.doc["accessors"][1].update(byteOffset=1 << 40))
    broken("invalid/bufferview_out_of_range.gltf", "bufferView 0 runs past the end of buffer 0",
           lambda g: g.doc["bufferViews"][0].update(byteLength=4096))
    g = Gltf()
    g.mesh([{"attributes": {"POSITION": g.data(TRI, FLOAT, "VEC3")}, "indices": g.data([0, 1, 7], USHORT, "SCALAR")}])
    g.scene([g.node(mesh=0)])
    g.write("invalid/index_out_of_range.gltf", "rejected: index 7 is out of range (3 vertices)")
    g = Gltf()
    g.mesh([{"attributes": {"POSITION": g.data([(0, 0, 0), (float("nan"), 0, 0), (0, 1, 0)], FLOAT, "VEC3")}}])
    g.scene([g.node(mesh=0)])
    g.write("invalid/nan_position.gltf", "rejected: POSITION holds NaN")
    g = Gltf()
    g.mesh([{"attributes": {"POSITION": g.data(TRI, FLOAT, "VEC3"),
                            "NORMAL": g.data([(0, 0, 1), (0, 0, float("inf")), (0, 0, 1)], FLOAT, "VEC3")}}])
    g.scene([g.node(mesh=0)])
    g.write("invalid/inf_normal.gltf", "rejected: NORMAL holds Inf")
    broken("invalid/transform_overflow.gltf", "node world transform overflows",
           lambda g: g.doc.update(nodes=[{"scale": [1e300, 1e300, 1e300], "children": [1]},
                                         {"mesh": 0, "scale": [1e300, 1e300, 1e300]}], scenes=[{"nodes": [0]}]))
    broken("invalid/big_number.gltf", "JSON number overflow (1e999 in a transform)",
           lambda g: None)
    path = os.path.join(HERE, "invalid/big_number.gltf")
    with open(path) as f:
        text = f.read().replace('"mesh": 0', '"mesh": 0, "translation": [1e999, 0, 0]', 1)
    with open(path, "w") as f:
        f.write(text)
    broken("invalid/node_cycle.gltf", "node cycle (1 -> 2 -> 1, unreachable from the root)",
           lambda g: g.doc.update(nodes=[{"mesh": 0}, {"children": [2]}, {"children": [1]}],
                                  scenes=[{"nodes": [0]}]))
    broken("invalid/self_child.gltf", "node is its own child",
           lambda g: g.doc["nodes"][0].update(children=[0]))
    broken("invalid/two_parents.gltf", "node with two parents",
           lambda g: g.doc.update(nodes=[{"children": [2]}, {"children": [2]}, {"mesh": 0}], scenes=[{"nodes": [0, 1]}]))
    broken("invalid/absurd_count.gltf", "accessor count absurd (2^40, no bufferView; the primitive's TEXCOORD_0)",
           lambda g: g.doc["accessors"].append({"componentType": FLOAT, "count": 1 << 40, "type": "VEC2"})
           or g.doc["meshes"][0]["primitives"][0]["attributes"].update(TEXCOORD_0=3))
    broken("invalid/bad_component_type.gltf", "componentType 5124 (INT) is not glTF 2.0",
           lambda g: g.doc["accessors"][0].update(componentType=5124))
    g = Gltf()
    g.mesh([{"attributes": {"POSITION": g.data(TRI, FLOAT, "VEC3")}, "indices": g.data([0, 1, 2], FLOAT, "SCALAR")}])
    g.scene([g.node(mesh=0)])
    g.write("invalid/float_indices.gltf", "rejected: indices accessor is not unsigned byte/short/int")
    broken("invalid/bad_mode.gltf", "primitive mode 9",
           lambda g: g.doc["meshes"][0]["primitives"][0].update(mode=9))
    broken("invalid/stride_too_small.gltf", "byteStride smaller than an element",
           lambda g: g.doc["bufferViews"][0].update(byteStride=8))
    broken("invalid/count_mismatch.gltf", "attribute NORMAL has 2 elements, POSITION has 3",
           lambda g: g.doc["accessors"][1].update(count=2))
    broken("invalid/bad_scene.gltf", "scene 5 does not exist", lambda g: g.doc.update(scene=5))
    broken("invalid/bad_mesh_ref.gltf", "node mesh 4 does not exist", lambda g: g.doc["nodes"][0].update(mesh=4))
    broken("invalid/bad_material_ref.gltf", "primitive material 3 does not exist",
           lambda g: g.doc["meshes"][0]["primitives"][0].update(material=3))
    broken("invalid/not_multiple_of_3.gltf", "TRIANGLES with 4 indices",
           lambda g: g.doc["accessors"][2].update(count=4) or g.doc["bufferViews"][2].update(byteLength=8))
    broken("invalid/bad_alpha_mode.gltf", "alphaMode \"GLASS\"",
           lambda g: g.doc.update(materials=[{"alphaMode": "GLASS"}]))
    broken("invalid/bad_camera.gltf", "camera yfov must be in (0, pi)",
           lambda g: g.doc.update(cameras=[{"type": "perspective", "perspective": {"yfov": 0, "znear": 0.1}}]))
    broken("invalid/bad_light.gltf", "KHR_lights_punctual light type \"area\"",
           lambda g: g.doc.update(extensions={"KHR_lights_punctual": {"lights": [{"type": "area"}]}}))
    broken("invalid/sparse_bad_index.gltf", "sparse index 9 out of range",
           lambda g: g.doc["accessors"][0].update(sparse={
               "count": 1, "indices": {"bufferView": g.view(struct.pack("<H", 9)), "componentType": USHORT},
               "values": {"bufferView": 0}}))
    broken("invalid/zero_quaternion.gltf", "rotation is a zero quaternion",
           lambda g: g.doc["nodes"][0].update(rotation=[0, 0, 0, 0]))
    # Indices of 2^32 and more: tinygltf holds an int, so 2^32 would wrap to 0 and name what exists.
    broken("invalid/wrapped_buffer_view.gltf", "accessor bufferView 4294967296 does not exist",
           lambda g: g.doc["accessors"][0].update(bufferView=1 << 32))
    broken("invalid/wrapped_buffer.gltf", "bufferView buffer 4294967296 does not exist",
           lambda g: g.doc["bufferViews"][0].update(buffer=1 << 32))
    broken("invalid/wrapped_mesh.gltf", "node mesh 4294967296 does not exist",
           lambda g: g.doc["nodes"][0].update(mesh=1 << 32))
    broken("invalid/wrapped_position.gltf", "primitive attributes.POSITION 4294967296 does not exist",
           lambda g: g.doc["meshes"][0]["primitives"][0]["attributes"].update(POSITION=1 << 32))


def main():
    valid()
    extensions_and_ignored_parts()
    invalid()
    with open(os.path.join(HERE, "README.md"), "w") as f:
        f.write("# glTF test corpus\n\nGenerated by `make_corpus.py` (committed; CI does not regenerate it). "
                "One case per file; `tests/test_gltf.cpp` asserts each outcome.\n\n| file | expected outcome |\n|---|---|\n")
        for path, outcome in CASES:
            f.write("| `%s` | %s |\n" % (path, outcome))


if __name__ == "__main__":
    main()
