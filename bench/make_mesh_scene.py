#!/usr/bin/env python3
"""Writes a large-mesh benchmark scene: the cbox-diffuse Cornell box of tests/references with its
two blocks replaced by a bumpy sphere of about N triangles (a closed, connected surface with the
density of a scanned mesh), as OUT_DIR/scene.gltf + scene.bin for pt, and the same triangles as
Mitsuba 3 XML (OUT_DIR/mitsuba/scene.xml, the box's PLYs and bumpy_sphere.ply) with
OUT_DIR/meta.json, so that bench/bench_vs_mitsuba.py can render it with both. Needs python3-numpy.

    python3 bench/make_mesh_scene.py OUT_DIR [--triangles 1000000] [--size 128]
"""
import argparse
import json
import math
import os
import re
import shutil
import sys

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BASE = os.path.join(ROOT, "tests", "references", "cbox-diffuse")


def bumpy_sphere(triangles, centre, radius):
    """Latitude-longitude sphere (2 * rings * segments triangles, segments = 2 * rings) displaced
    by a few sine octaves. Returns float32 positions (V, 3) and uint32 indices (T * 3)."""
    rings = max(4, int(math.sqrt(triangles / 4.0)))
    segments = 2 * rings
    theta = np.linspace(0.0, math.pi, rings + 1, dtype=np.float64)[:, None]
    phi = np.linspace(0.0, 2.0 * math.pi, segments, endpoint=False, dtype=np.float64)[None, :]
    d = np.stack(np.broadcast_arrays(np.sin(theta) * np.cos(phi), np.cos(theta), np.sin(theta) * np.sin(phi)), -1)
    bump = (0.15 * np.sin(7.0 * d[..., 0]) * np.sin(5.0 * d[..., 1] + 1.0)
            + 0.05 * np.sin(23.0 * d[..., 2] + 11.0 * d[..., 0]) + 0.01 * np.sin(97.0 * d[..., 1]))
    p = (d * (radius * (1.0 + bump))[..., None] + np.asarray(centre)).reshape(-1, 3).astype(np.float32)
    r = np.arange(rings)[:, None]
    s = np.arange(segments)[None, :]
    a = r * segments + s
    b = (r + 1) * segments + s
    c = (r + 1) * segments + (s + 1) % segments
    e = r * segments + (s + 1) % segments
    # Counter-clockwise seen from outside (the material is double-sided anyway).
    tris = np.stack([a, c, b, a, e, c], -1).reshape(-1, 3)
    # The triangles touching a pole with two corners are degenerate: leave them out.
    pole = np.repeat(np.arange(rings), segments * 2)
    second = np.tile([False, True], rings * segments)
    keep = ~(((pole == 0) & second) | ((pole == rings - 1) & ~second))
    return p, tris[keep].reshape(-1).astype(np.uint32)


def write_ply(path, positions, indices):
    """Binary little-endian PLY: float x y z vertices, triangles as uchar-counted int lists."""
    faces = indices.reshape(-1, 3)
    header = ("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
              "property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n"
              % (len(positions), len(faces)))
    face_records = np.zeros(len(faces), dtype=[("n", "u1"), ("v", "<i4", 3)])
    face_records["n"] = 3
    face_records["v"] = faces
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(positions.astype("<f4").tobytes())
        f.write(face_records.tobytes())


def write_mitsuba(out_dir, positions, indices, size, triangles):
    """The box's Mitsuba XML (tests/references/cbox-diffuse/mitsuba) without its blocks, with the
    bumpy sphere in the white material (two-sided, as the glTF's is double-sided) and a film of
    size x size; and meta.json, which bench_vs_mitsuba.py reads for the image size."""
    dst = os.path.join(out_dir, "mitsuba")
    os.makedirs(dst, exist_ok=True)
    src = os.path.join(BASE, "mitsuba")
    xml = open(os.path.join(src, "scene.xml")).read()
    xml = re.sub(r'\s*<shape type="ply" id="(short|tall)_block">.*?</shape>', "", xml, flags=re.S)
    xml = xml.replace('<integer name="width" value="256"/>', '<integer name="width" value="%d"/>' % size)
    xml = xml.replace('<integer name="height" value="256"/>', '<integer name="height" value="%d"/>' % size)
    sphere = ('  <shape type="ply" id="bumpy_sphere">\n    <string name="filename" value="bumpy_sphere.ply"/>\n'
              '    <boolean name="face_normals" value="true"/>\n    <ref id="mat-white"/>\n  </shape>\n')
    xml = xml.replace("</scene>", sphere + "</scene>")
    xml = xml.replace("<!-- cbox-diffuse:", "<!-- cbox-bumpy-sphere (bench/make_mesh_scene.py) from cbox-diffuse:")
    with open(os.path.join(dst, "scene.xml"), "w") as f:
        f.write(xml)
    for name in os.listdir(src):
        if name.endswith(".ply") and not name.startswith(("short_block", "tall_block")):
            shutil.copyfile(os.path.join(src, name), os.path.join(dst, name))
    write_ply(os.path.join(dst, "bumpy_sphere.ply"), positions, indices)
    meta = json.load(open(os.path.join(BASE, "meta.json")))
    meta.update(name="cbox-bumpy-sphere", width=size, height=size, triangles_total=triangles,
                description="cbox-diffuse with its blocks replaced by a bumpy sphere of %d triangles "
                            "(bench/make_mesh_scene.py)" % triangles)
    meta.pop("triangles", None)
    with open(os.path.join(out_dir, "meta.json"), "w") as f:
        json.dump(meta, f, indent=1)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out_dir")
    ap.add_argument("--triangles", type=int, default=1000000)
    ap.add_argument("--size", type=int, default=128, help="image width and height of the Mitsuba film and meta.json")
    args = ap.parse_args()
    if args.triangles < 32:
        sys.exit("make_mesh_scene.py: --triangles must be at least 32")

    gltf = json.load(open(os.path.join(BASE, "scene.gltf")))
    blob = bytearray(open(os.path.join(BASE, gltf["buffers"][0]["uri"]), "rb").read())
    # The blocks go; everything else (walls, light, camera, materials) stays.
    names = {i: n.get("name") for i, n in enumerate(gltf["nodes"])}
    gltf["scenes"][0]["nodes"] = [i for i in gltf["scenes"][0]["nodes"] if names[i] not in ("short_block", "tall_block")]

    positions, indices = bumpy_sphere(args.triangles, (0.0, -0.35, 0.0), 0.5)
    while len(blob) % 4:
        blob.append(0)
    views = gltf["bufferViews"]
    accessors = gltf["accessors"]
    pos_view = len(views)
    views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": positions.nbytes, "target": 34962})
    blob += positions.tobytes()
    views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": indices.nbytes, "target": 34963})
    blob += indices.tobytes()
    accessors.append({"bufferView": pos_view, "componentType": 5126, "count": len(positions), "type": "VEC3",
                      "min": positions.min(0).tolist(), "max": positions.max(0).tolist()})
    accessors.append({"bufferView": pos_view + 1, "componentType": 5125, "count": len(indices), "type": "SCALAR"})
    gltf["meshes"].append({"name": "bumpy_sphere", "primitives": [
        {"attributes": {"POSITION": len(accessors) - 2}, "indices": len(accessors) - 1, "material": 0, "mode": 4}]})
    gltf["nodes"].append({"name": "bumpy_sphere", "mesh": len(gltf["meshes"]) - 1})
    gltf["scenes"][0]["nodes"].append(len(gltf["nodes"]) - 1)
    gltf["scenes"][0]["name"] = "cbox-bumpy-sphere"
    gltf["scenes"][0].setdefault("extras", {})["description"] = (
        "cbox-diffuse with its blocks replaced by a bumpy sphere of %d triangles (bench/make_mesh_scene.py)"
        % (len(indices) // 3))
    gltf["buffers"] = [{"uri": "scene.bin", "byteLength": len(blob)}]

    os.makedirs(args.out_dir, exist_ok=True)
    with open(os.path.join(args.out_dir, "scene.bin"), "wb") as f:
        f.write(blob)
    with open(os.path.join(args.out_dir, "scene.gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
    box_triangles = 32 - 20  # the reference box without its two 10-triangle blocks
    write_mitsuba(args.out_dir, positions, indices, args.size, box_triangles + len(indices) // 3)
    print("%s: %d triangles in the sphere" % (os.path.join(args.out_dir, "scene.gltf"), len(indices) // 3))


if __name__ == "__main__":
    main()
