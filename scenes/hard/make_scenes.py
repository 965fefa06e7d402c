#!/usr/bin/env python3
"""Writes the glTF files of scenes/hard/ (README.md there says what each tests).

The files embed their buffers as base64 so that each is one readable file; this script is the
readable form of their geometry. Run it from anywhere: python3 scenes/hard/make_scenes.py
"""
import base64
import json
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
NAN = float("nan")


class Gltf:
    """A glTF 2.0 document with one embedded buffer, built mesh by mesh."""

    def __init__(self, name, description):
        self.blob = bytearray()
        self.doc = {
            "asset": {"version": "2.0", "generator": "pt: scenes/hard/make_scenes.py"},
            "extensionsUsed": ["KHR_materials_specular", "KHR_materials_emissive_strength"],
            "scene": 0,
            "scenes": [{"name": name, "nodes": [], "extras": {"description": description}}],
            "nodes": [], "meshes": [], "materials": [], "accessors": [], "bufferViews": [], "cameras": [],
        }

    def material(self, name, base=1.0, emission=0.0):
        """A Lambertian material (specularFactor 0), black and emitting `emission` when given."""
        m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": [base, base, base, 1.0], "metallicFactor": 0.0,
                                                    "roughnessFactor": 1.0},
             "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}}
        if emission > 0:
            m["emissiveFactor"] = [1.0, 1.0, 1.0]
            m["extensions"]["KHR_materials_emissive_strength"] = {"emissiveStrength": emission}
        self.doc["materials"].append(m)
        return len(self.doc["materials"]) - 1

    def _accessor(self, values, fmt, gltf_type, component, count, target, extra=None):
        while len(self.blob) % 4:
            self.blob.append(0)
        data = struct.pack("<" + fmt * len(values), *values)
        self.doc["bufferViews"].append({"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(data), "target": target})
        self.blob += data
        acc = {"bufferView": len(self.doc["bufferViews"]) - 1, "componentType": component, "count": count, "type": gltf_type}
        acc.update(extra or {})
        self.doc["accessors"].append(acc)
        return len(self.doc["accessors"]) - 1

    def mesh(self, name, material, positions, triangles, normals=None, node=None):
        """A triangle mesh and the node placing it (`node`: extra node fields, e.g. rotation)."""
        flat = [c for p in positions for c in p]
        lo = [min(p[i] for p in positions) for i in range(3)]
        hi = [max(p[i] for p in positions) for i in range(3)]
        attributes = {"POSITION": self._accessor(flat, "f", "VEC3", 5126, len(positions), 34962, {"min": lo, "max": hi})}
        if normals is not None:
            attributes["NORMAL"] = self._accessor([c for n in normals for c in n], "f", "VEC3", 5126, len(normals), 34962)
        indices = self._accessor([i for t in triangles for i in t], "I", "SCALAR", 5125, 3 * len(triangles), 34963)
        self.doc["meshes"].append({"name": name, "primitives": [{"attributes": attributes, "indices": indices,
                                                                 "material": material}]})
        self.node(dict(name=name, mesh=len(self.doc["meshes"]) - 1, **(node or {})))

    def node(self, node):
        self.doc["nodes"].append(node)
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)

    def camera(self, name, yfov, translation, rotation):
        self.doc["cameras"].append({"type": "perspective", "perspective": {"yfov": yfov, "znear": 0.01}})
        self.node({"name": name, "camera": len(self.doc["cameras"]) - 1, "translation": translation, "rotation": rotation})

    def directional_light(self, name, irradiance, rotation):
        self.doc.setdefault("extensions", {}).setdefault("KHR_lights_punctual", {"lights": []})
        lights = self.doc["extensions"]["KHR_lights_punctual"]["lights"]
        lights.append({"name": name, "type": "directional", "intensity": irradiance})
        self.doc["extensionsUsed"].append("KHR_lights_punctual")
        self.node({"name": name, "rotation": rotation, "extensions": {"KHR_lights_punctual": {"light": len(lights) - 1}}})

    def write(self, file_name):
        self.doc["buffers"] = [{"byteLength": len(self.blob),
                                "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(self.blob)).decode()}]
        with open(os.path.join(HERE, file_name), "w") as f:
            json.dump(self.doc, f, indent=1, allow_nan=False)
            f.write("\n")


def quad(corner, u, v):
    """Four corners of corner + [0,1]^2 (u, v); with QUAD it faces along u x v."""
    return [corner, [corner[i] + u[i] for i in range(3)], [corner[i] + u[i] + v[i] for i in range(3)],
            [corner[i] + v[i] for i in range(3)]]


QUAD = [[0, 1, 2], [0, 2, 3]]
LOOK_DOWN = [-math.sqrt(0.5), 0.0, 0.0, math.sqrt(0.5)]  # -90 degrees about x: -z becomes -y


def degenerate_input():
    g = Gltf("degenerate-input",
             "A white floor (x, z in [-1, 1]) whose vertex normals are zero-length and NaN, zero-area emissive "
             "triangles above it, an emitter lying in the floor's plane (seen exactly edge-on from it), an emitter "
             "rotated by exactly 90 degrees by its node (facing along the floor), and a 1e-3 triangle of radiance 1e12 "
             "at 1000 straight above. The floor's radiance is (E_sun + E_wall) / pi from Lambert's polygon formula.")
    white = g.material("white floor")
    lamp = g.material("lamp", base=0.0, emission=1.0)
    sun = g.material("far tiny sun", base=0.0, emission=1e12)
    # Normals: zero-length, NaN, valid, and zero: the loader must keep the triangles (shading
    # with the geometric normal) and never pass a NaN on.
    g.mesh("floor", white, quad([-1, 0, 1], [2, 0, 0], [0, 0, -2]), QUAD,
           normals=[[0, 0, 0], [NAN, NAN, NAN], [0, 1, 0], [0, 0, 0]])
    # Zero-area triangles, emissive: a repeated vertex, three collinear points, one point thrice.
    g.mesh("zero-area triangles", lamp,
           [[-0.5, 0.3, 0], [-0.5, 0.3, 0], [0.5, 0.3, 0], [0, 0.3, -0.5], [0, 0.3, 0], [0, 0.3, 0.5], [0.2, 0.4, 0.2]],
           [[0, 1, 2], [3, 4, 5], [6, 6, 6]])
    # In the floor's plane, beside it, facing up: the floor sees it at exactly 90 degrees.
    g.mesh("edge-on lamp", lamp, quad([1.2, 0, 0.5], [0.4, 0, 0], [0, 0, -1]), QUAD)
    # Made facing -y, turned by exactly 90 degrees about z by its node: it faces +x, along the
    # floor, standing on the floor's plane at x = -1.1.
    g.mesh("wall lamp", lamp, quad([0, 0, -0.5], [0.6, 0, 0], [0, 0, 1]), QUAD,
           node={"translation": [-1.1, 0, 0], "rotation": [0, 0, math.sqrt(0.5), math.sqrt(0.5)]})
    # 1e-3 across, 1000 up, facing down: E = L A / d^2 = 1e12 * 5e-7 / 1e6 = 0.5 on the floor.
    g.mesh("far tiny sun", sun, [[0, 1000, 0], [0, 1000, -1e-3], [1e-3, 1000, 0]], [[0, 1, 2]])
    g.camera("above", 1.05, [0, 3, 0], LOOK_DOWN)
    g.write("degenerate-input.gltf")


def icosphere(subdivisions):
    t = (1 + math.sqrt(5)) / 2
    v = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t], [0, -1, -t], [0, 1, -t], [t, 0, -1],
         [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    f = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2], [10, 7, 6],
         [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7],
         [9, 8, 1]]

    def unit(p):
        n = math.sqrt(sum(c * c for c in p))
        return [c / n for c in p]

    v = [unit(p) for p in v]
    for _ in range(subdivisions):
        mid = {}

        def midpoint(a, b):
            key = (min(a, b), max(a, b))
            if key not in mid:
                v.append(unit([v[a][i] + v[b][i] for i in range(3)]))
                mid[key] = len(v) - 1
            return mid[key]

        nf = []
        for a, b, c in f:
            ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
            nf += [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
        f = nf
    return v, f


def smooth_icosphere():
    g = Gltf("smooth-icosphere",
             "An icosphere of 80 flat triangles with smooth vertex normals (the unit sphere's), albedo 1, under a "
             "directional light of irradiance pi at 90 degrees to the view: direct light shows n_s . l, with no black "
             "faceted band at the terminator and nothing on the far side.")
    white = g.material("white")
    v, f = icosphere(1)
    g.mesh("icosphere", white, v, f, normals=v)
    g.camera("front", 0.6, [0, 0, 4], [0, 0, 0, 1])
    # The light travels along its node's -z: turned so that it comes from (1, 0.15, 0.1).
    to_light = [1.0, 0.15, 0.1]
    n = math.sqrt(sum(c * c for c in to_light))
    to_light = [c / n for c in to_light]
    # Rotation taking +z to to_light (the light then travels along -to_light): axis z x l.
    axis = [-to_light[1], to_light[0], 0.0]
    s = math.sqrt(sum(c * c for c in axis))
    angle = math.acos(to_light[2])
    q = [axis[i] / s * math.sin(angle / 2) for i in range(3)] + [math.cos(angle / 2)]
    g.directional_light("grazing sun", math.pi, q)
    g.write("smooth-icosphere.gltf")


if __name__ == "__main__":
    degenerate_input()
    smooth_icosphere()
