#!/usr/bin/env python3
"""Writes a scene lit by many small lights (the light tree, shaders/lights/light_tree.glsl): a
hall 12 wide and 40 deep with two rows of pillars, 160 ceiling lamps of random colours and
powers facing down, 24 wall lamps facing into the hall and an emissive ball of 1,280 triangles
on the floor (half of them facing away from whatever they light), seen from one end
(OUT_DIR/scene.gltf, embedded buffer). Each point is lit mostly by the few lamps near it, which
the power CDF does not know.

    python3 bench/make_many_lights_scene.py OUT_DIR
"""
import math
import os
import random
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gltf_scene import box, merge, quad, write_gltf  # noqa: E402


def icosphere(centre, radius, subdivisions):
    t = (1 + 5 ** 0.5) / 2
    verts = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t],
             [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    faces = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2],
             [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11],
             [6, 2, 10], [8, 6, 7], [9, 8, 1]]
    verts = [[c / math.sqrt(sum(x * x for x in v)) for c in v] for v in verts]
    for _ in range(subdivisions):
        cache, out = {}, []

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                m = [(verts[a][i] + verts[b][i]) / 2 for i in range(3)]
                n = math.sqrt(sum(x * x for x in m))
                verts.append([x / n for x in m])
                cache[key] = len(verts) - 1
            return cache[key]
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            out += [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
        faces = out
    pos = [[centre[i] + radius * v[i] for i in range(3)] for v in verts]
    return pos, [i for f in faces for i in f]


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    rng = random.Random(795)
    materials = [{"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0}},
                 {"name": "walls", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.65, 0.6, 1], "metallicFactor": 0}},
                 {"name": "pillars", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.35, 0.25, 1], "metallicFactor": 0}},
                 {"name": "ball", "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0},
                  "emissiveFactor": [1, 0.6, 0.2], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 6}}}]
    W, D, H = 12.0, 40.0, 4.0
    meshes = [("floor", quad([-W / 2, 0, 0], [W, 0, 0], [0, 0, -D]), 0),
              ("ceiling", quad([-W / 2, H, -D], [W, 0, 0], [0, 0, D]), 1),
              ("left wall", quad([-W / 2, 0, -D], [0, H, 0], [0, 0, D]), 1),
              ("right wall", quad([W / 2, 0, 0], [0, H, 0], [0, 0, -D]), 1),
              ("far wall", quad([W / 2, 0, -D], [0, H, 0], [-W, 0, 0]), 1),
              ("near wall", quad([-W / 2, 0, 0.01], [0, H, 0], [W, 0, 0]), 1)]  # every face inwards
    pillars = [box([x - 0.3, 0, -z - 0.3], [x + 0.3, H, -z + 0.3]) for x in (-3, 3) for z in range(4, 40, 4)]
    meshes.append(("pillars", merge(pillars), 2))
    meshes.append(("ball", icosphere([1.5, 0.8, -14], 0.8, 3), 3))
    lamps = []
    for k in range(160):  # ceiling lamps, facing down
        x, z = rng.uniform(-W / 2 + 0.5, W / 2 - 0.5), rng.uniform(-D + 0.5, -0.5)
        s = rng.uniform(0.15, 0.35)
        lamps.append((quad([x - s / 2, H - 0.02, z - s / 2], [s, 0, 0], [0, 0, s]), k))
    for k in range(24):  # wall lamps, facing into the hall
        side = -1 if k % 2 == 0 else 1
        z = -1.5 - (D - 3) * k / 24
        s = 0.25
        lamps.append((quad([side * (W / 2 - 0.02), 1.8, z], [0, 0, -s] if side < 0 else [0, s, 0],
                           [0, s, 0] if side < 0 else [0, 0, -s]), 160 + k))
    for (pos_idx, k) in lamps:
        colour = [rng.uniform(0.3, 1.0) for _ in range(3)]
        strength = rng.uniform(10, 60)
        materials.append({"name": "lamp %d" % k, "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1],
                                                                           "metallicFactor": 0},
                          "emissiveFactor": colour,
                          "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}})
        meshes.append(("lamp %d" % k, pos_idx, len(materials) - 1))
    # Camera at (-1, 1.6, -0.5), looking down the hall and a little down.
    camera_node = {"name": "camera", "camera": 0, "translation": [-1, 1.6, -0.5],
                   "rotation": [-0.0436, -0.0436, -0.0019, 0.9981]}
    camera = {"type": "perspective", "perspective": {"yfov": 0.9, "aspectRatio": 4 / 3, "znear": 0.01}}
    write_gltf(os.path.join(out, "scene.gltf"), meshes, materials, camera_node, camera,
               {"width": 256, "height": 192, "max_depth": 8}, "pt bench/make_many_lights_scene.py",
               ["KHR_materials_emissive_strength"])


if __name__ == "__main__":
    main()
