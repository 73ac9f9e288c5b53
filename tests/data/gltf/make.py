#!/usr/bin/env python3
"""Writes the small glTF test scenes of crates/scene/tests/gltf.rs (standard library only).

Run from anywhere: `python3 tests/data/gltf/make.py`; the files land beside this script.
Every number the tests check is derived in the test from the values written here.
"""

import base64
import json
import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))

FLOAT, U8, U16, U32 = 5126, 5121, 5123, 5125
TRIANGLES, LINES, STRIP, FAN = 4, 1, 5, 6


def png(width, height, rows):
    """An 8-bit RGB PNG; rows of (r, g, b) tuples, top row first."""
    raw = b"".join(b"\0" + bytes(c for px in row for c in px) for row in rows)

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header)
            + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


# Top-left red, top-right green, bottom-left blue, bottom-right sRGB grey 128.
CHECKER = png(2, 2, [[(255, 0, 0), (0, 255, 0)], [(0, 0, 255), (128, 128, 128)]])


class Doc:
    """A glTF document with one binary buffer assembled as accessors are added."""

    def __init__(self):
        self.bin = bytearray()
        self.gltf = {"asset": {"version": "2.0", "generator": "invlight tests/data/gltf/make.py"},
                     "bufferViews": [], "accessors": []}
        self.images = []  # (index in gltf["images"], PNG bytes)

    def view(self, data):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.gltf["bufferViews"].append(
            {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)})
        self.bin += data
        return len(self.gltf["bufferViews"]) - 1

    def accessor(self, kind, component, values):
        fmt = {FLOAT: "f", U8: "B", U16: "H", U32: "I"}[component]
        flat = [x for v in values for x in (v if isinstance(v, (list, tuple)) else [v])]
        acc = {"bufferView": self.view(struct.pack("<%d%s" % (len(flat), fmt), *flat)),
               "componentType": component, "count": len(values), "type": kind}
        if kind == "VEC3" and component == FLOAT:
            acc["min"] = [min(v[i] for v in values) for i in range(3)]
            acc["max"] = [max(v[i] for v in values) for i in range(3)]
        self.gltf["accessors"].append(acc)
        return len(self.gltf["accessors"]) - 1

    def primitive(self, positions, indices=None, index_type=U16, mode=TRIANGLES,
                  material=None, uvs=None, uvs1=None):
        p = {"attributes": {"POSITION": self.accessor("VEC3", FLOAT, positions)}}
        if indices is not None:
            p["indices"] = self.accessor("SCALAR", index_type, indices)
        if uvs is not None:
            p["attributes"]["TEXCOORD_0"] = self.accessor("VEC2", FLOAT, uvs)
        if uvs1 is not None:
            p["attributes"]["TEXCOORD_1"] = self.accessor("VEC2", FLOAT, uvs1)
        if mode != TRIANGLES:
            p["mode"] = mode
        if material is not None:
            p["material"] = material
        return p

    def image(self):
        self.gltf.setdefault("images", []).append({})
        self.images.append((len(self.gltf["images"]) - 1, CHECKER))
        return len(self.gltf["images"]) - 1

    def write(self, name, container):
        """container: 'embedded' (data URIs), 'external' (NAME.bin + NAME.png beside)
        or 'glb' (BIN chunk, images in buffer views)."""
        doc = json.loads(json.dumps(self.gltf))
        binary = bytearray(self.bin)
        stem = os.path.splitext(name)[0]
        for i, data in self.images:
            if container == "glb":
                while len(binary) % 4:
                    binary.append(0)
                doc["bufferViews"].append(
                    {"buffer": 0, "byteOffset": len(binary), "byteLength": len(data)})
                binary += data
                doc["images"][i] = {"bufferView": len(doc["bufferViews"]) - 1,
                                    "mimeType": "image/png"}
            elif container == "external":
                with open(os.path.join(HERE, "%s %d.png" % (stem, i)), "wb") as f:
                    f.write(data)
                doc["images"][i] = {"uri": "%s%%20%d.png" % (stem, i)}
            else:
                doc["images"][i] = {"uri": "data:image/png;base64," + base64.b64encode(data).decode()}
        buffer = {"byteLength": len(binary)}
        if container == "embedded":
            buffer["uri"] = "data:application/octet-stream;base64," + base64.b64encode(binary).decode()
        elif container == "external":
            buffer["uri"] = stem + ".bin"
            with open(os.path.join(HERE, stem + ".bin"), "wb") as f:
                f.write(binary)
        doc["buffers"] = [buffer]
        text = json.dumps(doc, indent=1).encode()
        with open(os.path.join(HERE, name), "wb") as f:
            if container == "glb":
                text += b" " * (-len(text) % 4)
                binary += b"\0" * (-len(binary) % 4)
                chunks = (struct.pack("<I4s", len(text), b"JSON") + text
                          + struct.pack("<I4s", len(binary), b"BIN\0") + binary)
                f.write(struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks)
            else:
                f.write(text)


QUAD = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
QUAD_UV = [(0, 1), (1, 1), (1, 0), (0, 0)]


def hierarchy():
    """Node hierarchy with TRS and matrix, a shared mesh, name fallbacks, strips, fans,
    lines and non-indexed primitives, placements, lights and a camera."""
    d = Doc()
    g = d.gltf
    half = math.sqrt(0.5)
    g["meshes"] = [
        {"name": "QuadMesh", "primitives": [d.primitive(QUAD, [0, 1, 2, 0, 2, 3], U16, uvs=QUAD_UV)]},
        {"name": "TriMesh", "primitives": [d.primitive([(0, 0, 0), (1, 0, 0), (0, 1, 0)])]},
        {"name": "StripMesh", "primitives": [
            d.primitive(QUAD, [0, 1, 3, 2], U8, STRIP),
            d.primitive(QUAD, [0, 1, 1, 2], U8, LINES)]},
        {"name": "FanMesh", "primitives": [d.primitive(QUAD, [0, 1, 2, 3], U32, FAN)]},
        {"name": "LinesOnly", "primitives": [d.primitive(QUAD, [0, 1], U16, LINES)]},
        # A rectangle as two triangles of six vertices, as exporters write it unindexed.
        {"name": "DeskRect", "primitives": [d.primitive(
            [(0, 0, 0), (2, 0, 0), (2, 0, 1), (0, 0, 0), (2, 0, 1), (0, 0, 1)])]},
    ]
    g["extensionsUsed"] = ["KHR_lights_punctual"]
    g["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"name": "BulbLight", "type": "point", "color": [1, 0.5, 0.25], "intensity": 100,
         "extensions": {"EXT_unknown": {"a": 1}}, "extras": {"note": "ignored"}},
        {"name": "SpotLight", "type": "spot", "intensity": 50,
         "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}},
        {"name": "Sun", "type": "directional", "intensity": 1000, "range": 3},
        {"type": "spot", "intensity": 5, "spot": {}},
    ]}}
    g["cameras"] = [{"name": "CamData", "type": "perspective",
                     "perspective": {"yfov": 0.8, "aspectRatio": 1.5, "znear": 0.1}}]
    g["nodes"] = [
        # 0: Room = T(10,0,0) R_y(90°) S(2)
        {"name": "Room", "translation": [10, 0, 0], "rotation": [0, half, 0, half],
         "scale": [2, 2, 2], "children": [1, 2]},
        # 1: Table = column-major matrix translating by (0,1,0)
        {"name": "Table", "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 1, 0, 1],
         "mesh": 0, "children": [3]},
        # 2: unnamed: takes its mesh's name
        {"mesh": 1},
        # 3: Cup reuses the quad mesh
        {"name": "Cup", "translation": [0, 0, 1], "mesh": 0},
        {"name": "Strip", "mesh": 2},
        {"name": "Fan", "mesh": 3, "translation": [0, 0, -5]},
        {"name": "Wire", "mesh": 4},
        {"name": "Desk__Geometry", "mesh": 5, "translation": [0, 1, 0]},
        {"name": "Bulb", "translation": [1, 2, 3], "extras": {"blender": {"prop": [1, 2]}},
         "extensions": {"KHR_lights_punctual": {"light": 0}}},
        # Spot: R_x(−90°) turns −Z to −Y (down).
        {"name": "Spot", "translation": [0, 3, 0], "rotation": [-half, 0, 0, half],
         "extensions": {"KHR_lights_punctual": {"light": 1}}},
        # Unnamed: the light's name; R_y(90°) turns −Z to −X.
        {"rotation": [0, half, 0, half], "extensions": {"KHR_lights_punctual": {"light": 2}}},
        {"name": "Eye", "translation": [0, 1, 5], "rotation": [0, half, 0, half], "camera": 0},
        {"name": "DefaultCone", "extensions": {"KHR_lights_punctual": {"light": 3}}},
        # Not in the scene: never placed.
        {"name": "Orphan", "mesh": 0},
        # 14: mirrored in x (determinant < 0): glTF's front face stays +Z.
        {"name": "Mirrored", "mesh": 0, "scale": [-1, 1, 1]},
    ]
    g["scene"] = 0
    g["scenes"] = [{"nodes": [0, 4, 5, 6, 7, 8, 9, 10, 11, 12, 14], "name": "Main"}]
    d.write("hierarchy.gltf", "embedded")
    d.write("hierarchy.glb", "glb")
    with open(os.path.join(HERE, "hierarchy.glb"), "rb") as f:
        whole = f.read()
    with open(os.path.join(HERE, "truncated.glb"), "wb") as f:
        f.write(whole[: len(whole) // 2])


def materials():
    """One quad per material kind; the textured one in every container."""
    d = Doc()
    g = d.gltf
    g["extensionsUsed"] = ["KHR_materials_emissive_strength", "KHR_materials_transmission",
                           "KHR_materials_ior"]
    g["materials"] = [
        {"name": "Lamp", "emissiveFactor": [1, 0.5, 0.25],
         "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0},
         "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 10}}},
        {"name": "Mirror", "pbrMetallicRoughness": {
            "baseColorFactor": [0.9, 0.8, 0.7, 1], "metallicFactor": 1, "roughnessFactor": 0.1}},
        {"name": "RoughMetal", "pbrMetallicRoughness": {
            "baseColorFactor": [0.9, 0.8, 0.7, 1], "roughnessFactor": 0.5}},
        {"name": "Glass", "pbrMetallicRoughness": {"metallicFactor": 0, "roughnessFactor": 0},
         "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1},
                        "KHR_materials_ior": {"ior": 1.45}}},
        {"name": "HalfGlass", "pbrMetallicRoughness": {
            "baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0},
         "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.5}}},
        {"name": "Aperture", "extensions": {"KHR_materials_ior": {"ior": 0.5}}},
        {"name": "Checker", "pbrMetallicRoughness": {
            "baseColorFactor": [1, 0.5, 1, 1], "metallicFactor": 0,
            "baseColorTexture": {"index": 0}}},
        # The same texture read through the second uv set.
        {"name": "CheckerSet1", "pbrMetallicRoughness": {
            "metallicFactor": 0, "baseColorTexture": {"index": 0, "texCoord": 1}}},
    ]
    g["images"] = []
    d.image()
    g["textures"] = [{"source": 0}]
    g["meshes"] = [{"name": m["name"] + "Mesh", "primitives": [
        d.primitive(QUAD, [0, 1, 2, 0, 2, 3], U16, material=i, uvs=QUAD_UV)]}
        for i, m in enumerate(g["materials"][:-1])]
    g["meshes"].append({"name": "CheckerSet1Mesh", "primitives": [d.primitive(
        QUAD, [0, 1, 2, 0, 2, 3], U16, material=len(g["materials"]) - 1,
        uvs=[(0.5, 0.5)] * 4, uvs1=QUAD_UV)]})
    g["meshes"].append({"name": "PlainMesh", "primitives": [d.primitive(QUAD, [0, 1, 2, 0, 2, 3])]})
    # Nodes named after their material; the plain one unnamed, so named by its mesh.
    g["nodes"] = [{"name": m["name"], "mesh": i} for i, m in enumerate(g["materials"])]
    g["nodes"].append({"mesh": len(g["materials"])})
    g["scenes"] = [{"nodes": list(range(len(g["nodes"])))}]
    d.write("materials.gltf", "embedded")
    d.write("materials.glb", "glb")
    d.write("external.gltf", "external")


def broken():
    """Files that must fail with a located error."""
    d = Doc()
    d.gltf["meshes"] = [{"primitives": [d.primitive(QUAD, [0, 1, 2, 0, 2, 3])]}]
    d.gltf["nodes"] = [{"name": "Q", "mesh": 0}]
    d.gltf["scenes"] = [{"nodes": [0]}]
    d.write("missing_bin.gltf", "external")
    os.remove(os.path.join(HERE, "missing_bin.bin"))
    doc = d.gltf
    d.gltf = json.loads(json.dumps(doc))
    d.gltf["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 99
    d.write("bad_accessor.gltf", "embedded")
    d.gltf = json.loads(json.dumps(doc))
    d.gltf["meshes"] = [{"primitives": [d.primitive(QUAD, [0, 1, 2, 0, 2, 7])]}]
    d.write("bad_index.gltf", "embedded")
    d.gltf = json.loads(json.dumps(doc))
    d.gltf["nodes"] = [{"name": "A", "children": [1]}, {"name": "B", "children": [0]}]
    d.write("cycle.gltf", "embedded")
    d.gltf = json.loads(json.dumps(doc))
    d.gltf["meshes"][0]["primitives"][0]["mode"] = 9
    d.write("bad_mode.gltf", "embedded")
    d.gltf = json.loads(json.dumps(doc))
    d.gltf["meshes"][0]["primitives"][0]["material"] = 0
    d.gltf["materials"] = [
        {"name": "Lantern", "emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 0}}
    ]
    d.gltf["textures"] = [{"source": 0}]
    d.gltf["images"] = [{"uri": "external 0.png"}]
    d.write("emissive_texture.gltf", "embedded")
    with open(os.path.join(HERE, "hierarchy.gltf"), "rb") as f:
        text = f.read()
    with open(os.path.join(HERE, "malformed.gltf"), "wb") as f:
        f.write(text[: len(text) // 3])


if __name__ == "__main__":
    hierarchy()
    materials()
    broken()
