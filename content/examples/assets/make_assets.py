#!/usr/bin/env python3
"""Writes the small glTF assets the light examples are built from, so that those
examples need nothing outside the project (../shared/content may be missing in a
fresh clone). Deterministic: running it again gives the same bytes.

  block.gltf    unit cube centred on the origin, flat normals (place and scale it
                into floors, walls, pillars)
  ball.gltf     sphere of radius 0.5 centred on the origin, smooth normals
  metal_ball.gltf  the same sphere, gold-coloured metal (metallic 1, roughness 0.3)
  curtain.gltf  hair: 240 wavy strands of 14 points hanging 1 m down from a 1.2 m
                rod along X at y = 1, as one LINES primitive (consecutive segments
                that share an index form one strand); needs 'width' in the scene

Usage: content/examples/assets/make_assets.py   (writes next to itself)
"""
import base64
import json
import math
import os
import struct


def gltf(name, positions, normals, indices, mode, colour, metallic=0.0, roughness=0.8):
    """One mesh, one node, one material; the buffer as a data URI. The material is not
    metal and fairly rough unless asked: glTF's defaults (metallic 1, roughness 1)
    would make it rough metal."""
    pos = b"".join(struct.pack("<3f", *p) for p in positions)
    nor = b"".join(struct.pack("<3f", *n) for n in normals) if normals else b""
    idx = b"".join(struct.pack("<I", i) for i in indices)
    blob = pos + nor + idx
    lo = [min(p[k] for p in positions) for k in range(3)]
    hi = [max(p[k] for p in positions) for k in range(3)]
    views = [{"buffer": 0, "byteOffset": 0, "byteLength": len(pos)}]
    accessors = [{"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
                  "min": lo, "max": hi}]
    attributes = {"POSITION": 0}
    if normals:
        views.append({"buffer": 0, "byteOffset": len(pos), "byteLength": len(nor)})
        accessors.append({"bufferView": 1, "componentType": 5126, "count": len(normals), "type": "VEC3"})
        attributes["NORMAL"] = 1
    views.append({"buffer": 0, "byteOffset": len(pos) + len(nor), "byteLength": len(idx)})
    accessors.append({"bufferView": len(views) - 1, "componentType": 5125, "count": len(indices),
                      "type": "SCALAR"})
    return {
        "asset": {"version": "2.0", "generator": "content/examples/assets/make_assets.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": name, "mesh": 0}],
        "materials": [{"name": name, "pbrMetallicRoughness": {"baseColorFactor": colour + [1.0],
                                                              "metallicFactor": metallic, "roughnessFactor": roughness}}],
        "meshes": [{"name": name, "primitives": [
            {"attributes": attributes, "indices": len(accessors) - 1, "mode": mode, "material": 0}]}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
    }


def block():
    positions, normals, indices = [], [], []
    for axis in range(3):
        for sign in (1.0, -1.0):
            n = [0.0, 0.0, 0.0]
            n[axis] = sign
            u, v = [(axis + 1) % 3, (axis + 2) % 3]
            base = len(positions)
            for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis], p[u], p[v] = 0.5 * sign, 0.5 * a, 0.5 * b
                positions.append(p)
                normals.append(n)
            # (u, v, axis) is right-handed, so (0,1,2) winds counter-clockwise seen from +axis.
            quad = [0, 1, 2, 0, 2, 3] if sign > 0 else [0, 2, 1, 0, 3, 2]
            indices += [base + i for i in quad]
    return gltf("block", positions, normals, indices, 4, [0.72, 0.72, 0.68])


def ball(name="ball", colour=(0.75, 0.28, 0.2), metallic=0.0, roughness=0.8, rings=16, segments=32):
    positions, normals, indices = [], [], []
    for r in range(rings + 1):
        theta = math.pi * r / rings
        for s in range(segments + 1):
            phi = 2.0 * math.pi * s / segments
            n = [math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi)]
            normals.append([round(c, 6) for c in n])
            positions.append([round(0.5 * c, 6) for c in n])
    for r in range(rings):
        for s in range(segments):
            a, b = r * (segments + 1) + s, (r + 1) * (segments + 1) + s
            if r > 0:  # the first ring's other triangle would have two corners at the pole
                indices += [a, b, a + 1]
            if r < rings - 1:
                indices += [a + 1, b, b + 1]
    return gltf(name, positions, normals, indices, 4, list(colour), metallic, roughness)


def curtain(strands=240, points=14):
    positions, indices = [], []
    for k in range(strands):
        x = -0.6 + 1.2 * (k + 0.5) / strands
        phase = 2.399963 * k  # the golden angle: neighbouring strands do not wave together
        for i in range(points):
            t = i / (points - 1)
            sway = 0.03 * t * math.sin(phase + 5.0 * t)
            positions.append([round(x + 0.4 * sway, 6), round(1.0 - t, 6), round(sway, 6)])
            if i:
                indices += [len(positions) - 2, len(positions) - 1]
    return gltf("curtain", positions, None, indices, 1, [0.55, 0.33, 0.16])


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    metal_ball = ball("metal_ball", (1.0, 0.78, 0.34), metallic=1.0, roughness=0.3)  # gold-like F0
    for name, asset in (("block", block()), ("ball", ball()), ("metal_ball", metal_ball), ("curtain", curtain())):
        with open(os.path.join(here, name + ".gltf"), "w") as out:
            json.dump(asset, out, indent=1)
            out.write("\n")


if __name__ == "__main__":
    main()
