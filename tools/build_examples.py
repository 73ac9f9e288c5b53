#!/usr/bin/env python3
"""Builds the scenes of the bundled examples from the original geometry.

    python3 tools/build_examples.py [--scenes DIR] [--out DIR] [--only NAME] [--wall-value V]

Python 3 standard library only. Reads the original models from their zips
(DIR/sponza/sponza.zip, DIR/conference/conference.zip; DIR defaults to ../shared/scenes
beside the repository) and writes glTF 2.0 scenes (`scene.gltf` + `scene.bin`) into
examples/atrium-skylight, examples/atrium-colour, examples/conference-sun and
examples/office-target, examples/office-ies and examples/office-daylight (the same
office, built from nothing, no source geometry; office-ies also gets
tests/data/photometry/downlight.ldt, office-daylight a skylight instead of lamps). The output
is byte-for-byte the same on every run, so a reader can redo it and diff.

What is added to the original geometry (a roof, a hole, a jar, lamps, the sun, ceiling
panels, a window, a blackboard, cameras) and every reflectance and photometric value is
set here, in one place per example, and documented in that example's README.md.

Conventions of invlight's glTF loader (crates/scene/src/gltf): node names are surface
names and a named node covers its descendants; KHR_lights_punctual point lights are in
candela and directional lights in lux, shining along the node's local -Z; an emissive
material's luminance is emissiveFactor x KHR_materials_emissive_strength in cd/m2,
emitted from the counter-clockwise (front) face; a material with KHR_materials_ior
ior < 1 is a hole (ILPSolver's convention): rays pass every surface inside the hole
object's bounding box; a node named `*__Geometry` is a placement rectangle whose four
distinct vertices, in file order, are A, B, C, D going around it.

`--wall-value V` writes atrium-colour with the inner walls' HSV value V (hue 39 deg,
saturation 0.23) into --out: used to measure the floor at the ends of the colour
variable's range when choosing the cap (see examples/atrium-colour/README.md).
"""

import argparse
import colorsys
import json
import math
import os
import struct
import zipfile

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# --------------------------------------------------------------------------- maths


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def normalize(a):
    n = math.sqrt(dot(a, a))
    return (a[0] / n, a[1] / n, a[2] / n)


def look_rotation(forward, up_hint=(0.0, 1.0, 0.0)):
    """The unit quaternion [x, y, z, w] turning local -Z onto `forward` with local +Y as
    close to `up_hint` as possible (glTF cameras and lights look along local -Z)."""
    f = normalize(forward)
    if abs(dot(f, normalize(up_hint))) > 0.999:
        up_hint = (1.0, 0.0, 0.0)
    r = normalize(cross(f, up_hint))
    u = cross(r, f)
    z = (-f[0], -f[1], -f[2])
    # Rotation matrix with columns r, u, z; quaternion by Shepperd's method.
    m00, m01, m02 = r[0], u[0], z[0]
    m10, m11, m12 = r[1], u[1], z[1]
    m20, m21, m22 = r[2], u[2], z[2]
    tr = m00 + m11 + m22
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        q = ((m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s, 0.25 * s)
    elif m00 > m11 and m00 > m22:
        s = math.sqrt(1.0 + m00 - m11 - m22) * 2
        q = (0.25 * s, (m01 + m10) / s, (m02 + m20) / s, (m21 - m12) / s)
    elif m11 > m22:
        s = math.sqrt(1.0 + m11 - m00 - m22) * 2
        q = ((m01 + m10) / s, 0.25 * s, (m12 + m21) / s, (m02 - m20) / s)
    else:
        s = math.sqrt(1.0 + m22 - m00 - m11) * 2
        q = ((m02 + m20) / s, (m12 + m21) / s, 0.25 * s, (m10 - m01) / s)
    return [round(c, 9) for c in q]


def hsv(hue_deg, saturation, value):
    """Linear RGB K_d from HSV, as ILPSolver and invlight's `color` variable use it."""
    return list(colorsys.hsv_to_rgb(hue_deg / 360.0, saturation, value))


# --------------------------------------------------------------------------- glTF


class Gltf:
    """A glTF 2.0 document with one binary buffer: f32 positions, u32 indices."""

    def __init__(self, generator):
        self.doc = {
            "asset": {"version": "2.0", "generator": generator},
            "extensionsUsed": [],
            "scene": 0,
            "scenes": [{"nodes": []}],
            "nodes": [],
            "meshes": [],
            "materials": [],
            "accessors": [],
            "bufferViews": [],
            "buffers": [],
        }
        self.bin = bytearray()
        self.lights = []
        self.cameras = []

    def use(self, ext):
        if ext not in self.doc["extensionsUsed"]:
            self.doc["extensionsUsed"].append(ext)

    def material(self, name, base=(0.5, 0.5, 0.5), emission=None, hole=False):
        """A rough dielectric: diffuse K_d = `base`; `emission` cd/m2 makes it an emitter
        (black reflectance); `hole` makes it an aperture (ior 0.5 < 1)."""
        m = {
            "name": name,
            "pbrMetallicRoughness": {
                "baseColorFactor": [round(c, 6) for c in base] + [1.0],
                "metallicFactor": 0.0,
                "roughnessFactor": 1.0,
            },
        }
        if emission is not None:
            m["pbrMetallicRoughness"]["baseColorFactor"] = [0.0, 0.0, 0.0, 1.0]
            m["emissiveFactor"] = [1.0, 1.0, 1.0]
            m["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": emission}}
            self.use("KHR_materials_emissive_strength")
        if hole:
            m["extensions"] = {"KHR_materials_ior": {"ior": 0.5}}
            self.use("KHR_materials_ior")
        self.doc["materials"].append(m)
        return len(self.doc["materials"]) - 1

    def _view(self, data, target):
        while len(self.bin) % 4:
            self.bin.append(0)
        self.doc["bufferViews"].append(
            {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data), "target": target}
        )
        self.bin.extend(data)
        return len(self.doc["bufferViews"]) - 1

    def mesh(self, name, positions, triangles, material):
        """A triangle mesh from `positions` (xyz tuples) and `triangles` (index triples)."""
        flat = [c for p in positions for c in p]
        pos = struct.pack("<%df" % len(flat), *flat)
        # min/max of the f32 values actually stored (the spec requires them exact).
        stored = struct.unpack("<%df" % len(flat), pos)
        lo = [min(stored[i::3]) for i in range(3)]
        hi = [max(stored[i::3]) for i in range(3)]
        idx = [i for t in triangles for i in t]
        acc = self.doc["accessors"]
        acc.append({"bufferView": self._view(pos, 34962), "componentType": 5126,
                    "count": len(positions), "type": "VEC3", "min": lo, "max": hi})
        acc.append({"bufferView": self._view(struct.pack("<%dI" % len(idx), *idx), 34963),
                    "componentType": 5125, "count": len(idx), "type": "SCALAR"})
        self.doc["meshes"].append({
            "name": name,
            "primitives": [{"attributes": {"POSITION": len(acc) - 2}, "indices": len(acc) - 1,
                            "material": material, "mode": 4}],
        })
        return len(self.doc["meshes"]) - 1

    def node(self, name, parent=None, mesh=None, translation=None, rotation=None,
             light=None, camera=None):
        n = {"name": name}
        if mesh is not None:
            n["mesh"] = mesh
        if translation is not None:
            n["translation"] = [round(c, 6) for c in translation]
        if rotation is not None:
            n["rotation"] = rotation
        if light is not None:
            n["extensions"] = {"KHR_lights_punctual": {"light": light}}
        if camera is not None:
            n["camera"] = camera
        self.doc["nodes"].append(n)
        i = len(self.doc["nodes"]) - 1
        if parent is None:
            self.doc["scenes"][0]["nodes"].append(i)
        else:
            self.doc["nodes"][parent].setdefault("children", []).append(i)
        return i

    def point_light(self, name, position, candela, parent=None):
        self.use("KHR_lights_punctual")
        self.lights.append({"name": name, "type": "point", "color": [1.0, 1.0, 1.0],
                            "intensity": candela})
        return self.node(name, parent, translation=position, light=len(self.lights) - 1)

    def spot_light(self, name, position, direction, candela, inner_deg, outer_deg, parent=None):
        """A spot of `candela` on its axis, full inside `inner_deg`, fading to nothing at
        `outer_deg` (half-angles), shining along `direction`."""
        self.use("KHR_lights_punctual")
        self.lights.append({"name": name, "type": "spot", "color": [1.0, 1.0, 1.0],
                            "intensity": candela, "spot": {
                                "innerConeAngle": round(math.radians(inner_deg), 6),
                                "outerConeAngle": round(math.radians(outer_deg), 6)}})
        return self.node(name, parent, translation=position, rotation=look_rotation(direction),
                         light=len(self.lights) - 1)

    def sun(self, name, direction, lux, parent=None):
        """A directional light travelling along `direction`."""
        self.use("KHR_lights_punctual")
        self.lights.append({"name": name, "type": "directional", "color": [1.0, 1.0, 1.0],
                            "intensity": lux})
        return self.node(name, parent, rotation=look_rotation(direction),
                         light=len(self.lights) - 1)

    def camera(self, name, eye, target, yfov_deg=60.0, aspect=4.0 / 3.0):
        self.cameras.append({"name": name, "type": "perspective", "perspective": {
            "yfov": round(math.radians(yfov_deg), 6), "aspectRatio": round(aspect, 6),
            "znear": 0.05, "zfar": 200.0}})
        return self.node(name, translation=eye, rotation=look_rotation(sub(target, eye)),
                         camera=len(self.cameras) - 1)

    def write(self, folder, stem="scene"):
        os.makedirs(folder, exist_ok=True)
        doc = dict(self.doc)
        if self.lights:
            doc["extensions"] = {"KHR_lights_punctual": {"lights": self.lights}}
        if self.cameras:
            doc["cameras"] = self.cameras
        doc["buffers"] = [{"uri": stem + ".bin", "byteLength": len(self.bin)}]
        with open(os.path.join(folder, stem + ".bin"), "wb") as f:
            f.write(self.bin)
        with open(os.path.join(folder, stem + ".gltf"), "w") as f:
            json.dump(doc, f, indent=1)
            f.write("\n")
        print("wrote %s/%s.gltf + .bin (%.1f MB, %d triangles)" % (
            os.path.relpath(folder, REPO), stem, len(self.bin) / 1e6,
            sum(a["count"] for a in self.doc["accessors"] if a["type"] == "SCALAR") // 3))


# --------------------------------------------------------------------------- shapes


def quad(a, b, c, d):
    """Positions and triangles of the quad a, b, c, d (listed going around it; the front
    face is the one from which a, b, c, d turn counter-clockwise)."""
    return [a, b, c, d], [(0, 1, 2), (0, 2, 3)]


def box(half):
    """A closed box centred on the origin with half-extents `half`, faces outward."""
    hx, hy, hz = half
    p = [(x, y, z) for x in (-hx, hx) for y in (-hy, hy) for z in (-hz, hz)]
    # Vertex k = 4*ix + 2*iy + iz.
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    tris = []
    for a, b, c, d in faces:
        tris += [(a, b, c), (a, c, d)]
    return p, tris


def lathe(profile, segments):
    """A closed surface of revolution about +Y from a profile of (radius, height) points
    running from the bottom centre (radius 0) to the top centre (radius 0); faces
    outward."""
    pos, tris = [], []
    ring = []
    for r, y in profile:
        if r == 0.0:
            ring.append([len(pos)])
            pos.append((0.0, y, 0.0))
        else:
            row = []
            for k in range(segments):
                a = 2 * math.pi * k / segments
                row.append(len(pos))
                pos.append((r * math.cos(a), y, -r * math.sin(a)))
            ring.append(row)
    for lower, upper in zip(ring, ring[1:]):
        for k in range(segments):
            k1 = (k + 1) % segments
            if len(lower) == 1:
                tris.append((lower[0], upper[k], upper[k1]))
            elif len(upper) == 1:
                tris.append((lower[k], upper[0], lower[k1]))
            else:
                tris.append((lower[k], upper[k], upper[k1]))
                tris.append((lower[k], upper[k1], lower[k1]))
    return pos, tris


def translate(points, t):
    return [(p[0] + t[0], p[1] + t[1], p[2] + t[2]) for p in points]


# --------------------------------------------------------------------------- OBJ


def read_obj(zip_path, member):
    """Positions and, per group (`g`; '' before any), triangles (fans of polygons)."""
    positions, groups, current = [], {}, ""
    with zipfile.ZipFile(zip_path) as z:
        for raw in z.read(member).decode("latin-1").splitlines():
            if raw.startswith("v "):
                positions.append(tuple(float(t) for t in raw.split()[1:4]))
            elif raw.startswith("g "):
                current = raw.split(None, 1)[1].strip()
            elif raw.startswith("f "):
                idx = []
                for t in raw.split()[1:]:
                    i = int(t.split("/")[0])
                    idx.append(i - 1 if i > 0 else len(positions) + i)
                tris = groups.setdefault(current, [])
                for k in range(1, len(idx) - 1):
                    tris.append((idx[0], idx[k], idx[k + 1]))
    return positions, groups


def submesh(positions, triangles, transform=lambda p: p):
    """The vertices `triangles` use, renumbered in first-use order."""
    remap, pos, out = {}, [], []
    for t in triangles:
        tri = []
        for i in t:
            if i not in remap:
                remap[i] = len(pos)
                pos.append(transform(positions[i]))
            tri.append(remap[i])
        out.append(tuple(tri))
    return pos, out


def normal_area(positions, t):
    a, b, c = (positions[i] for i in t)
    n = cross(sub(b, a), sub(c, a))
    return n, 0.5 * math.sqrt(dot(n, n))


# --------------------------------------------------------------------------- Sponza

# Sponza (Marko Dabrovic, 2002): units are metres (the ground floor is at y = 0.09, the
# gallery floors at 4.82 and 10.25, the top at 15.65). The open courtyard's top is the
# parapet's inner edge, x in [-10.913, 10.927], z in [-2.519, 2.521] at y = 15.65; the
# outer roof (group outside01) leaves x in [-11.653, 11.667], z in [-3.179, 3.181] open.
SPONZA_TOP = 15.65
ROOF_Y = 15.66  # 1 cm above the outer roof, so that the two never coincide
ROOF_HALF = (11.75, 3.30)  # covers the outer roof's opening with 9-12 cm of overlap
HOLE_HALF = 1.0  # the hole is 2 m x 2 m
# The hole's centre moves on this rectangle: the opening inset by the hole's half-size,
# so that the hole never reaches the parapet (inner edge at |x| = 10.91, |z| = 2.52).
ROOF_PLACEMENT_HALF = (9.9, 1.5)
STONE = (0.5, 0.5, 0.5)
FLOOR = (0.4, 0.4, 0.4)
WALL_HUE, WALL_SATURATION = 39.0, 0.23
WALL_VALUE = 0.6  # initial HSV value of the inner walls: K_d = (0.60, 0.55, 0.46)
LAMP_CD = 2000.0
LAMPS = [("Lamp1", (-5.5, 6.5, 0.0)), ("Lamp2", (5.5, 6.5, 0.0))]
SUN_LUX = 90000.0
SUN_TILT_DEG = 15.0
JAR_AT = (0.0, 0.09, 0.0)
JAR_PROFILE = [(0.0, 0.0), (0.14, 0.0), (0.20, 0.05), (0.27, 0.20), (0.30, 0.34),
               (0.28, 0.48), (0.20, 0.62), (0.12, 0.70), (0.11, 0.76), (0.15, 0.80),
               (0.0, 0.80)]
JAR_COLOUR = (0.5, 0.25, 0.15)  # terracotta


def sponza(gl, scenes_dir, walls_kd):
    """The Sponza atrium under a node `Sponza`: every OBJ group as its own node, with the
    group `walls` as `InnerWalls` (its own material) and the ground floor of `floors` as
    `Floor`; and the roof over the courtyard, node `Roof`."""
    positions, groups = read_obj(os.path.join(scenes_dir, "sponza", "sponza.zip"), "sponza.obj")
    stone = gl.material("Stone", STONE)
    floor = gl.material("Floor", FLOOR)
    walls = gl.material("InnerWalls", walls_kd)
    root = gl.node("Sponza")
    for name in sorted(groups):
        tris = groups[name]
        if name == "floors":
            ground, rest = [], []
            for t in tris:
                n, area = normal_area(positions, t)
                on_ground = all(abs(positions[i][1] - 0.09) < 0.01 for i in t)
                (ground if on_ground and n[1] > 0 else rest).append(t)
            gl.node("Floor", root, mesh=gl.mesh("Floor", *submesh(positions, ground), floor))
            gl.node("UpperFloors", root, mesh=gl.mesh("UpperFloors", *submesh(positions, rest), floor))
        elif name == "walls":
            gl.node("InnerWalls", root, mesh=gl.mesh("InnerWalls", *submesh(positions, tris), walls))
        else:
            gl.node(name, root, mesh=gl.mesh(name, *submesh(positions, tris), stone))
    hx, hz = ROOF_HALF
    # Front face down, into the atrium.
    roof = quad((-hx, ROOF_Y, -hz), (-hx, ROOF_Y, hz), (hx, ROOF_Y, hz), (hx, ROOF_Y, -hz))
    gl.node("Roof", mesh=gl.mesh("Roof", *roof, stone))
    for name, at in LAMPS:
        gl.point_light(name, at, LAMP_CD)


def atrium_skylight(scenes_dir, out):
    gl = Gltf("invlight tools/build_examples.py: atrium-skylight")
    sponza(gl, scenes_dir, hsv(WALL_HUE, WALL_SATURATION, WALL_VALUE))
    px, pz = ROOF_PLACEMENT_HALF
    a = (-px, ROOF_Y, -pz)
    corners = [a, (px, ROOF_Y, -pz), (px, ROOF_Y, pz), (-px, ROOF_Y, pz)]
    placement_mat = gl.material("Placement", STONE)
    gl.node("Roof__Geometry", mesh=gl.mesh("Roof__Geometry", *quad(*corners), placement_mat))
    # The hole: a 2 m x 2 m x 0.3 m box straddling the roof, authored with its centre at
    # vertex A, so that the solver's placement point P is the hole's centre.
    hole = gl.material("Aperture", hole=True)
    gl.node("Hole", mesh=gl.mesh("Hole", *box((HOLE_HALF, 0.15, HOLE_HALF)), hole), translation=a)
    jar = gl.material("Terracotta", JAR_COLOUR)
    gl.node("Jar", mesh=gl.mesh("Jar", *lathe(JAR_PROFILE, 32), jar), translation=JAR_AT)
    t = math.radians(SUN_TILT_DEG)
    gl.sun("Sun", (math.sin(t), -math.cos(t), 0.0), SUN_LUX)
    gl.camera("Camera", (-10.0, 1.8, 2.0), (0.0, 1.0, 0.0), 70.0)
    gl.write(out)


def atrium_colour(scenes_dir, out, value=WALL_VALUE):
    gl = Gltf("invlight tools/build_examples.py: atrium-colour")
    sponza(gl, scenes_dir, hsv(WALL_HUE, WALL_SATURATION, value))
    gl.camera("Camera", (-14.5, 1.8, -5.5), (0.0, 3.0, 0.0), 70.0)
    gl.write(out)


# --------------------------------------------------------------------------- conference

# Conference room (Anat Grynberg and Greg Ward, 1991): the notes say "scale by 0.003 to
# get metres", which gives a 1.96 m ceiling, a 0.54 m table and 0.35 m seats. The table
# top (182 units above the floor) at a standard 0.73 m gives 0.004 m per unit: ceiling
# 2.61 m, seats 0.47 m, room 10.4 m x 6.4 m. The floor (y = -1.572) is moved to y = 0.
CONF_SCALE = 0.004
CONF_FLOOR = -1.57216
CONF_WALLS_X = (-946.888, 1653.25)  # near and far (blackboard) walls
CONF_WALL_Z = 595.246  # right wall
CONF_WINDOW_ZONE = -990.0  # z below this: the window wall (blinds at -1016, outside at -1056)
CONF_CEILING = 650.293


def conf_m(p):
    return (p[0] * CONF_SCALE, (p[1] - CONF_FLOOR) * CONF_SCALE, p[2] * CONF_SCALE)


CONF_REFLECTANCE = {
    "Floor": (0.2, 0.2, 0.2),  # carpet
    "Ceiling": (0.8, 0.8, 0.8),
    "Walls": (0.7, 0.7, 0.7),
    "WindowWall": (0.6, 0.6, 0.6),  # blinds and the wall behind them
    "Furniture": (0.3, 0.3, 0.3),  # table, chairs
}
BLACKBOARD = (0.04, 0.10, 0.06)  # dark green slate
PANEL_LUMINANCE = 3000.0  # cd/m2: a 0.6 x 1.2 m LED panel of about 6800 lm
PANEL_HALF = (0.6, 0.3)
PANEL_X = (-2.49, 0.11, 2.71, 5.31)
PANEL_Z = (-2.44, 0.76)
# Window: the wall at z = -4.06..-4.22 m, x in [3.0, 5.8] m, sill 0.9 m, head 2.3 m.
WINDOW_LO = (3.0, 0.9, -4.30)
WINDOW_HI = (5.8, 2.3, -4.00)
# Blackboard on the far wall (x = 6.613 m), 3.6 m x 1.2 m, 1 cm proud of the wall.
BOARD_X = CONF_WALLS_X[1] * CONF_SCALE - 0.01
BOARD_Z = (-2.64, 0.96)
BOARD_Y = (0.9, 2.1)
CONF_SUN = (0.0, -math.sin(math.radians(60.0)), math.cos(math.radians(60.0)))  # initial: high


def conference(scenes_dir, out):
    positions, groups = read_obj(os.path.join(scenes_dir, "conference", "conference.zip"),
                                 "conference.obj")
    classes = {k: [] for k in CONF_REFLECTANCE}
    tol = 2.0  # units (8 mm)
    for tris in groups.values():
        for t in tris:
            ps = [positions[i] for i in t]
            n, area = normal_area(positions, t)
            if all(p[2] < CONF_WINDOW_ZONE for p in ps):
                kind = "WindowWall"
            elif all(p[1] < 0.5 for p in ps) and n[1] > 0:
                kind = "Floor"
            elif all(abs(p[1] - CONF_CEILING) < tol for p in ps):
                kind = "Ceiling"
            elif any(all(abs(p[0] - x) < tol for p in ps) for x in CONF_WALLS_X) or \
                    all(abs(p[2] - CONF_WALL_Z) < tol for p in ps):
                kind = "Walls"
            else:
                kind = "Furniture"
            classes[kind].append(t)
    gl = Gltf("invlight tools/build_examples.py: conference-sun")
    root = gl.node("Conference")
    for name, kd in CONF_REFLECTANCE.items():
        mat = gl.material(name, kd)
        gl.node(name, root, mesh=gl.mesh(name, *submesh(positions, classes[name], conf_m), mat))
    # Panels: front face down, into the room.
    panel = gl.material("Panel", emission=PANEL_LUMINANCE)
    y = (CONF_CEILING - CONF_FLOOR) * CONF_SCALE - 0.01
    hx, hz = PANEL_HALF
    k = 0
    for z in PANEL_Z:
        for x in PANEL_X:
            k += 1
            q = quad((-hx, 0.0, -hz), (hx, 0.0, -hz), (hx, 0.0, hz), (-hx, 0.0, hz))
            gl.node("Panel%d" % k, mesh=gl.mesh("Panel%d" % k, *q, panel), translation=(x, y, z))
    # Window: a hole box through the window wall's blinds and outer wall.
    lo, hi = WINDOW_LO, WINDOW_HI
    centre = tuple((a + b) / 2 for a, b in zip(lo, hi))
    half = tuple((b - a) / 2 for a, b in zip(lo, hi))
    gl.node("Window", mesh=gl.mesh("Window", *box(half), gl.material("Aperture", hole=True)),
            translation=centre)
    # Blackboard: front face toward -x, into the room.
    x = BOARD_X
    (z0, z1), (y0, y1) = BOARD_Z, BOARD_Y
    board = quad((x, y0, z1), (x, y0, z0), (x, y1, z0), (x, y1, z1))
    gl.node("Blackboard", mesh=gl.mesh("Blackboard", *board, gl.material("Blackboard", BLACKBOARD)))
    gl.sun("Sun", CONF_SUN, SUN_LUX)
    # In front of the cabinet that stands at x = −1.9 m across the back of the room.
    gl.camera("Camera", (-1.6, 1.7, -0.84), (6.6, 1.3, -0.84), 60.0)
    gl.write(out)
    print("  conference triangles per surface:",
          ", ".join("%s %d" % (k, len(v)) for k, v in classes.items()))
    inside = [t for v in classes.values() for t in v if any(
        all(lo[i] < conf_m(positions[j])[i] < hi[i] for i in range(3)) for j in t)]
    window_wall = set(classes["WindowWall"])
    print("  triangles with a vertex inside the window's hole box: %d (all WindowWall: %s)"
          % (len(inside), all(t in window_wall for t in inside)))


# --------------------------------------------------------------------------- office

# A 5 m x 4 m x 2.8 m office (Y up, x east-west, z north-south), a desk with a screen,
# two identical downlights to place and dim: "500 lx on the desk, U0 >= 0.6, <= 300 lx
# on the screen, least power". Built from nothing: no source geometry.
OFFICE = (5.0, 2.8, 4.0)
OFFICE_REFLECTANCE = {"Floor": 0.2, "Walls": 0.5, "Ceiling": 0.7}
DESK_TOP = 0.75  # m
DESK_X = (1.7, 3.3)  # 1.6 m wide
DESK_Z = (1.6, 2.4)  # 0.8 m deep; the user sits at z < 1.6, facing +z
DESK_KD = 0.35  # light oak
SCREEN_X = (2.2, 2.8)  # 0.6 m x 0.35 m display, facing the user (-z)
SCREEN_Y = (0.85, 1.2)
SCREEN_Z = 2.25
SCREEN_KD = 0.05  # a dark display
LAMP_CD = 2000.0  # on the axis: about 3 200 lm with these cones
LAMP_CONES = (30.0, 60.0)  # inner, outer half-angles, degrees
LAMP_Y = OFFICE[1] - 0.01
LAMP_ZONE = ((1.0, 0.5), (4.0, 3.5))  # (x, z) corners of the ceiling zone lamps may take
LAMPS = ((1.5, 1.0), (3.5, 3.0))  # as authored: not where a designer would put them
SKYLIGHT_SIZE = 1.0  # m, a square
SKYLIGHT_ZONE = ((0.5, 0.5), (4.5, 3.5))  # (x, z) corners its centre may take: the ceiling less half its size


def office_room(gl, room, w, h, d):
    """The floor, ceiling and walls of a w x h x d room (Y up) under node `room`, of
    OFFICE_REFLECTANCE."""
    # Every room surface faces into the room.
    faces = {
        "Floor": [quad((0, 0, 0), (0, 0, d), (w, 0, d), (w, 0, 0))],
        "Ceiling": [quad((0, h, 0), (w, h, 0), (w, h, d), (0, h, d))],
        "Walls": [
            quad((0, 0, 0), (w, 0, 0), (w, h, 0), (0, h, 0)),  # south, z = 0
            quad((0, 0, d), (0, h, d), (w, h, d), (w, 0, d)),  # north
            quad((0, 0, 0), (0, h, 0), (0, h, d), (0, 0, d)),  # west, x = 0
            quad((w, 0, 0), (w, 0, d), (w, h, d), (w, h, 0)),  # east
        ],
    }
    for name, quads in faces.items():
        pos, tris = [], []
        for qp, qt in quads:
            tris += [tuple(i + len(pos) for i in t) for t in qt]
            pos += qp
        kd = OFFICE_REFLECTANCE[name]
        gl.node(name, room, mesh=gl.mesh(name, pos, tris, gl.material(name, (kd, kd, kd))))


def office(_scenes_dir, out, name="office-target", skylight=False):
    """The office; with `skylight`, office-daylight's: no screen and no lamps, and a
    hole that may go anywhere in the ceiling's SKYLIGHT_ZONE."""
    w, h, d = OFFICE
    gl = Gltf("invlight tools/build_examples.py: " + name)
    room = gl.node("Room")
    office_room(gl, room, w, h, d)
    oak = gl.material("Oak", (DESK_KD, DESK_KD * 0.9, DESK_KD * 0.75))
    (x0, x1), (z0, z1) = DESK_X, DESK_Z
    top = quad((x0, DESK_TOP, z0), (x0, DESK_TOP, z1), (x1, DESK_TOP, z1), (x1, DESK_TOP, z0))
    gl.node("Desk", mesh=gl.mesh("Desk", *top, oak))
    # The desk's body, 1 mm under its top, and four legs.
    body = box(((x1 - x0) / 2, 0.0145, (z1 - z0) / 2))
    gl.node("DeskBody", mesh=gl.mesh("DeskBody", *body, oak),
            translation=((x0 + x1) / 2, DESK_TOP - 0.0155, (z0 + z1) / 2))
    leg = gl.mesh("Leg", *box((0.025, (DESK_TOP - 0.03) / 2, 0.025)), oak)
    for k, (x, z) in enumerate([(x0 + 0.05, z0 + 0.05), (x1 - 0.05, z0 + 0.05),
                                (x0 + 0.05, z1 - 0.05), (x1 - 0.05, z1 - 0.05)]):
        gl.node("Leg%d" % (k + 1), mesh=leg, translation=(x, (DESK_TOP - 0.03) / 2, z))
    if skylight:
        # The zone the skylight's centre may take, on the ceiling, and the hole: a
        # SKYLIGHT_SIZE square box 0.3 m tall straddling the ceiling, authored with its
        # centre at vertex A so that the placement point P is the skylight's centre.
        (ax, az), (bx, bz) = SKYLIGHT_ZONE
        corners = [(ax, h, az), (bx, h, az), (bx, h, bz), (ax, h, bz)]
        gl.node("Roof__Geometry", mesh=gl.mesh("Roof__Geometry", *quad(*corners),
                                                gl.material("Zone", (0.7, 0.7, 0.7))))
        half = SKYLIGHT_SIZE / 2
        gl.node("Skylight", mesh=gl.mesh("Skylight", *box((half, 0.15, half)),
                                          gl.material("Aperture", hole=True)),
                translation=corners[0])
        gl.camera("Camera", (0.6, 1.6, 0.4), (2.5, 0.8, 2.1), 60.0)
        gl.write(out)
        return
    # The screen: its display faces -z, toward the user; a 3 cm body behind it.
    (sx0, sx1), (sy0, sy1) = SCREEN_X, SCREEN_Y
    z = SCREEN_Z
    display = quad((sx1, sy0, z), (sx0, sy0, z), (sx0, sy1, z), (sx1, sy1, z))
    gl.node("Screen", mesh=gl.mesh("Screen", *display, gl.material("Display", (SCREEN_KD,) * 3)))
    casing = gl.material("Casing", (0.1, 0.1, 0.1))
    gl.node("ScreenBody", mesh=gl.mesh("ScreenBody", *box(((sx1 - sx0) / 2, (sy1 - sy0) / 2, 0.0145)),
                                       casing), translation=((sx0 + sx1) / 2, (sy0 + sy1) / 2, z + 0.0155))
    gl.node("Stand", mesh=gl.mesh("Stand", *box((0.03, (sy0 - DESK_TOP) / 2, 0.02)), casing),
            translation=((sx0 + sx1) / 2, (sy0 + DESK_TOP) / 2, z + 0.05))
    # The zone the lamps may take, 1 cm under the ceiling, facing down.
    (ax, az), (bx, bz) = LAMP_ZONE
    zone = quad((ax, LAMP_Y, az), (bx, LAMP_Y, az), (bx, LAMP_Y, bz), (ax, LAMP_Y, bz))
    gl.node("LampZone__Geometry", mesh=gl.mesh("LampZone__Geometry", *zone,
                                                  gl.material("Zone", (0.7, 0.7, 0.7))))
    for k, (x, z) in enumerate(LAMPS):
        gl.spot_light("Lamp%d" % (k + 1), (x, LAMP_Y, z), (0.0, -1.0, 0.0), LAMP_CD, *LAMP_CONES)
    gl.camera("Camera", (0.6, 1.6, 0.4), (2.5, 0.8, 2.1), 60.0)
    gl.write(out)


def office_ies(scenes_dir, out):
    """The office of office-target whose lamps take a photometric file (problem.xml's
    <luminaire>): the LED downlight of tests/data/photometry (make_photometry.py
    there writes it), copied beside the problem."""
    office(scenes_dir, out, "office-ies")
    src = os.path.join(REPO, "tests", "data", "photometry", "downlight.ldt")
    with open(src, "rb") as f, open(os.path.join(out, "downlight.ldt"), "wb") as g:
        g.write(f.read())


def office_daylight(scenes_dir, out):
    """The office of office-target with no lamps and a skylight to place for the most
    daylight factor on the desk under the CIE overcast sky."""
    office(scenes_dir, out, "office-daylight", skylight=True)


# --------------------------------------------------------------------------- open office

# A 7.2 m x 4.8 m x 2.8 m open-plan office (Y up, x along its length, z across), ceiling,
# walls and floor of reflectance 0.7, 0.5 and 0.2, six downlights to place anywhere on
# the ceiling (0.3 m from the walls) and dim: "Em >= 500 lx and U0 >= 0.6 over the task
# area (0.85 m above the floor, less a 0.5 m border: problem.xml's <workplane>), the
# least electrical power".
# Built from nothing: no source geometry.
OPEN_OFFICE = (7.2, 2.8, 4.8)
OPEN_OFFICE_LAMPS = 6
OPEN_OFFICE_ZONE_MARGIN = 0.3  # m, the lamps' centres from the walls


def open_office(scenes_dir, out):
    """examples/open-office: the office with its lamps in a row (scene.gltf, for the
    search) and in the regular 3 x 2 array a designer lays first, half a spacing from
    the walls (grid.gltf, for grid.xml's dimming alone)."""
    open_office_scene(out, "scene", None)
    w, _, d = OPEN_OFFICE
    grid = [((i + 0.5) * w / 3, (j + 0.5) * d / 2) for j in range(2) for i in range(3)]
    open_office_scene(out, "grid", grid)


def open_office_scene(out, stem, lamps):
    """The open-plan office: the room, the ceiling zone the lamps may take and six
    lamps at `lamps` ((x, z) each), or authored in a row along the room's axis (not
    where a designer would put them), each emitting downlight.ldt. The task area is the
    problem's <workplane>, which receives light without touching it."""
    w, h, d = OPEN_OFFICE
    gl = Gltf("invlight tools/build_examples.py: open-office")
    room = gl.node("Room")
    office_room(gl, room, w, h, d)
    m = OPEN_OFFICE_ZONE_MARGIN
    ly = h - 0.01
    zone = quad((m, ly, m), (w - m, ly, m), (w - m, ly, d - m), (m, ly, d - m))
    gl.node("LampZone__Geometry", mesh=gl.mesh("LampZone__Geometry", *zone,
                                                  gl.material("Zone", (0.7, 0.7, 0.7))))
    row = [(m + (k + 0.5) * (w - 2 * m) / OPEN_OFFICE_LAMPS, d / 2)
           for k in range(OPEN_OFFICE_LAMPS)]
    for k, (x, z) in enumerate(lamps or row):
        gl.point_light("Lamp%d" % (k + 1), (x, ly, z), 100.0)
    gl.camera("Camera", (0.5, 1.6, 0.5), (4.0, 0.8, 3.0), 70.0)
    gl.write(out, stem)
    src = os.path.join(REPO, "tests", "data", "photometry", "downlight.ldt")
    with open(src, "rb") as f, open(os.path.join(out, "downlight.ldt"), "wb") as g:
        g.write(f.read())


CLASSROOM = (9.0, 3.0, 7.2)  # width x (along the board), height, depth z (board at z = 0)
CLASSROOM_LAMPS = 12
CLASSROOM_ZONE_MARGIN = 0.6  # m, the lamps' centres from the walls


def classroom(_scenes_dir, out):
    """examples/classroom: a 9.0 m x 7.2 m x 3.0 m classroom (reflectances 0.7 / 0.5 /
    0.2), twelve linear LED luminaires (linear.ldt: 1500 x 60 mm, 3000 lm, 25 W) hung
    0.05 m under the ceiling, authored in a row (the problems set them out), the ceiling
    zone they may take and a camera at the back. The board wall is z = 0; the pupils
    face it (-z)."""
    w, h, d = CLASSROOM
    gl = Gltf("invlight tools/build_examples.py: classroom")
    room = gl.node("Room")
    office_room(gl, room, w, h, d)
    m = CLASSROOM_ZONE_MARGIN
    ly = h - 0.05
    zone = quad((m, ly, m), (w - m, ly, m), (w - m, ly, d - m), (m, ly, d - m))
    gl.node("LampZone__Geometry", mesh=gl.mesh("LampZone__Geometry", *zone,
                                                  gl.material("Zone", (0.7, 0.7, 0.7))))
    for k in range(CLASSROOM_LAMPS):
        x = m + (k + 0.5) * (w - 2 * m) / CLASSROOM_LAMPS
        gl.point_light("Lamp%d" % (k + 1), (x, ly, d / 2), 100.0)
    gl.camera("Camera", (w / 2, 1.6, d - 0.3), (w / 2, 1.0, 0.0), 70.0)
    gl.write(out, "scene")
    # The luminaire: tests/data/photometry/linear.ldt's distribution behind a 300 mm
    # wide opal cover (luminaire 1520 x 320 mm, luminous area 1500 x 300 mm), so that
    # its luminance is a classroom luminaire's rather than a bare LED strip's.
    src = os.path.join(REPO, "tests", "data", "photometry", "linear.ldt")
    with open(src, encoding="ascii", newline="") as f:
        text = f.read()
    newline = "\r\n" if "\r\n" in text else "\n"
    lines = text.split(newline)
    lines[8] = "Linear LED luminaire 1500 mm, opal cover 300 mm (invlight example)"
    lines[10] = "classroom.ldt"
    lines[13] = "320"  # width of the luminaire, mm
    lines[16] = "300"  # width of the luminous area, mm
    with open(os.path.join(out, "classroom.ldt"), "w", encoding="ascii", newline="") as g:
        g.write(newline.join(lines))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scenes", default=os.path.join(os.path.dirname(REPO), "shared", "scenes"),
                    help="folder holding sponza/sponza.zip and conference/conference.zip")
    ap.add_argument("--out", default=os.path.join(REPO, "examples"), help="examples folder")
    ap.add_argument("--only", choices=["atrium-skylight", "atrium-colour", "conference-sun",
                                       "office-target", "office-ies", "office-daylight",
                                       "open-office", "classroom"])
    ap.add_argument("--wall-value", type=float,
                    help="write only atrium-colour, with this inner-wall HSV value, into --out")
    args = ap.parse_args()
    if args.wall_value is not None:
        atrium_colour(args.scenes, args.out, args.wall_value)
        return
    builders = {"atrium-skylight": atrium_skylight, "atrium-colour": atrium_colour,
                "conference-sun": conference, "office-target": office,
                "office-ies": office_ies, "office-daylight": office_daylight,
                "open-office": open_office, "classroom": classroom}
    for name, build in builders.items():
        if args.only in (None, name):
            build(args.scenes, os.path.join(args.out, name))


if __name__ == "__main__":
    main()
