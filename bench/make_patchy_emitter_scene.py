#!/usr/bin/env python3
"""Writes a benchmark scene for textured emitters: a UV sphere of 8,192 triangles whose emission
texture is black but for 24 small bright spots (a helmet's lights, a panel's LEDs), over a grey
floor, with a camera; as OUT_DIR/scene.gltf + scene.bin + spots.png. Light selection that weighs
triangles by their emission factor alone spends almost every light sample on black triangles;
weighed by the texture (lights/texture_emission.h) it samples the spots. Render it under a dim
sky: `pt render OUT_DIR/scene.gltf --env-colour 0.05 0.05 0.05`. Needs python3-numpy and
python3-pil.

    python3 bench/make_patchy_emitter_scene.py OUT_DIR
"""
import base64
import json
import os
import sys

import numpy as np
from PIL import Image


def uv_sphere(segments, rings, radius, centre):
    pos, uv, idx = [], [], []
    for r in range(rings + 1):
        theta = np.pi * r / rings
        for s in range(segments + 1):
            phi = 2 * np.pi * s / segments
            n = np.array([np.sin(theta) * np.cos(phi), np.cos(theta), np.sin(theta) * np.sin(phi)])
            pos.append(centre + radius * n)
            uv.append([s / segments, r / rings])
    for r in range(rings):
        for s in range(segments):
            a, b = r * (segments + 1) + s, (r + 1) * (segments + 1) + s
            idx += [[a, a + 1, b], [a + 1, b + 1, b]]  # counter-clockwise seen from outside
    return np.array(pos, np.float32), np.array(uv, np.float32), np.array(idx, np.uint32)


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    rng = np.random.default_rng(5)
    tex = np.zeros((128, 256, 3), np.uint8)
    for _ in range(24):
        x, y = rng.integers(8, 248), rng.integers(24, 104)
        tex[y - 2:y + 2, x - 2:x + 2] = 255
    Image.fromarray(tex).save(os.path.join(out, "spots.png"))
    sp, suv, sidx = uv_sphere(128, 32, 1.0, np.array([0, 1.2, 0]))
    fp = np.array([[-4, 0, -4], [4, 0, -4], [4, 0, 4], [-4, 0, 4]], np.float32)
    fidx = np.array([[0, 3, 2], [0, 2, 1]], np.uint32)  # facing +y
    blobs, views, accessors = [], [], []

    def add(array, target=None, kind="VEC3", ctype=5126, minmax=False):
        data = array.tobytes()
        offset = sum(len(b) for b in blobs)
        blobs.append(data + b"\0" * (-len(data) % 4))
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(data)})
        acc = {"bufferView": len(views) - 1, "componentType": ctype, "count": int(array.shape[0]), "type": kind}
        if minmax:
            acc["min"] = array.min(0).tolist()
            acc["max"] = array.max(0).tolist()
        accessors.append(acc)
        return len(accessors) - 1

    s_pos = add(sp, minmax=True)
    s_uv = add(suv, kind="VEC2")
    s_idx = add(sidx.reshape(-1), kind="SCALAR", ctype=5125)
    f_pos = add(fp, minmax=True)
    f_idx = add(fidx.reshape(-1), kind="SCALAR", ctype=5125)
    blob = b"".join(blobs)
    open(os.path.join(out, "scene.bin"), "wb").write(blob)
    gltf = {
        "asset": {"version": "2.0"}, "scene": 0,
        "scenes": [{"nodes": [0, 1, 2], "extras": {"width": 256, "height": 192, "max_depth": 8}}],
        "nodes": [{"mesh": 0}, {"mesh": 1},
                  {"camera": 0, "translation": [0, 1.6, 4.2], "rotation": [-0.0499792, 0, 0, 0.9987503]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.01, "aspectRatio": 1.333}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": s_pos, "TEXCOORD_0": s_uv}, "indices": s_idx,
                                    "material": 0}]},
                   {"primitives": [{"attributes": {"POSITION": f_pos}, "indices": f_idx, "material": 1}]}],
        "materials": [
            {"name": "spots", "pbrMetallicRoughness": {"baseColorFactor": [0.05, 0.05, 0.05, 1], "metallicFactor": 0},
             "emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 0},
             "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 40},
                            "KHR_materials_specular": {"specularFactor": 0}}},
            {"name": "floor", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.6, 0.6, 1], "metallicFactor": 0},
             "extensions": {"KHR_materials_specular": {"specularFactor": 0}}}],
        "textures": [{"source": 0}], "images": [{"uri": "spots.png"}],
        "extensionsUsed": ["KHR_materials_emissive_strength", "KHR_materials_specular"],
        "buffers": [{"uri": "scene.bin", "byteLength": len(blob)}],
        "bufferViews": views, "accessors": accessors,
    }
    json.dump(gltf, open(os.path.join(out, "scene.gltf"), "w"), indent=1)
    print(os.path.join(out, "scene.gltf"))


if __name__ == "__main__":
    main()
