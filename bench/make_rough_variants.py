#!/usr/bin/env python3
"""Variants of the rough box (bench/make_rough_scene.py) for calibrating `--integrator auto`.

Reads IN_DIR/scene.gltf (made by make_rough_scene.py, with or without --mitsuba) and writes
OUT_DIR/scene.gltf with its blocks changed, plus the files it refers to (scene.bin, checker.png)
and meta.json copied. The tall block is the rough gold, the short block the rough glass.

  --no-glass            remove the short block
  --glass-scale S       shrink the short block by S about the centre of its base
  --glass-roughness R   the glass's roughness (alpha = R^2)
  --gold-roughness R    the gold's roughness
  --gold-scale S        shrink the tall block by S towards the box's vertical axis, on the floor

bench/RESULTS.md, "Glossy caustics choose BDPT", lists the variants measured and their commands.
"""
import argparse
import json
import os
import shutil

import numpy as np


def accessor_bounds(gltf, index):
    a = gltf["accessors"][index]
    return np.array(a["min"], dtype=float), np.array(a["max"], dtype=float)


def node_for_mesh(gltf, mesh_name):
    index = next(i for i, m in enumerate(gltf["meshes"]) if m["name"] == mesh_name)
    return index, next(n for n in gltf["nodes"] if n.get("mesh") == index)


def scale_about(node, scale, pivot):
    """Scale a node's (identity-placed) mesh by `scale` about `pivot`."""
    assert "matrix" not in node and "scale" not in node and "translation" not in node, "placed already"
    node["scale"] = [scale] * 3
    node["translation"] = list(pivot * (1.0 - scale))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("in_dir")
    ap.add_argument("out_dir")
    ap.add_argument("--no-glass", action="store_true")
    ap.add_argument("--glass-scale", type=float)
    ap.add_argument("--glass-roughness", type=float)
    ap.add_argument("--gold-roughness", type=float)
    ap.add_argument("--gold-scale", type=float)
    args = ap.parse_args()

    gltf = json.load(open(os.path.join(args.in_dir, "scene.gltf")))
    materials = {m["name"]: m for m in gltf["materials"]}
    if args.glass_roughness is not None:
        materials["rough_glass"]["pbrMetallicRoughness"]["roughnessFactor"] = args.glass_roughness
    if args.gold_roughness is not None:
        materials["rough_gold"]["pbrMetallicRoughness"]["roughnessFactor"] = args.gold_roughness
    if args.glass_scale is not None:
        mesh, node = node_for_mesh(gltf, "short_block")
        lo, hi = accessor_bounds(gltf, gltf["meshes"][mesh]["primitives"][0]["attributes"]["POSITION"])
        scale_about(node, args.glass_scale, np.array([(lo[0] + hi[0]) / 2, lo[1], (lo[2] + hi[2]) / 2]))
    if args.gold_scale is not None:
        mesh, node = node_for_mesh(gltf, "tall_block")
        lo, _ = accessor_bounds(gltf, gltf["meshes"][mesh]["primitives"][0]["attributes"]["POSITION"])
        scale_about(node, args.gold_scale, np.array([0.0, lo[1], 0.0]))
    if args.no_glass:
        _, glass = node_for_mesh(gltf, "short_block")
        kept = [n for n in gltf["nodes"] if n is not glass]
        renumber = {i: kept.index(n) for i, n in enumerate(gltf["nodes"]) if n is not glass}
        gltf["nodes"] = kept
        for n in kept:
            if "children" in n:
                n["children"] = [renumber[c] for c in n["children"] if c in renumber]
        for s in gltf["scenes"]:
            s["nodes"] = [renumber[c] for c in s["nodes"] if c in renumber]

    os.makedirs(args.out_dir, exist_ok=True)
    for name in ("scene.bin", "checker.png", "meta.json"):
        if os.path.exists(os.path.join(args.in_dir, name)):
            shutil.copy(os.path.join(args.in_dir, name), args.out_dir)
    with open(os.path.join(args.out_dir, "scene.gltf"), "w") as f:
        json.dump(gltf, f, indent=1)
    print(os.path.join(args.out_dir, "scene.gltf"))


if __name__ == "__main__":
    main()
