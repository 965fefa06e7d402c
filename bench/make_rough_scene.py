#!/usr/bin/env python3
"""Writes a rough-material benchmark scene: the cbox-diffuse Cornell box of tests/references
with its tall block rough gold (GGX, roughness 0.35), its short block rough glass (GGX
transmission, roughness 0.2, IOR 1.5) and its floor a textured glTF PBR dielectric (a 64x64
checkerboard base colour, roughness 0.5, the default specular), as OUT_DIR/scene.gltf +
scene.bin + checker.png. The shading cost of the glTF PBR model is what it measures
(bench/RESULTS.md, "Shading cost"). Needs python3-numpy and python3-pil.

    python3 bench/make_rough_scene.py OUT_DIR
"""
import argparse
import json
import os

import numpy as np
from PIL import Image

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BASE = os.path.join(ROOT, "tests", "references", "cbox-diffuse")


def accessor_array(gltf, blob, index):
    acc = gltf["accessors"][index]
    view = gltf["bufferViews"][acc["bufferView"]]
    offset = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
    return np.frombuffer(bytes(blob[offset:offset + acc["count"] * 12]), dtype=np.float32).reshape(-1, 3)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out_dir")
    args = ap.parse_args()

    gltf = json.load(open(os.path.join(BASE, "scene.gltf")))
    blob = bytearray(open(os.path.join(BASE, gltf["buffers"][0]["uri"]), "rb").read())
    materials = gltf["materials"]
    materials.append({"name": "rough_gold", "pbrMetallicRoughness": {
        "baseColorFactor": [1.0, 0.78, 0.34, 1.0], "metallicFactor": 1.0, "roughnessFactor": 0.35}})
    materials.append({"name": "rough_glass", "pbrMetallicRoughness": {
        "baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.2},
        "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                       "KHR_materials_volume": {"thicknessFactor": 1.0}, "KHR_materials_ior": {"ior": 1.5}}})
    materials.append({"name": "checker_floor", "pbrMetallicRoughness": {
        "baseColorTexture": {"index": 0}, "metallicFactor": 0.0, "roughnessFactor": 0.5}})
    gold, glass, floor = len(materials) - 3, len(materials) - 2, len(materials) - 1
    meshes = {m["name"]: m for m in gltf["meshes"]}
    meshes["tall_block"]["primitives"][0]["material"] = gold
    meshes["short_block"]["primitives"][0]["material"] = glass

    # The floor gets texture coordinates from its x and z (it spans about [-1, 1] in both).
    prim = meshes["floor"]["primitives"][0]
    p = accessor_array(gltf, blob, prim["attributes"]["POSITION"])
    uv = np.stack([(p[:, 0] + 1.0) * 0.5, (p[:, 2] + 1.0) * 0.5], -1).astype(np.float32)
    while len(blob) % 4:
        blob.append(0)
    gltf["bufferViews"].append({"buffer": 0, "byteOffset": len(blob), "byteLength": uv.nbytes, "target": 34962})
    blob += uv.tobytes()
    gltf["accessors"].append({"bufferView": len(gltf["bufferViews"]) - 1, "componentType": 5126, "count": len(uv),
                              "type": "VEC2"})
    prim["attributes"]["TEXCOORD_0"] = len(gltf["accessors"]) - 1
    prim["material"] = floor

    os.makedirs(args.out_dir, exist_ok=True)
    cells = (np.indices((64, 64)) // 8).sum(0) % 2
    texels = np.where(cells[..., None] == 1, [200, 190, 170], [40, 60, 90]).astype(np.uint8)
    Image.fromarray(texels, "RGB").save(os.path.join(args.out_dir, "checker.png"))
    gltf["images"] = [{"uri": "checker.png"}]
    gltf["samplers"] = [{"magFilter": 9728, "minFilter": 9728}]
    gltf["textures"] = [{"source": 0, "sampler": 0}]
    used = set(gltf.get("extensionsUsed", [])) | {"KHR_materials_transmission", "KHR_materials_volume",
                                                   "KHR_materials_ior"}
    gltf["extensionsUsed"] = sorted(used)
    gltf["scenes"][0]["name"] = "cbox-rough"
    gltf["scenes"][0].setdefault("extras", {})["description"] = (
        "cbox-diffuse with a rough gold block, a rough glass block and a checkerboard floor (bench/make_rough_scene.py)")
    gltf["buffers"] = [{"uri": "scene.bin", "byteLength": len(blob)}]
    with open(os.path.join(args.out_dir, "scene.bin"), "wb") as f:
        f.write(blob)
    with open(os.path.join(args.out_dir, "scene.gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
    print(os.path.join(args.out_dir, "scene.gltf"))


if __name__ == "__main__":
    main()
