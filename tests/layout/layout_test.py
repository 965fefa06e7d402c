#!/usr/bin/env python3
"""Checks that includes run with the data flow (README: Layout).

src/: base < image < scene < {accel, lights, gpu} < flatten < film < render < viewer < app.
shaders/: shared < common < textures < geometry < {material, bsdf, lights} < {integrator, viewer} < tests.
A file may include its own folder and folders of a lower level, never one of its own level or
above (siblings in braces do not include each other); scene/gltf and scene/ceng795 do not
include each other. Generated headers (pt_*_spv.h) and shaders/shared are open to everyone.
Also: no folder of src/ or shaders/ holds more than MAX_FILES files (split it by concept).
Exits 1 and names every include that runs upstream and every folder that is too big.

  tests/layout/layout_test.py [REPO]     (default: this file's repository)
"""
import os
import re
import sys

SRC_LEVELS = {"base": -1, "image": 0, "scene": 1, "accel": 2, "lights": 2, "gpu": 2, "flatten": 3,
              "film": 4, "render": 5, "viewer": 6, "app": 7}
SHADER_LEVELS = {"shared": 0, "common": 1, "textures": 2, "geometry": 3, "material": 4, "bsdf": 4,
                 "lights": 4, "integrator": 5, "viewer": 5, "tests": 6}
MAX_FILES = 22
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def folder_of(path):
    parts = path.split("/")
    return parts[0] if len(parts) > 1 else ""


def check_tree(root, tree, levels, problems):
    base = os.path.join(root, tree)
    for dirpath, _, files in os.walk(base):
        if len(files) > MAX_FILES:
            problems.append(f"{os.path.relpath(dirpath, root)}: {len(files)} files, more than {MAX_FILES}")
        for name in sorted(files):
            if not name.endswith((".h", ".cpp", ".glsl", ".comp", ".in")):
                continue
            path = os.path.join(dirpath, name)
            rel = os.path.relpath(path, base).replace(os.sep, "/")
            here = folder_of(rel)
            if here not in levels:
                problems.append(f"{tree}/{rel}: folder '{here}' has no level in {sys.argv[0]}")
                continue
            with open(path, encoding="utf-8") as f:
                text = f.read()
            for target in INCLUDE.findall(text):
                if re.fullmatch(r"pt_\w+_spv\.h", target):
                    continue  # generated SPIR-V
                there = folder_of(target)
                if there == "shared":
                    continue  # shaders/shared: the layout header and the feature table
                if there not in levels:
                    problems.append(f"{tree}/{rel}: includes '{target}', not in a known folder")
                    continue
                if here == "scene" and {rel.split("/")[1], target.split("/")[1]} == {"gltf", "ceng795"}:
                    problems.append(f"{tree}/{rel}: includes '{target}': the glTF and course loaders are independent")
                    continue
                if there != here and levels[there] >= levels[here]:
                    problems.append(f"{tree}/{rel}: includes '{target}', which is not below '{here}'")


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
    problems = []
    check_tree(root, "src", SRC_LEVELS, problems)
    check_tree(root, "shaders", SHADER_LEVELS, problems)
    for p in problems:
        print(p)
    print(f"{'1 failed' if problems else '1 passed'}: {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
