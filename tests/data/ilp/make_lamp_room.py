#!/usr/bin/env python3
"""Writes lamp-room.gltf: a 4 m x 4 m room, 1.2 m high (Y up), grey walls, a desk off
centre, a 100 cd point lamp "Lamp" authored at vertex A of the placement rectangle
"Ceiling__Geometry" (y = 1.1). lamp-room.xml asks where on the ceiling the lamp lights
the desk best: right above it, at (3.0, 1.1, 1.25). Run: python3 make_lamp_room.py"""
import base64, json, struct

quads = {  # name: (corners counter-clockwise seen from the lit side, material)
    "Floor": ([(0, 0, 0), (0, 0, 4), (4, 0, 4), (4, 0, 0)], 0),
    "Ceiling": ([(0, 1.2, 0), (4, 1.2, 0), (4, 1.2, 4), (0, 1.2, 4)], 0),
    "WallW": ([(0, 0, 0), (0, 1.2, 0), (0, 1.2, 4), (0, 0, 4)], 0),
    "WallE": ([(4, 0, 0), (4, 0, 4), (4, 1.2, 4), (4, 1.2, 0)], 0),
    "WallS": ([(0, 0, 0), (4, 0, 0), (4, 1.2, 0), (0, 1.2, 0)], 0),
    "WallN": ([(0, 0, 4), (0, 1.2, 4), (4, 1.2, 4), (4, 0, 4)], 0),
    "Desk": ([(2.75, 0.01, 1.0), (2.75, 0.01, 1.5), (3.25, 0.01, 1.5), (3.25, 0.01, 1.0)], 1),
    "Ceiling__Geometry": ([(0, 1.1, 0), (4, 1.1, 0), (4, 1.1, 4), (0, 1.1, 4)], 0),
}
blob = b""
views, accessors, meshes, nodes = [], [], [], []
for name, (corners, material) in quads.items():
    pos = b"".join(struct.pack("<3f", *c) for c in corners)
    idx = struct.pack("<6H", 0, 1, 2, 0, 2, 3) + b"\0\0"
    for data, target in ((pos, 34962), (idx, 34963)):
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
        blob += data
    accessors.append({"bufferView": len(views) - 2, "componentType": 5126, "count": 4, "type": "VEC3",
                      "min": [min(c[i] for c in corners) for i in range(3)],
                      "max": [max(c[i] for c in corners) for i in range(3)]})
    accessors.append({"bufferView": len(views) - 1, "componentType": 5123, "count": 6, "type": "SCALAR"})
    meshes.append({"name": name, "primitives": [{"attributes": {"POSITION": len(accessors) - 2},
                                                 "indices": len(accessors) - 1, "material": material}]})
    nodes.append({"name": name, "mesh": len(meshes) - 1})
nodes.append({"name": "Lamp", "translation": [0, 1.1, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}})
gltf = {
    "asset": {"version": "2.0", "generator": "tests/data/ilp/make_lamp_room.py"},
    "extensionsUsed": ["KHR_lights_punctual"],
    "extensions": {"KHR_lights_punctual": {"lights": [{"name": "Lamp", "type": "point", "intensity": 100.0}]}},
    "materials": [
        {"name": "Grey", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0}},
        {"name": "Desk", "pbrMetallicRoughness": {"baseColorFactor": [0.3, 0.2, 0.1, 1], "metallicFactor": 0}},
    ],
    "buffers": [{"byteLength": len(blob), "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
    "bufferViews": views, "accessors": accessors, "meshes": meshes, "nodes": nodes,
    "scenes": [{"nodes": list(range(len(nodes)))}], "scene": 0,
}
with open("lamp-room.gltf", "w") as f:
    json.dump(gltf, f, indent=1)
    f.write("\n")
