#!/usr/bin/env python3
"""Writes one small room as glTF, COLLADA and OBJ+MTL (standard library only).

Run from anywhere: `python3 tests/data/triple/make.py`; room.gltf, room.dae, room.obj and
room.mtl land beside this script. tests/cli.rs (module `triple`) checks that invlight
loads the three to the same surfaces, areas and light, and measures the same
illuminance on them.

The scene, in metres, +Y up:
- a 4 x 2.5 x 3 room (x in [0, 4], y in [0, 2.5], z in [0, 3]): `Floor` (K_d 0.6, 0.3,
  0.2), `Ceiling` and `Walls` (grey, K_d 0.5), all facing into the room;
- `Box`, a 0.5 m cube standing on the floor (x in [2.5, 3], z in [0.75, 1.25]); it has
  no bottom face, which would lie in the floor's plane where no light reaches;
- `Lamp`, a 0.5 x 0.5 m panel 1/64 m under the middle of the ceiling, facing down
  (counter-clockwise seen from below), emitting 1000 cd/m^2: flux pi * 1000 * 0.25 =
  785.4 lm. Its diffuse reflectance is 0.8, as Blender's default material has.

Every coordinate is a multiple of 1/64, so the box's translation (a node transform in
glTF and COLLADA, baked into the vertices in OBJ, which has none) is exact in f32 and
the three files describe bit-identical world-space triangles, in the same order.

Emission in each format (what the loaders in crates/scene read as cd/m^2):
- glTF: emissiveFactor (1, 1, 1) x KHR_materials_emissive_strength 1000;
- COLLADA: <emission><color>1000 1000 1000 1</color> (the colour is the luminance, as
  ILPSolver reads Blender's exports; crates/scene/src/collada/effect.rs);
- OBJ: `Ke 1000 1000 1000` (crates/scene/src/obj/mtl.rs).
"""

import base64
import json
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))

# name -> (K_d, emission cd/m^2)
MATERIALS = {
    "Wall": ((0.5, 0.5, 0.5), 0.0),
    "FloorPaint": ((0.6, 0.3, 0.2), 0.0),
    "BoxPaint": ((0.5, 0.5, 0.5), 0.0),
    "Emitter": ((0.8, 0.8, 0.8), 1000.0),
}

LAMP_Y = 2.5 - 1 / 64
BOX_AT = (2.75, 0.25, 1.0)  # centre of the box: the node translation


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def quad(a, b, c, d, normal):
    """A planar quad a b c d, counter-clockwise seen from the side `normal` points to."""
    n = cross(sub(b, a), sub(c, a))
    assert sum(x * y for x, y in zip(n, normal)) > 0, (a, b, c, d, normal)
    return [a, b, c, d], normal


def box_faces(h):
    """The cube of half-size h around the origin without its bottom face, facing out."""
    return [
        quad((-h, h, -h), (-h, h, h), (h, h, h), (h, h, -h), (0, 1, 0)),
        quad((-h, -h, -h), (-h, -h, h), (-h, h, h), (-h, h, -h), (-1, 0, 0)),
        quad((h, -h, -h), (h, h, -h), (h, h, h), (h, -h, h), (1, 0, 0)),
        quad((-h, -h, -h), (-h, h, -h), (h, h, -h), (h, -h, -h), (0, 0, -1)),
        quad((-h, -h, h), (h, -h, h), (h, h, h), (-h, h, h), (0, 0, 1)),
    ]


# (node name, material, quads in local coordinates, node translation)
OBJECTS = [
    ("Floor", "FloorPaint",
     [quad((0, 0, 0), (0, 0, 3), (4, 0, 3), (4, 0, 0), (0, 1, 0))], None),
    ("Ceiling", "Wall",
     [quad((0, 2.5, 0), (4, 2.5, 0), (4, 2.5, 3), (0, 2.5, 3), (0, -1, 0))], None),
    ("Walls", "Wall", [
        quad((0, 0, 0), (0, 2.5, 0), (0, 2.5, 3), (0, 0, 3), (1, 0, 0)),
        quad((4, 0, 0), (4, 0, 3), (4, 2.5, 3), (4, 2.5, 0), (-1, 0, 0)),
        quad((0, 0, 0), (4, 0, 0), (4, 2.5, 0), (0, 2.5, 0), (0, 0, 1)),
        quad((0, 0, 3), (0, 2.5, 3), (4, 2.5, 3), (4, 0, 3), (0, 0, -1)),
    ], None),
    ("Box", "BoxPaint", box_faces(0.25), BOX_AT),
    ("Lamp", "Emitter",
     [quad((1.75, LAMP_Y, 1.25), (2.25, LAMP_Y, 1.25), (2.25, LAMP_Y, 1.75),
           (1.75, LAMP_Y, 1.75), (0, -1, 0))], None),
]


def flat(quads):
    """Positions (4 per quad) and fan triangles (0 1 2, 0 2 3), as every format gets them."""
    positions, triangles = [], []
    for corners, _ in quads:
        k = len(positions)
        positions += corners
        triangles += [(k, k + 1, k + 2), (k, k + 2, k + 3)]
    return positions, triangles


def num(x):
    return repr(float(x)).removesuffix(".0")


def write_gltf():
    buf = bytearray()
    views, accessors, meshes, nodes = [], [], [], []

    def accessor(fmt, values, kind, component):
        while len(buf) % 4:
            buf.append(0)
        flat_values = [x for v in values for x in v]
        data = struct.pack("<%d%s" % (len(flat_values), fmt), *flat_values)
        views.append({"buffer": 0, "byteOffset": len(buf), "byteLength": len(data)})
        buf.extend(data)
        acc = {"bufferView": len(views) - 1, "componentType": component,
               "count": len(values), "type": kind}
        if kind == "VEC3":
            acc["min"] = [min(v[i] for v in values) for i in range(3)]
            acc["max"] = [max(v[i] for v in values) for i in range(3)]
        accessors.append(acc)
        return len(accessors) - 1

    names = list(MATERIALS)
    for name, material, quads, at in OBJECTS:
        positions, triangles = flat(quads)
        p = accessor("f", positions, "VEC3", 5126)
        i = accessor("H", triangles, "SCALAR", 5123)
        accessors[i]["count"] *= 3
        meshes.append({"name": name + "-mesh", "primitives": [{
            "attributes": {"POSITION": p}, "indices": i,
            "material": names.index(material)}]})
        node = {"name": name, "mesh": len(meshes) - 1}
        if at:
            node["translation"] = list(at)
        nodes.append(node)

    materials = []
    for name, (kd, emission) in MATERIALS.items():
        m = {"name": name, "pbrMetallicRoughness": {
            "baseColorFactor": list(kd) + [1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}}
        if emission:
            m["emissiveFactor"] = [1.0, 1.0, 1.0]
            m["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": emission}}
        materials.append(m)

    gltf = {
        "asset": {"version": "2.0", "generator": "invlight tests/data/triple/make.py"},
        "extensionsUsed": ["KHR_materials_emissive_strength"],
        "scene": 0,
        "scenes": [{"name": "Scene", "nodes": list(range(len(nodes)))}],
        "nodes": nodes, "meshes": meshes, "materials": materials,
        "buffers": [{"byteLength": len(buf), "uri": "data:application/octet-stream;base64,"
                     + base64.b64encode(bytes(buf)).decode()}],
        "bufferViews": views, "accessors": accessors,
    }
    with open(os.path.join(HERE, "room.gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")


def write_dae():
    """COLLADA 1.4.1 the way Blender's exporter lays it out."""
    out = ['<?xml version="1.0" encoding="utf-8"?>',
           '<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">',
           '  <asset>',
           '    <contributor>',
           '      <author>invlight</author>',
           '      <authoring_tool>tests/data/triple/make.py</authoring_tool>',
           '    </contributor>',
           '    <created>2026-11-22T00:00:00</created>',
           '    <modified>2026-11-22T00:00:00</modified>',
           '    <unit name="meter" meter="1"/>',
           '    <up_axis>Y_UP</up_axis>',
           '  </asset>',
           '  <library_images/>',
           '  <library_effects>']
    for name, (kd, emission) in MATERIALS.items():
        e = " ".join(num(emission) for _ in range(3))
        d = " ".join(num(x) for x in kd)
        out += [f'    <effect id="{name}-effect">',
                '      <profile_COMMON>',
                '        <technique sid="common">',
                '          <lambert>',
                '            <emission>',
                f'              <color sid="emission">{e} 1</color>',
                '            </emission>',
                '            <diffuse>',
                f'              <color sid="diffuse">{d} 1</color>',
                '            </diffuse>',
                '          </lambert>',
                '        </technique>',
                '      </profile_COMMON>',
                '    </effect>']
    out += ['  </library_effects>', '  <library_materials>']
    for name in MATERIALS:
        out += [f'    <material id="{name}-material" name="{name}">',
                f'      <instance_effect url="#{name}-effect"/>',
                '    </material>']
    out += ['  </library_materials>', '  <library_geometries>']
    for name, material, quads, _ in OBJECTS:
        g = name + "-mesh"
        positions, triangles = flat(quads)
        normals = [n for _, n in quads]

        def source(kind, values):
            floats = " ".join(num(x) for v in values for x in v)
            return [f'        <source id="{g}-{kind}">',
                    f'          <float_array id="{g}-{kind}-array" count="{3 * len(values)}">'
                    f'{floats}</float_array>',
                    '          <technique_common>',
                    f'            <accessor source="#{g}-{kind}-array" count="{len(values)}" '
                    'stride="3">',
                    '              <param name="X" type="float"/>',
                    '              <param name="Y" type="float"/>',
                    '              <param name="Z" type="float"/>',
                    '            </accessor>',
                    '          </technique_common>',
                    '        </source>']

        # Vertex index, then the face's normal index (shared <input> offsets).
        p = " ".join(f"{v} {t // 2}" for t, tri in enumerate(triangles) for v in tri)
        out += [f'    <geometry id="{g}" name="{name}">', '      <mesh>',
                *source("positions", positions), *source("normals", normals),
                f'        <vertices id="{g}-vertices">',
                f'          <input semantic="POSITION" source="#{g}-positions"/>',
                '        </vertices>',
                f'        <triangles material="{material}-material" count="{len(triangles)}">',
                f'          <input semantic="VERTEX" source="#{g}-vertices" offset="0"/>',
                f'          <input semantic="NORMAL" source="#{g}-normals" offset="1"/>',
                f'          <p>{p}</p>',
                '        </triangles>',
                '      </mesh>',
                '    </geometry>']
    out += ['  </library_geometries>', '  <library_visual_scenes>',
            '    <visual_scene id="Scene" name="Scene">']
    for name, material, _, at in OBJECTS:
        t = at or (0, 0, 0)
        matrix = f"1 0 0 {num(t[0])} 0 1 0 {num(t[1])} 0 0 1 {num(t[2])} 0 0 0 1"
        out += [f'      <node id="{name}" name="{name}" type="NODE">',
                f'        <matrix sid="transform">{matrix}</matrix>',
                f'        <instance_geometry url="#{name}-mesh" name="{name}">',
                '          <bind_material>',
                '            <technique_common>',
                f'              <instance_material symbol="{material}-material" '
                f'target="#{material}-material"/>',
                '            </technique_common>',
                '          </bind_material>',
                '        </instance_geometry>',
                '      </node>']
    out += ['    </visual_scene>', '  </library_visual_scenes>', '  <scene>',
            '    <instance_visual_scene url="#Scene"/>', '  </scene>', '</COLLADA>']
    with open(os.path.join(HERE, "room.dae"), "w") as f:
        f.write("\n".join(out) + "\n")


def write_obj():
    mtl = ["# The materials of room.obj (tests/data/triple/make.py)."]
    for name, (kd, emission) in MATERIALS.items():
        mtl += ["", f"newmtl {name}", "illum 1",
                "Kd " + " ".join(num(x) for x in kd),
                "Ke " + " ".join(num(emission) for _ in range(3))]
    with open(os.path.join(HERE, "room.mtl"), "w") as f:
        f.write("\n".join(mtl) + "\n")

    obj = ["# The room of tests/data/triple/make.py; quads, which the loader splits as a fan.",
           "mtllib room.mtl"]
    first = 1
    for name, material, quads, at in OBJECTS:
        t = at or (0, 0, 0)
        obj += ["", f"o {name}", f"usemtl {material}"]
        for corners, _ in quads:
            obj += ["v " + " ".join(num(c + o) for c, o in zip(p, t)) for p in corners]
        for q in range(len(quads)):
            obj.append("f " + " ".join(str(first + 4 * q + k) for k in range(4)))
        first += 4 * len(quads)
    with open(os.path.join(HERE, "room.obj"), "w") as f:
        f.write("\n".join(obj) + "\n")


if __name__ == "__main__":
    write_gltf()
    write_dae()
    write_obj()
