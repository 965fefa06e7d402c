#!/usr/bin/env python3
"""Writes a scene lit by a large emitter close to what it lights (solid-angle sampling of
triangle lights, shaders/lights/triangle_light.glsl): a floor with two boxes under a square
panel 2.4 across hanging 0.9 above it, facing down, seen from the side (OUT_DIR/scene.gltf,
embedded buffer).

    python3 bench/make_near_light_scene.py OUT_DIR
"""
import base64
import json
import os
import struct
import sys


def quad(corner, u, v):
    p = [corner, [corner[i] + u[i] for i in range(3)], [corner[i] + u[i] + v[i] for i in range(3)],
         [corner[i] + v[i] for i in range(3)]]
    return p, [0, 1, 2, 0, 2, 3]


def box(lo, hi):
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    faces = [quad([x0, y1, z1], [x1 - x0, 0, 0], [0, 0, z0 - z1]),   # top (+y)
             quad([x0, y0, z1], [x1 - x0, 0, 0], [0, y1 - y0, 0]),   # front (+z)
             quad([x1, y0, z0], [x0 - x1, 0, 0], [0, y1 - y0, 0]),   # back (-z)
             quad([x1, y0, z1], [0, 0, z0 - z1], [0, y1 - y0, 0]),   # right (+x)
             quad([x0, y0, z0], [0, 0, z1 - z0], [0, y1 - y0, 0])]   # left (-x)
    pos, idx = [], []
    for p, i in faces:
        idx += [len(pos) + k for k in i]
        pos += p
    return pos, idx


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    meshes = [("floor", quad([-4, 0, 4], [8, 0, 0], [0, 0, -8]), 0),
              ("box a", box([-1.0, 0, -0.6], [-0.3, 0.5, 0.2]), 1),
              ("box b", box([0.4, 0, -0.2], [1.1, 0.3, 0.6]), 1),
              ("panel", quad([-1.2, 0.9, -1.2], [2.4, 0, 0], [0, 0, 2.4]), 2)]
    blob = bytearray()
    views, accessors, gmeshes, nodes = [], [], [], []
    for name, (pos, idx), material in meshes:
        off = len(blob)
        blob += b"".join(struct.pack("<3f", *p) for p in pos)
        views.append({"buffer": 0, "byteOffset": off, "byteLength": 12 * len(pos)})
        lo = [min(p[i] for p in pos) for i in range(3)]
        hi = [max(p[i] for p in pos) for i in range(3)]
        accessors.append({"bufferView": len(views) - 1, "componentType": 5126, "count": len(pos), "type": "VEC3",
                          "min": lo, "max": hi})
        off = len(blob)
        blob += b"".join(struct.pack("<I", i) for i in idx)
        views.append({"buffer": 0, "byteOffset": off, "byteLength": 4 * len(idx)})
        accessors.append({"bufferView": len(views) - 1, "componentType": 5125, "count": len(idx), "type": "SCALAR"})
        gmeshes.append({"name": name, "primitives": [{"attributes": {"POSITION": len(accessors) - 2},
                                                      "indices": len(accessors) - 1, "material": material}]})
        nodes.append({"name": name, "mesh": len(gmeshes) - 1})
    # Camera at (0, 0.45, 3.2) looking at (0, 0.2, 0).
    nodes.append({"name": "camera", "camera": 0, "translation": [0, 0.45, 3.2],
                  "rotation": [-0.0389, 0, 0, 0.9992]})
    gltf = {"asset": {"version": "2.0", "generator": "pt bench/make_near_light_scene.py"}, "scene": 0,
            "scenes": [{"nodes": list(range(len(nodes))), "extras": {"width": 256, "height": 192, "max_depth": 8}}],
            "nodes": nodes,
            "cameras": [{"type": "perspective", "perspective": {"yfov": 0.7, "aspectRatio": 4 / 3, "znear": 0.01}}],
            "materials": [{"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.6, 0.6, 1], "metallicFactor": 0}},
                          {"name": "boxes", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.4, 0.3, 1], "metallicFactor": 0}},
                          {"name": "panel", "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0},
                           "emissiveFactor": [1, 1, 1]}],
            "meshes": gmeshes, "accessors": accessors, "bufferViews": views,
            "buffers": [{"byteLength": len(blob),
                         "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}]}
    with open(os.path.join(out, "scene.gltf"), "w") as f:
        json.dump(gltf, f, indent=1)


if __name__ == "__main__":
    main()
