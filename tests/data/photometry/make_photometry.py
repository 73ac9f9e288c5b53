#!/usr/bin/env python3
"""Writes the photometric test files of this folder (see README.md): synthetic tables
with closed-form fluxes, each symmetry written with and without it, and four
manufacturer-style luminaires. Python standard library only; run it from anywhere:
the files land beside this script. The files are committed, so tests never run it."""

import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))


def num(x, comma=False):
    s = ("%.4f" % x).rstrip("0").rstrip(".")
    if s in ("-0", ""):
        s = "0"
    return s.replace(".", ",") if comma else s


def wrap(values, per_line=10):
    out = []
    for k in range(0, len(values), per_line):
        out.append(" ".join(num(v) for v in values[k:k + per_line]))
    return out


def write(name, lines, encoding="latin-1", crlf=False):
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(("\r\n" if crlf else "\n").join(lines).encode(encoding) + (b"\r\n" if crlf else b"\n"))


def ies(name, header, keywords, h, v, intensity, lamps=1, lumens=-1.0, mult=1.0,
        ptype=1, units=2, width=0.0, length=0.0, height=0.0, ballast=1.0,
        factor=1.0, watts=0.0, tilt=None, crlf=False):
    """An IES file; `intensity(h, v)` in cd before the multipliers."""
    lines = [header] if header else []
    lines += keywords
    if tilt is None:
        lines.append("TILT=NONE")
    else:
        geometry, angles, factors = tilt
        lines.append("TILT=INCLUDE")
        lines.append(str(geometry))
        lines.append(str(len(angles)))
        lines += wrap(angles)
        lines += wrap(factors)
    lines.append("%d %s %s %d %d %d %d %s %s %s" % (
        lamps, num(lumens), num(mult), len(v), len(h), ptype, units,
        num(width), num(length), num(height)))
    lines.append("%s %s %s" % (num(ballast), ("%.5f" % factor).rstrip("0").rstrip("."), num(watts)))
    lines += wrap(v)
    lines += wrap(h)
    for a in h:
        lines += wrap([intensity(a, b) for b in v])
    write(name, lines, crlf=crlf)


def ldt(name, company, isym, c_all, gammas, intensity, lamp_flux, lor, ityp=1,
        luminaire="", number="", lamps=1, lamp_type="", watts=0.0, dims=(0, 0, 0),
        area=(0, 0), area_heights=(0, 0, 0, 0), cct="3000", cri="80", comma=False,
        crlf=True):
    """A EULUMDAT file; `intensity(c, g)` in cd/klm for the planes Isym keeps."""
    mc = len(c_all)
    dc = c_all[1] - c_all[0] if mc > 1 else 0
    ng = len(gammas)
    dg = gammas[1] - gammas[0]
    planes = {0: c_all, 1: c_all[:1], 2: c_all[:mc // 2 + 1],
              3: c_all[mc // 4:3 * mc // 4 + 1], 4: c_all[:mc // 4 + 1]}[isym]
    n = lambda x: num(x, comma)
    lines = [company, str(ityp), str(isym), str(mc), n(dc), str(ng), n(dg), "R-" + name,
             luminaire, number, name, "2026-12-01 invlight tests",
             n(dims[0]), n(dims[1]), n(dims[2]), n(area[0]), n(area[1])]
    lines += [n(x) for x in area_heights]
    down = 100.0  # every file here sends its light downward
    lines += [n(down), n(100.0 * lor), n(1.0), n(0.0), "1", str(lamps), lamp_type,
              n(lamp_flux), cct, cri, n(watts)]
    lines += [n(0.5 + 0.04 * k) for k in range(10)]
    lines += [n(c) for c in c_all]
    lines += [n(g) for g in gammas]
    for c in planes:
        lines += [n(intensity(c, g)) for g in gammas]
    write(name, lines, crlf=crlf)


def frange(a, b, step):
    k = int(round((b - a) / step))
    return [a + i * step for i in range(k + 1)]


def cos_d(x):
    return math.cos(math.radians(x))


def sin_d(x):
    return math.sin(math.radians(x))


# 1. I(γ) = 100·cos γ below the horizon, every degree: flux π·100 lm.
I0 = 100.0
cosine = lambda c, g: I0 * cos_d(g) if g <= 90 else 0.0
ies("cosine.ies", "IESNA:LM-63-2002",
    ["[TEST] synthetic", "[MANUFAC] invlight tests", "[LUMINAIRE] Lambertian point, I = 100 cd cos g"],
    [0.0], frange(0, 90, 1), cosine)
ldt("cosine.ldt", "invlight tests", 1, frange(0, 345, 15), frange(0, 180, 1),
    lambda c, g: cosine(c, g), 1000.0, math.pi * I0 / 1000.0, luminaire="Lambertian point",
    lamp_type="synthetic")

# 2. Light toward C0 only: I = 200·cos γ·(1 + cos C)/2, every 15° of C and 5° of γ.
asym = lambda c, g: 200.0 * cos_d(g) * 0.5 * (1.0 + cos_d(c)) if g <= 90 else 0.0
ies("asymmetric.ies", "IESNA:LM-63-2002", ["[TEST] synthetic", "[LUMINAIRE] toward C0"],
    frange(0, 360, 15), frange(0, 90, 5), asym)

# 3. Each symmetry, written with it and in full (the reference). Lamp flux 1000 lm and
# conversion 1 make cd/klm equal cd, so every file expands to the same numbers.
shapes = {
    "rotational": (lambda c: 1.0, [0.0], 1),
    "quadrant": (lambda c: 1.0 + 0.5 * cos_d(2 * c), frange(0, 90, 15), 4),
    "c0": (lambda c: 1.0 + 0.5 * cos_d(c) + 0.2 * cos_d(2 * c), frange(0, 180, 15), 2),
    "c90": (lambda c: 1.0 + 0.5 * sin_d(c), frange(90, 270, 15), 3),
}
gam = frange(0, 180, 10)
for key, (f, planes, isym) in shapes.items():
    table = lambda c, g, f=f: round(300.0 * f(c) * (1.2 + cos_d(g)), 1)
    # The quadrant file is IESNA91, whose ballast-lamp factor (2) the reader applies,
    # against a ballast factor of 0.5; the rotational one is headerless LM-63-1986.
    header = {"rotational": None, "quadrant": "IESNA91", "c90": "IESNA:LM-63-1995"}.get(key, "IESNA:LM-63-2002")
    kw = ["symmetry test: %s" % key] if header is None else ["[TEST] symmetry %s" % key]
    ballast, factor = (0.5, 2.0) if key == "quadrant" else (1.0, 1.0)
    ies("sym-%s.ies" % key, header, kw, planes, gam, table, ballast=ballast, factor=factor)
    ies("sym-%s-full.ies" % key, "IESNA:LM-63-2002", ["[TEST] symmetry %s, written out" % key],
        frange(0, 360, 15), gam, table)
    ldt("sym-%s.ldt" % key, "invlight tests", isym, frange(0, 345, 15), gam, table, 1000.0, 1.0,
        comma=(key == "c0"))
ldt("sym-c90-full.ldt", "invlight tests", 0, frange(0, 345, 15), gam,
    lambda c, g: round(300.0 * (1.0 + 0.5 * sin_d(c)) * (1.2 + cos_d(g)), 1), 1000.0, 1.0)

# 4. Manufacturer-style luminaires, each with its closed-form flux (README.md).
# 4a. LED downlight, I = I0·cos⁴γ, Φ = 2π·I0/5 = 1700 lm from a 2000 lm module.
i_dl = 1700.0 * 5.0 / (2.0 * math.pi)
dl = lambda c, g: i_dl * cos_d(g) ** 4 if g <= 90 else 0.0
ies("downlight.ies", "IESNA:LM-63-2002",
    ["[TEST] LT-2026-0412", "[TESTLAB] invlight photometry lab", "[ISSUEDATE] 01-DEC-2026",
     "[MANUFAC] Lumen & Co.", "[LUMCAT] DL150-840-WH", "[LUMINAIRE] Recessed LED downlight 150 mm, matt reflector",
     "[LAMPCAT] LED module 2000 lm 840", "[LAMP] 1 x LED 2000 lm", "[_ANALYTIC_FLUX] 1700"],
    [0.0], frange(0, 90, 2.5), lambda c, g: dl(c, g) / 2.0, lumens=2000.0, mult=2.0,
    width=-0.15, length=-0.15, height=0.02, watts=18.5, crlf=True)
ldt("downlight.ldt", "Lumen & Co.", 1, frange(0, 330, 30), frange(0, 180, 2.5),
    lambda c, g: dl(c, g) / 2.0, 2000.0, 0.85, luminaire="Recessed LED downlight 150 mm",
    number="DL150-840-WH", lamp_type="LED module 2000 lm 840", watts=18.5,
    dims=(170, 0, 95), area=(150, 0), area_heights=(0, 0, 0, 0), cct="4000", cri="83")

# 4b. Batwing office panel 600 × 600, 4 × 1350 lm T5, efficiency 0.68:
# I = I0·cos γ·(0.6 + 2.4 sin²γ)·(1 + 0.25 cos 2C), Φ = 2π·I0·(0.3 + 0.6) = 3672 lm.
i_bw = 0.68 * 5400.0 / (2.0 * math.pi * 0.9)
bw = lambda c, g: (i_bw * cos_d(g) * (0.6 + 2.4 * sin_d(g) ** 2) * (1.0 + 0.25 * cos_d(2 * c))
                   if g <= 90 else 0.0)
ies("batwing.ies", "IES:LM-63-2019",
    ["[TEST] LT-2026-0977", "[TESTLAB] invlight photometry lab", "[ISSUEDATE] 01-DEC-2026",
     "[MANUFAC] Lichtwerk Lüdenscheid GmbH", "[LUMCAT] OP-600-4T5",
     "[LUMINAIRE] Recessed office panel 600 × 600, batwing louvre",
     "[MORE] specular aluminium, UGR < 19", "[LAMP] 4 x T5 14 W, 1350 lm", "[_ANALYTIC_FLUX] 3672"],
    frange(0, 90, 22.5), frange(0, 90, 5), bw, lamps=4, lumens=1350.0,
    units=1, width=0.6 / 0.3048, length=0.6 / 0.3048, height=0.0, factor=1.10001, watts=64.0)
ldt("batwing.ldt", "Lichtwerk Lüdenscheid GmbH", 4, frange(0, 337.5, 22.5), frange(0, 180, 5),
    lambda c, g: bw(c, g) * 1000.0 / 5400.0, 5400.0, 0.68, ityp=3,
    luminaire="Recessed office panel 600 × 600", number="OP-600-4T5", lamps=4,
    lamp_type="T5 14 W", watts=64.0, dims=(597, 597, 70), area=(590, 590), cct="4000", cri="85",
    comma=True)

# 4c. Asymmetric wall washer (LED, absolute photometry), light thrown toward C0:
# I = I0·(0.3 cos γ + sin γ cos γ)·(1 + 0.8 cos C), Φ = 2π·I0·(0.15 + 1/3) = 1200 lm.
i_ww = 1200.0 / (2.0 * math.pi * (0.15 + 1.0 / 3.0))
ww = lambda c, g: (i_ww * (0.3 * cos_d(g) + sin_d(g) * cos_d(g)) * (1.0 + 0.8 * cos_d(c))
                   if g <= 90 else 0.0)
ies("wallwasher.ies", "IESNA:LM-63-1995",
    ["[TEST] LT-2026-1203", "[MANUFAC] Lumen & Co.", "[LUMCAT] WW-LED-30",
     "[LUMINAIRE] Recessed LED wall washer, lens toward C0", "[LAMP] LED, absolute photometry",
     "[_ANALYTIC_FLUX] 1200"],
    frange(0, 180, 15), frange(0, 90, 5), ww, lumens=-1.0, width=0.12, length=0.12, watts=14.0)
ldt("wallwasher.ldt", "Lumen & Co.", 2, frange(0, 345, 15), frange(0, 180, 5),
    lambda c, g: ww(c, g) * 1000.0 / 1200.0, 1200.0, 1.0, ityp=3,
    luminaire="Recessed LED wall washer", number="WW-LED-30", lamp_type="LED", watts=14.0,
    dims=(130, 130, 80), area=(120, 120))

# 4e. A linear luminaire 1500 × 60 mm, the same one written in both formats, whose
# along-the-lamp plane is unmistakable: cosine-like along its axis, batwing across it.
# With C' the plane angle from the luminaire axis:
# I = I0·cos γ·(1 + 1.5 sin²γ sin²C'), Φ = π·I0·(1 + 1.5/4) = 3000 lm.
# IES LM-63 lays the length along 0°–180° (C' = C); EULUMDAT along C90–C270
# (C' = C − 90°, sin²C' = cos²C).
i_ln = 3000.0 / (math.pi * 1.375)
ln = lambda cp, g: (i_ln * cos_d(g) * (1.0 + 1.5 * sin_d(g) ** 2 * sin_d(cp) ** 2)
                    if g <= 90 else 0.0)
ies("linear.ies", "IESNA:LM-63-2002",
    ["[TEST] LT-2026-1500", "[MANUFAC] Lumen & Co.", "[LUMCAT] LN-1500",
     "[LUMINAIRE] Linear LED luminaire 1500 mm, batwing across the lamp",
     "[LAMP] LED, absolute photometry", "[_ANALYTIC_FLUX] 3000"],
    frange(0, 90, 15), frange(0, 90, 5), ln, lumens=-1.0, width=0.06, length=1.5, watts=25.0)
ldt("linear.ldt", "Lumen & Co.", 4, frange(0, 345, 15), frange(0, 180, 5),
    lambda c, g: ln(c - 90.0, g) * 1000.0 / 3000.0, 3000.0, 1.0, ityp=2,
    luminaire="Linear LED luminaire 1500 mm", number="LN-1500", lamp_type="LED", watts=25.0,
    dims=(1520, 80, 50), area=(1500, 60))

# 4d. Type B floodlight, 250 W metal halide (20000 lm), tilt data included:
# I = I0·cos⁶V·cos³H over V, H in ±90°, dω = cos H dH dV: Φ = I0·(5π/16)·(3π/8) = 14000 lm.
i_fl = 14000.0 / ((5.0 * math.pi / 16.0) * (3.0 * math.pi / 8.0))
fl = lambda h, v: i_fl * cos_d(v) ** 6 * cos_d(h) ** 3
ies("floodlight.ies", "IESNA:LM-63-2002",
    ["[TEST] LT-2026-0055", "[MANUFAC] Lumen & Co.", "[LUMCAT] FL-250-MH",
     "[LUMINAIRE] Floodlight, symmetric beam", "[LAMP] 1 x HIT 250 W, 20000 lm", "[_ANALYTIC_FLUX] 14000"],
    frange(0, 90, 5), frange(-90, 90, 5), fl, lumens=20000.0, ptype=2, width=0.4, length=0.3,
    watts=270.0, tilt=(1, frange(0, 90, 15), [1.0, 0.99, 0.97, 0.94, 0.9, 0.86, 0.82]))

# 5. A glTF placing two EXT_lights_ies profiles: asymmetric.ies by uri on a node turned
# so that its aim (local −Z) is world −Y and its C0 (local +X) world −Z, with multiplier 2
# and colour (1, 0.5, 0.25); cosine.ies embedded in a buffer view, aimed down.
import base64
import json


def quat_mul(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return [aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
            aw * bw - ax * bx - ay * by - az * bz]


def quat_axis(axis, degrees):
    s = math.sin(math.radians(degrees) / 2.0)
    return [axis[0] * s, axis[1] * s, axis[2] * s, math.cos(math.radians(degrees) / 2.0)]


down = quat_axis((1, 0, 0), -90.0)
turned = quat_mul(quat_axis((0, 1, 0), 90.0), down)
profile = open(os.path.join(HERE, "cosine.ies"), "rb").read()
gltf = {
    "asset": {"version": "2.0", "generator": "invlight tests/data/photometry/make_photometry.py"},
    "extensionsUsed": ["EXT_lights_ies"],
    "extensions": {"EXT_lights_ies": {"lights": [
        {"uri": "asymmetric.ies"},
        {"bufferView": 0, "mimeType": "application/x-ies-lm-63", "name": "cosine"},
    ]}},
    "buffers": [{"byteLength": len(profile),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(profile).decode()}],
    "bufferViews": [{"buffer": 0, "byteLength": len(profile)}],
    "scene": 0,
    "scenes": [{"nodes": [0, 1]}],
    "nodes": [
        {"name": "WallWasher", "translation": [1.0, 3.0, 0.0], "rotation": [round(x, 12) for x in turned],
         "scale": [2.0, 2.0, 2.0],
         "extensions": {"EXT_lights_ies": {"light": 0, "multiplier": 2.0, "color": [1.0, 0.5, 0.25]}}},
        {"translation": [0.0, 2.0, 0.0], "rotation": [round(x, 12) for x in down],
         "extensions": {"EXT_lights_ies": {"light": 1}}},
    ],
}
with open(os.path.join(HERE, "luminaires.gltf"), "w") as f:
    json.dump(gltf, f, indent=1)
    f.write("\n")
