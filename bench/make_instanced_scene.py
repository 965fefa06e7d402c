#!/usr/bin/env python3
"""Writes an instancing benchmark scene: one bumpy sphere of about N triangles (the mesh of
bench/make_mesh_scene.py) placed by K glTF nodes on a ground plane, in a grid with a turn and a
size of their own, lit by a sun (KHR_lights_punctual) and seen by a camera from above the grid's
corner (OUT_DIR/scene.gltf + scene.bin). With the defaults, 327,680 triangles x 300 nodes: 98 M
triangles once every node's copy is made. Needs python3-numpy.

    python3 bench/make_instanced_scene.py OUT_DIR [--triangles 327680] [--nodes 300]
"""
import argparse
import json
import math
import os
import random
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_mesh_scene import bumpy_sphere  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out_dir")
    ap.add_argument("--triangles", type=int, default=327680)
    ap.add_argument("--nodes", type=int, default=300)
    args = ap.parse_args()
    os.makedirs(args.out_dir, exist_ok=True)
    positions, indices = bumpy_sphere(args.triangles, np.zeros(3), 1.0)
    positions = positions.astype(np.float32)
    indices = indices.astype(np.uint32)
    ground = np.array([[-1, 0, -1], [1, 0, -1], [1, 0, 1], [-1, 0, 1]], dtype=np.float32)
    ground_indices = np.array([0, 2, 1, 0, 3, 2], dtype=np.uint32)
    blob = bytearray()
    views, accessors = [], []

    def add(array, target, kind, with_bounds):
        offset = len(blob)
        blob.extend(array.tobytes())
        while len(blob) % 4:
            blob.append(0)
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": array.nbytes, "target": target})
        acc = {"bufferView": len(views) - 1, "componentType": 5126 if array.dtype == np.float32 else 5125,
               "count": int(array.size // (3 if kind == "VEC3" else 1)), "type": kind}
        if with_bounds:
            acc["min"] = array.reshape(-1, 3).min(axis=0).tolist()
            acc["max"] = array.reshape(-1, 3).max(axis=0).tolist()
        accessors.append(acc)
        return len(accessors) - 1

    sphere_pos = add(positions.reshape(-1), 34962, "VEC3", True)
    sphere_idx = add(indices, 34963, "SCALAR", False)
    ground_pos = add(ground.reshape(-1), 34962, "VEC3", True)
    ground_idx = add(ground_indices, 34963, "SCALAR", False)
    side = math.ceil(math.sqrt(args.nodes))
    spacing = 3.0
    extent = side * spacing
    rng = random.Random(7)
    nodes = [{"name": "ground", "mesh": 1, "scale": [extent, 1, extent]}]
    for k in range(args.nodes):
        i, j = k % side, k // side
        size = 0.6 + 0.6 * rng.random()
        angle = rng.random() * math.pi
        nodes.append({"name": "ball %d" % k, "mesh": 0,
                      "translation": [(i - side / 2 + 0.5) * spacing, size, (j - side / 2 + 0.5) * spacing],
                      "rotation": [0.0, math.sin(angle / 2), 0.0, math.cos(angle / 2)],
                      "scale": [size, size * (0.8 + 0.4 * rng.random()), size]})
    # Camera above a corner looking across the grid; the sun from the other side.
    eye = np.array([-extent * 0.55, extent * 0.35, extent * 0.55])
    target = np.array([0.0, 0.0, 0.0])
    forward = (target - eye) / np.linalg.norm(target - eye)
    yaw = math.atan2(-forward[0], -forward[2])
    pitch = math.asin(forward[1])
    qy = [0.0, math.sin(yaw / 2), 0.0, math.cos(yaw / 2)]
    qx = [math.sin(pitch / 2), 0.0, 0.0, math.cos(pitch / 2)]
    rot = [qy[3] * qx[0], qy[1] * qx[3], -qy[1] * qx[0], qy[3] * qx[3]]  # qy * qx
    nodes.append({"name": "camera", "camera": 0, "translation": eye.tolist(), "rotation": rot})
    sun_angle = -0.8
    nodes.append({"name": "sun", "rotation": [math.sin(sun_angle / 2), 0.0, 0.0, math.cos(sun_angle / 2)],
                  "extensions": {"KHR_lights_punctual": {"light": 0}}})
    gltf = {
        "asset": {"version": "2.0", "generator": "pt bench/make_instanced_scene.py"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 3.0}]}},
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes))), "extras": {"width": 512, "height": 512}}],
        "nodes": nodes,
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.9, "aspectRatio": 1.0, "znear": 0.01}}],
        "materials": [{"name": "ball", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.55, 0.3, 1],
                                                               "metallicFactor": 0.0, "roughnessFactor": 0.5}},
                      {"name": "ground", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1],
                                                                 "metallicFactor": 0.0, "roughnessFactor": 1.0}}],
        "meshes": [{"name": "bumpy sphere", "primitives": [{"attributes": {"POSITION": sphere_pos},
                                                            "indices": sphere_idx, "material": 0}]},
                   {"name": "ground", "primitives": [{"attributes": {"POSITION": ground_pos},
                                                      "indices": ground_idx, "material": 1}]}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"uri": "scene.bin", "byteLength": len(blob)}],
    }
    with open(os.path.join(args.out_dir, "scene.bin"), "wb") as f:
        f.write(blob)
    with open(os.path.join(args.out_dir, "scene.gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
    print("%s: %d triangles x %d nodes = %d triangles placed" % (
        os.path.join(args.out_dir, "scene.gltf"), len(indices) // 3, args.nodes, len(indices) // 3 * args.nodes))


if __name__ == "__main__":
    main()
