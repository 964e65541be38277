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
  blender_room.gltf  a small room as Blender's glTF exporter (4.x) writes one: objects named
                as in Blender (Floor, Cube, Ball, Sun, Spot, Camera), Y up, lights in
                KHR_lights_punctual (the sun's strength as lux, the spot's watts as candela:
                W / 4 pi x 683 / 1000), the floor's tiling through KHR_texture_transform (a
                Mapping node's scale), a glowing cube through KHR_materials_emissive_strength,
                a repeating, mipmapped sampler, a camera, and an action (animation
                'BallAction'): the ball bounces twice in 2 s, sampled at 12 keys as
                Blender bakes one (LINEAR)
  screens.gltf  two upright 1 m squares in the XY plane facing +Z, centred at x = -0.7
                and x = 0.7: 'screen', alphaMode MASK (cutoff 0.5) with a texture of
                4 x 4 round holes (alpha 0 inside, 1 outside); 'pane', alphaMode BLEND,
                alpha 0.3, untextured (a tinted glass)

Usage: content/examples/assets/make_assets.py   (writes next to itself)
"""
import base64
import json
import math
import os
import struct
import zlib


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


def png(width, height, pixel):
    """An RGBA8 PNG of pixel(x, y) -> (r, g, b, a), rows top to bottom, unfiltered."""
    rows = b"".join(b"\x00" + b"".join(bytes(pixel(x, y)) for x in range(width)) for y in range(height))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    header = struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)  # 8 bits, RGBA
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows, 9)) +
            chunk(b"IEND", b""))


def hole_pattern(size=128, holes=4, radius=0.34):
    """Orange with `holes` x `holes` round holes (alpha 0) of `radius` cells."""
    cell = size / holes

    def pixel(x, y):
        dx = (x + 0.5) % cell / cell - 0.5
        dy = (y + 0.5) % cell / cell - 0.5
        return (230, 140, 40, 0 if dx * dx + dy * dy < radius * radius else 255)

    return png(size, size, pixel)


def screens():
    """Two upright unit squares sharing one quad (positions, normals, uvs, indices)."""
    positions = [[-0.5, -0.5, 0.0], [0.5, -0.5, 0.0], [0.5, 0.5, 0.0], [-0.5, 0.5, 0.0]]
    normals = [[0.0, 0.0, 1.0]] * 4
    uvs = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]]  # glTF's uv origin is the image's top left
    indices = [0, 1, 2, 0, 2, 3]
    pos = b"".join(struct.pack("<3f", *p) for p in positions)
    nor = b"".join(struct.pack("<3f", *n) for n in normals)
    tex = b"".join(struct.pack("<2f", *t) for t in uvs)
    idx = b"".join(struct.pack("<I", i) for i in indices)
    blob = pos + nor + tex + idx
    views, offset = [], 0
    for part in (pos, nor, tex, idx):
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(part)})
        offset += len(part)
    accessors = [
        {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-0.5, -0.5, 0.0],
         "max": [0.5, 0.5, 0.0]},
        {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
        {"bufferView": 3, "componentType": 5125, "count": 6, "type": "SCALAR"},
    ]
    primitive = {"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "mode": 4}
    image = "data:image/png;base64," + base64.b64encode(hole_pattern()).decode()
    return {
        "asset": {"version": "2.0", "generator": "content/examples/assets/make_assets.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"name": "screen", "mesh": 0, "translation": [-0.7, 0.0, 0.0]},
                  {"name": "pane", "mesh": 1, "translation": [0.7, 0.0, 0.0]}],
        "materials": [
            {"name": "screen", "alphaMode": "MASK", "alphaCutoff": 0.5, "doubleSided": True,
             "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}},
            {"name": "pane", "alphaMode": "BLEND", "doubleSided": True,
             "pbrMetallicRoughness": {"baseColorFactor": [0.3, 0.6, 0.9, 0.3]}},
        ],
        "meshes": [{"name": "screen", "primitives": [dict(primitive, material=0)]},
                   {"name": "pane", "primitives": [dict(primitive, material=1)]}],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"magFilter": 9729, "minFilter": 9729}],
        "images": [{"uri": image}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
    }


def checker(size=64, cells=8):
    """Light and dark grey squares, `cells` per side, with a thin dark line at each edge."""
    cell = size // cells

    def pixel(x, y):
        if x % cell == 0 or y % cell == 0:
            return (40, 40, 44, 255)
        light = (x // cell + y // cell) % 2 == 0
        return (200, 196, 188, 255) if light else (120, 124, 130, 255)

    return png(size, size, pixel)


def blender_room():
    """A floor, a glowing cube and a ball, lit by a sun and a spot, with a camera."""
    blob = b""
    views, accessors, meshes = [], [], []

    def add(data, fmt, count, kind, component=5126, extra=None):
        nonlocal blob
        packed = b"".join(struct.pack(fmt, *d) if isinstance(d, (list, tuple)) else struct.pack(fmt, d) for d in data)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(packed)})
        blob += packed
        accessor = {"bufferView": len(views) - 1, "componentType": component, "count": count, "type": kind}
        accessor.update(extra or {})
        accessors.append(accessor)
        return len(accessors) - 1

    def mesh(name, positions, normals, uvs, indices, material):
        lo = [min(p[k] for p in positions) for k in range(3)]
        hi = [max(p[k] for p in positions) for k in range(3)]
        attributes = {"POSITION": add(positions, "<3f", len(positions), "VEC3", extra={"min": lo, "max": hi}),
                      "NORMAL": add(normals, "<3f", len(normals), "VEC3")}
        if uvs:
            attributes["TEXCOORD_0"] = add(uvs, "<2f", len(uvs), "VEC2")
        primitive = {"attributes": attributes, "indices": add(indices, "<H", len(indices), "SCALAR", 5123),
                     "material": material}
        meshes.append({"name": name, "primitives": [primitive]})
        return len(meshes) - 1

    floor = mesh("Plane", [[-4, 0, 4], [4, 0, 4], [4, 0, -4], [-4, 0, -4]], [[0, 1, 0]] * 4,
                 [[0, 1], [1, 1], [1, 0], [0, 0]], [0, 1, 2, 0, 2, 3], 0)
    box, ball_mesh = block(), ball(rings=12, segments=24)
    cube = mesh("Cube", unpack(box, 0, "<3f"), unpack(box, 1, "<3f"), None, unpack(box, 2, "<I"), 1)
    sphere = mesh("Sphere", unpack(ball_mesh, 0, "<3f"), unpack(ball_mesh, 1, "<3f"), None, unpack(ball_mesh, 2, "<I"), 2)
    # The bounce: |sin| arcs, 1.2 m high, twice in 2 s, with a 0.6 m drift along X.
    key_times = [round(2.0 * k / 11, 6) for k in range(12)]
    key_values = [[round(0.9 - 0.3 * t, 6), round(0.5 + 1.2 * abs(math.sin(math.pi * t)), 6), 0.6] for t in key_times]
    times_accessor = add(key_times, "<f", len(key_times), "SCALAR", extra={"min": [key_times[0]], "max": [key_times[-1]]})
    values_accessor = add(key_values, "<3f", len(key_values), "VEC3")
    s = math.sqrt(0.5)
    # Blender's default spot: 45 degrees wide (spot_size), blend 0.15; outer = size / 2,
    # inner = outer x (1 - blend), as the exporter writes them.
    outer = math.radians(45.0) / 2.0
    return {
        "asset": {"version": "2.0", "generator": "content/examples/assets/make_assets.py (Blender glTF I/O 4.x conventions)"},
        "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_texture_transform"],
        "extensions": {"KHR_lights_punctual": {"lights": [
            {"name": "Sun", "type": "directional", "color": [1.0, 0.95, 0.88], "intensity": 3.0},
            {"name": "Spot", "type": "spot", "color": [0.75, 0.85, 1.0], "intensity": 54.35,
             "spot": {"innerConeAngle": round(outer * 0.85, 6), "outerConeAngle": round(outer, 6)}}]}},
        "scene": 0,
        "scenes": [{"name": "Scene", "nodes": [0, 1, 2, 3, 4, 5]}],
        "nodes": [
            {"name": "Floor", "mesh": floor},
            {"name": "Cube", "mesh": cube, "translation": [-0.8, 0.5, 0.0]},
            {"name": "Ball", "mesh": sphere, "translation": [0.9, 0.5, 0.6]},
            # Sun: turned 60 degrees down (about X) and 30 degrees about Y.
            {"name": "Sun", "rotation": [-0.482963, 0.224144, 0.129410, 0.836516],
             "extensions": {"KHR_lights_punctual": {"light": 0}}},
            # Spot: 3 m up, looking straight down (-Z turned -90 degrees about X).
            {"name": "Spot", "translation": [0.9, 3.0, 0.6], "rotation": [-s, 0.0, 0.0, s],
             "extensions": {"KHR_lights_punctual": {"light": 1}}},
            # Camera: 5.5 m back, 2.6 m up, pitched 22 degrees down.
            {"name": "Camera", "camera": 0, "translation": [0.0, 2.6, 5.5], "rotation": [-0.190809, 0.0, 0.0, 0.981627]},
        ],
        "animations": [{"name": "BallAction",
                        "samplers": [{"input": times_accessor, "output": values_accessor, "interpolation": "LINEAR"}],
                        "channels": [{"sampler": 0, "target": {"node": 2, "path": "translation"}}]}],
        "cameras": [{"name": "Camera", "type": "perspective",
                     "perspective": {"aspectRatio": 1.7778, "yfov": 0.6, "znear": 0.1, "zfar": 100.0}}],
        "materials": [
            {"name": "Floor", "pbrMetallicRoughness": {
                "baseColorTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"scale": [4.0, 4.0]}}},
                "metallicFactor": 0.0, "roughnessFactor": 0.7}},
            {"name": "Lamp", "emissiveFactor": [1.0, 0.55, 0.25],
             "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 1.0}},
             "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.6, 0.4, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.5}},
            {"name": "Ball", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.35, 0.75, 1.0], "metallicFactor": 0.0,
                                                      "roughnessFactor": 0.4}},
        ],
        "textures": [{"sampler": 0, "source": 0}],
        "samplers": [{"magFilter": 9729, "minFilter": 9987}],  # Blender's: linear, trilinear mipmaps, repeat
        "images": [{"name": "checker", "mimeType": "image/png",
                    "uri": "data:image/png;base64," + base64.b64encode(checker()).decode()}],
        "meshes": meshes,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
    }


def unpack(asset, accessor, fmt):
    """Accessor `accessor` of a one-buffer asset from gltf(), as a list of tuples (or ints)."""
    blob = base64.b64decode(asset["buffers"][0]["uri"].split(",", 1)[1])
    view = asset["bufferViews"][asset["accessors"][accessor]["bufferView"]]
    size = struct.calcsize(fmt)
    items = [struct.unpack_from(fmt, blob, view["byteOffset"] + i * size)
             for i in range(view["byteLength"] // size)]
    return [item[0] if len(item) == 1 else list(item) for item in items]


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    metal_ball = ball("metal_ball", (1.0, 0.78, 0.34), metallic=1.0, roughness=0.3)  # gold-like F0
    for name, asset in (("block", block()), ("ball", ball()), ("metal_ball", metal_ball), ("curtain", curtain()),
                        ("screens", screens()), ("blender_room", blender_room())):
        with open(os.path.join(here, name + ".gltf"), "w") as out:
            json.dump(asset, out, indent=1)
            out.write("\n")


if __name__ == "__main__":
    main()
