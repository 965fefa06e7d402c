#!/usr/bin/env python3
"""Writes a scene lit by a large emitter close to what it lights (solid-angle sampling of
triangle lights, shaders/lights/triangle_light.glsl): a floor with two boxes under a square
panel 2.4 across hanging 0.9 above it, facing down, seen from the side (OUT_DIR/scene.gltf,
embedded buffer).

    python3 bench/make_near_light_scene.py OUT_DIR
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gltf_scene import box, quad, write_gltf  # noqa: E402


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    meshes = [("floor", quad([-4, 0, 4], [8, 0, 0], [0, 0, -8]), 0),
              ("box a", box([-1.0, 0, -0.6], [-0.3, 0.5, 0.2]), 1),
              ("box b", box([0.4, 0, -0.2], [1.1, 0.3, 0.6]), 1),
              ("panel", quad([-1.2, 0.9, -1.2], [2.4, 0, 0], [0, 0, 2.4]), 2)]
    # Camera at (0, 0.45, 3.2) looking at (0, 0.2, 0).
    camera_node = {"name": "camera", "camera": 0, "translation": [0, 0.45, 3.2],
                   "rotation": [-0.0389, 0, 0, 0.9992]}
    camera = {"type": "perspective", "perspective": {"yfov": 0.7, "aspectRatio": 4 / 3, "znear": 0.01}}
    materials = [{"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.6, 0.6, 1], "metallicFactor": 0}},
                 {"name": "boxes", "pbrMetallicRoughness": {"baseColorFactor": [0.7, 0.4, 0.3, 1], "metallicFactor": 0}},
                 {"name": "panel", "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 0},
                  "emissiveFactor": [1, 1, 1]}]
    write_gltf(os.path.join(out, "scene.gltf"), meshes, materials, camera_node, camera,
               {"width": 256, "height": 192, "max_depth": 8}, "pt bench/make_near_light_scene.py")


if __name__ == "__main__":
    main()
