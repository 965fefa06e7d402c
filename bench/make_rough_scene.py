#!/usr/bin/env python3
"""Writes a rough-material benchmark scene: the cbox-diffuse Cornell box of tests/references
with its tall block rough gold (GGX, roughness 0.35), its short block rough glass (GGX
transmission, roughness 0.2, IOR 1.5) and its floor a textured glTF PBR dielectric (a 64x64
checkerboard base colour, roughness 0.5, the default specular), as OUT_DIR/scene.gltf +
scene.bin + checker.png. The shading cost of the glTF PBR model is what it measures
(bench/RESULTS.md, "Shading cost"). Needs python3-numpy and python3-pil.

With --mitsuba the floor is a textured Lambertian instead (glTF: KHR_materials_specular with
specularFactor 0), and the same scene is written as Mitsuba 3 XML too (OUT_DIR/mitsuba/scene.xml
with the box's PLYs, a floor PLY with the same texture coordinates, and OUT_DIR/meta.json), for
bench/bench_vs_mitsuba.py. The materials then mean the same in both renderers: the gold is
Mitsuba's principled BSDF with metallic 1 (Schlick's Fresnel from the base colour, GGX with
alpha = roughness^2, as glTF's metal), the glass its roughdielectric (GGX, alpha 0.04, exact
Fresnel, IOR 1.5 against 1.0, as glTF transmission with a volume), the floor its diffuse with the
checkerboard as a nearest-filtered sRGB bitmap. One difference remains: Mitsuba's microfacet
shadowing is the separable Smith G1(wi) G1(wo), pt's the height-correlated G2 (Heitz 2014), which
is up to a few percent brighter at grazing angles on the gold and the glass.

    python3 bench/make_rough_scene.py OUT_DIR [--mitsuba]
"""
import argparse
import json
import os
import re
import shutil

import numpy as np
from PIL import Image

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BASE = os.path.join(ROOT, "tests", "references", "cbox-diffuse")


def accessor_array(gltf, blob, index):
    acc = gltf["accessors"][index]
    view = gltf["bufferViews"][acc["bufferView"]]
    offset = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
    return np.frombuffer(bytes(blob[offset:offset + acc["count"] * 12]), dtype=np.float32).reshape(-1, 3)


def accessor_indices(gltf, blob, index):
    acc = gltf["accessors"][index]
    view = gltf["bufferViews"][acc["bufferView"]]
    offset = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
    dtype = {5121: np.uint8, 5123: np.uint16, 5125: np.uint32}[acc["componentType"]]
    return np.frombuffer(bytes(blob[offset:offset + acc["count"] * np.dtype(dtype).itemsize]), dtype=dtype)


def write_ply_with_uv(path, positions, indices, uv):
    """Binary little-endian PLY: float x y z u v vertices, triangles as uchar-counted int lists."""
    faces = indices.reshape(-1, 3)
    header = ("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
              "property float z\nproperty float u\nproperty float v\nelement face %d\n"
              "property list uchar int vertex_indices\nend_header\n" % (len(positions), len(faces)))
    vertices = np.concatenate([positions, uv], 1).astype("<f4")
    face_records = np.zeros(len(faces), dtype=[("n", "u1"), ("v", "<i4", 3)])
    face_records["n"] = 3
    face_records["v"] = faces
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(vertices.tobytes())
        f.write(face_records.tobytes())


def write_mitsuba(out_dir, floor_positions, floor_indices, floor_uv):
    """The box's Mitsuba XML (tests/references/cbox-diffuse/mitsuba) with the three materials
    (see the module's docstring), and meta.json for bench_vs_mitsuba.py."""
    dst = os.path.join(out_dir, "mitsuba")
    os.makedirs(dst, exist_ok=True)
    src = os.path.join(BASE, "mitsuba")
    for name in os.listdir(src):
        if name.endswith(".ply") and name != "floor.ply":
            shutil.copyfile(os.path.join(src, name), os.path.join(dst, name))
    shutil.copyfile(os.path.join(out_dir, "checker.png"), os.path.join(dst, "checker.png"))
    write_ply_with_uv(os.path.join(dst, "floor.ply"), floor_positions, floor_indices, floor_uv)
    xml = open(os.path.join(src, "scene.xml")).read()
    materials = """  <bsdf type="principled" id="mat-gold">
    <rgb name="base_color" value="1.0, 0.78, 0.34"/>
    <float name="metallic" value="1.0"/>
    <float name="roughness" value="0.35"/>
  </bsdf>
  <bsdf type="roughdielectric" id="mat-glass">
    <string name="distribution" value="ggx"/>
    <float name="alpha" value="0.04"/>
    <float name="int_ior" value="1.5"/>
    <float name="ext_ior" value="1.0"/>
  </bsdf>
  <bsdf type="twosided" id="mat-checker">
    <bsdf type="diffuse">
      <texture type="bitmap" name="reflectance">
        <string name="filename" value="checker.png"/>
        <string name="filter_type" value="nearest"/>
      </texture>
    </bsdf>
  </bsdf>
"""
    xml = xml.replace('  <shape type="ply" id="floor">', materials + '  <shape type="ply" id="floor">', 1)
    for shape, material in (("floor", "mat-checker"), ("tall_block", "mat-gold"), ("short_block", "mat-glass")):
        xml = re.sub(r'(<shape type="ply" id="%s">.*?)<ref id="mat-white"/>' % shape,
                     r'\1<ref id="%s"/>' % material, xml, count=1, flags=re.S)
    xml = xml.replace("<!-- cbox-diffuse:", "<!-- cbox-rough (bench/make_rough_scene.py --mitsuba) from cbox-diffuse:")
    with open(os.path.join(dst, "scene.xml"), "w") as f:
        f.write(xml)
    meta = json.load(open(os.path.join(BASE, "meta.json")))
    meta.update(name="cbox-rough", description="cbox-diffuse with a rough gold block, a rough glass block and a "
                "textured Lambertian floor (bench/make_rough_scene.py --mitsuba)")
    meta.pop("materials", None)
    with open(os.path.join(out_dir, "meta.json"), "w") as f:
        json.dump(meta, f, indent=1)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out_dir")
    ap.add_argument("--mitsuba", action="store_true",
                    help="a Lambertian floor, and the scene as Mitsuba 3 XML too (see above)")
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
    if args.mitsuba:
        materials[-1]["doubleSided"] = True
        materials[-1]["extensions"] = {"KHR_materials_specular": {"specularFactor": 0.0}}
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
    if args.mitsuba:
        floor_indices = accessor_indices(gltf, blob, prim["indices"])
        write_mitsuba(args.out_dir, p, floor_indices, uv)
    print(os.path.join(args.out_dir, "scene.gltf"))


if __name__ == "__main__":
    main()
