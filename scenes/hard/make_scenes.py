#!/usr/bin/env python3
"""Writes the scene files of scenes/hard/ (README.md there says what each tests).

Mesh-only scenes are glTF 2.0 with their buffers embedded as base64, so that each is one file;
this script is the readable form of their geometry. Scenes that need analytic spheres, glass or a
sky are the CENG795 course's XML (src/scene/ceng795_*), small enough to read as they are, lit by
white-sky.hdr where they need a sky. Run it from anywhere: python3 scenes/hard/make_scenes.py

The tests compute their expectations from the same numbers, so numbers are written as the float32
values the tests used when they built these scenes in C++ (f32 below rounds as C++ float does).
"""
import base64
import json
import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
NAN = float("nan")


def f32(x):
    """x rounded to float32, as C++ rounds a float result (x exact in double)."""
    return struct.unpack("<f", struct.pack("<f", x))[0]


def text(x):
    """The shortest decimal that reads back (via double, as the loaders read) as the float32 x."""
    x = f32(x)
    for digits in range(1, 18):
        s = repr(float("%.*g" % (digits, x)))
        if f32(float(s)) == x:
            return s[:-2] if s.endswith(".0") else s
    raise ValueError(x)


def short(x):
    """The float32 x as the double JSON writes shortest (static_cast<float> gives x back)."""
    return float(text(x))


def vec(v):
    return " ".join(text(c) for c in v)


def f32_normalize(v):
    """glm::normalize on a float vec3: v * (1 / sqrt(dot(v, v))), each step rounded to float."""
    d = f32(f32(f32(v[0] * v[0]) + f32(v[1] * v[1])) + f32(v[2] * v[2]))
    inv = f32(1.0 / f32(math.sqrt(d)))
    return [f32(c * inv) for c in v]


def f32_dot(a, b):
    """glm::dot on float vec3s: (x + y) + z of the products, each step rounded to float."""
    return f32(f32(f32(a[0] * b[0]) + f32(a[1] * b[1])) + f32(a[2] * b[2]))


def f32_cross(a, b):
    """glm::cross on float vec3s, each product and difference rounded to float."""
    return [f32(f32(a[1] * b[2]) - f32(b[1] * a[2])), f32(f32(a[2] * b[0]) - f32(b[2] * a[0])),
            f32(f32(a[0] * b[1]) - f32(b[0] * a[1]))]


def f32_step(x, k):
    """The float k steps (units in the last place) from the float x (x != 0)."""
    bits = struct.unpack("<i", struct.pack("<f", x))[0]
    return struct.unpack("<f", struct.pack("<i", bits + k))[0]


def f32_preimage(want, reads_as):
    """A float vector next to `want` (its zeros kept) that reads_as() maps to exactly `want`:
    the glTF loader renormalises what a node's matrix gives, and the result must be the float
    vector a test computes, bit for bit."""
    steps = sorted(((i, j, k) for i in range(-3, 4) for j in range(-3, 4) for k in range(-3, 4)),
                   key=lambda t: sum(abs(c) for c in t))
    for t in steps:
        if any(t[i] and want[i] == 0 for i in range(3)):
            continue
        v = [f32_step(want[i], t[i]) if t[i] else want[i] for i in range(3)]
        if reads_as(v) == want:
            return v
    raise ValueError(want)


def columns(x, y, z, t=(0.0, 0.0, 0.0)):
    """A glTF node matrix (column-major) with columns x, y, z and translation t."""
    return [short(c) for c in list(x) + [0.0] + list(y) + [0.0] + list(z) + [0.0] + list(t) + [1.0]]


def look_at_rotation(eye, target, up=(0.0, 1.0, 0.0)):
    """The unit quaternion [x, y, z, w] of a glTF camera node at eye looking at target."""
    f = [target[i] - eye[i] for i in range(3)]
    n = math.sqrt(sum(c * c for c in f))
    f = [c / n for c in f]
    r = [f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2], f[0] * up[1] - f[1] * up[0]]
    n = math.sqrt(sum(c * c for c in r))
    r = [c / n for c in r]
    u = [r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]]
    # Columns of the camera's rotation: right, up and back (-forward); matrix to quaternion.
    m = [[r[0], u[0], -f[0]], [r[1], u[1], -f[1]], [r[2], u[2], -f[2]]]
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 0:
        s = 2 * math.sqrt(1 + trace)
        q = [(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, s / 4]
    else:
        i = max(range(3), key=lambda k: m[k][k])
        j, k = (i + 1) % 3, (i + 2) % 3
        s = 2 * math.sqrt(1 + m[i][i] - m[j][j] - m[k][k])
        q = [0.0] * 4
        q[i] = s / 4
        q[j] = (m[j][i] + m[i][j]) / s
        q[k] = (m[k][i] + m[i][k]) / s
        q[3] = (m[k][j] - m[j][k]) / s
    return q


class Gltf:
    """A glTF 2.0 document with one embedded buffer, built mesh by mesh."""

    def __init__(self, name, description, **extras):
        """`extras`: settings pt reads from the scene (width, height, max_depth)."""
        self.blob = bytearray()
        self.doc = {
            "asset": {"version": "2.0", "generator": "pt: scenes/hard/make_scenes.py"},
            "extensionsUsed": ["KHR_materials_specular", "KHR_materials_emissive_strength"],
            "scene": 0,
            "scenes": [{"name": name, "nodes": [], "extras": dict(description=description, **extras)}],
            "nodes": [], "meshes": [], "materials": [], "accessors": [], "bufferViews": [], "cameras": [],
        }

    def material(self, name, base=1.0, emission=0.0, double_sided=False, normal_texture=None):
        """A Lambertian material (specularFactor 0), black and emitting `emission` when given;
        `normal_texture`: the index of its tangent-space normal map (see texture)."""
        m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": [base, base, base, 1.0], "metallicFactor": 0.0,
                                                    "roughnessFactor": 1.0},
             "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}}
        if double_sided:
            m["doubleSided"] = True
        if normal_texture is not None:
            m["normalTexture"] = {"index": normal_texture}
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

    def texture(self, name, png_bytes):
        """A texture of the PNG `png_bytes`, embedded as a data URI, sampled nearest and repeated.
        Return its index. (As a normal map pt reads it as linear: no sRGB decoding.)"""
        self.doc.setdefault("images", []).append(
            {"name": name, "uri": "data:image/png;base64," + base64.b64encode(png_bytes).decode()})
        self.doc.setdefault("samplers", []).append({"magFilter": 9728, "minFilter": 9728, "wrapS": 10497, "wrapT": 10497})
        self.doc.setdefault("textures", []).append({"sampler": len(self.doc["samplers"]) - 1,
                                                    "source": len(self.doc["images"]) - 1})
        return len(self.doc["textures"]) - 1

    def mesh(self, name, material, positions, triangles, normals=None, node=None, short_indices=False, uvs=None):
        """A triangle mesh and the node placing it (`node`: extra node fields, e.g. rotation);
        `uvs`: TEXCOORD_0, as pt reads it ((0, 0) the image's top-left corner)."""
        flat = [c for p in positions for c in p]
        lo = [min(p[i] for p in positions) for i in range(3)]
        hi = [max(p[i] for p in positions) for i in range(3)]
        attributes = {"POSITION": self._accessor(flat, "f", "VEC3", 5126, len(positions), 34962, {"min": lo, "max": hi})}
        if normals is not None:
            attributes["NORMAL"] = self._accessor([c for n in normals for c in n], "f", "VEC3", 5126, len(normals), 34962)
        if uvs is not None:
            attributes["TEXCOORD_0"] = self._accessor([c for uv in uvs for c in uv], "f", "VEC2", 5126, len(uvs), 34962)
        index_format, index_type = ("H", 5123) if short_indices else ("I", 5125)
        indices = self._accessor([i for t in triangles for i in t], index_format, "SCALAR", index_type, 3 * len(triangles), 34963)
        self.doc["meshes"].append({"name": name, "primitives": [{"attributes": attributes, "indices": indices,
                                                                 "material": material}]})
        self.node(dict(name=name, mesh=len(self.doc["meshes"]) - 1, **(node or {})))

    def node(self, node):
        self.doc["nodes"].append(node)
        self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)

    def camera(self, name, yfov, translation=None, rotation=None, matrix=None):
        """A perspective camera placed by translation and rotation, or by a node `matrix`."""
        self.doc["cameras"].append({"type": "perspective", "perspective": {"yfov": yfov, "znear": 0.01}})
        placement = {"matrix": matrix} if matrix is not None else {"translation": translation, "rotation": rotation}
        self.node(dict(name=name, camera=len(self.doc["cameras"]) - 1, **placement))

    def directional_light(self, name, irradiance, rotation=None, matrix=None):
        """Irradiance `irradiance` (W/m^2) travelling along the node's -z (by rotation or `matrix`)."""
        self._light(name, {"type": "directional", "intensity": irradiance},
                    {"matrix": matrix} if matrix is not None else {"rotation": rotation})

    def point_light(self, name, intensity, translation):
        """Radiant intensity `intensity` (W/sr) at `translation`."""
        self._light(name, {"type": "point", "intensity": intensity}, {"translation": translation})

    def _light(self, name, light, placement):
        if "KHR_lights_punctual" not in self.doc["extensionsUsed"]:
            self.doc["extensionsUsed"].append("KHR_lights_punctual")
        lights = self.doc.setdefault("extensions", {}).setdefault("KHR_lights_punctual", {"lights": []})["lights"]
        lights.append(dict(name=name, **light))
        self.node(dict(name=name, **placement, extensions={"KHR_lights_punctual": {"light": len(lights) - 1}}))

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


def box(lo, hi, inward=False):
    """A closed axis-aligned box, as the tests' makeBox built it before these files: corner i
    takes hi where bit (x, y, z) of i is set; 12 triangles facing out (in), two per face in the
    order -x, +x, -y, +y, -z, +z."""
    corners = [[hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1], hi[2] if i & 4 else lo[2]] for i in range(8)]
    triangles = []
    for a, b, c, d in [[0, 4, 6, 2], [1, 3, 7, 5], [0, 1, 5, 4], [2, 6, 7, 3], [0, 2, 3, 1], [4, 5, 7, 6]]:
        if inward:
            b, d = d, b
        triangles += [[a, b, c], [a, c, d]]
    return corners, triangles


# ---- glTF: mesh-only scenes (a sky, which glTF cannot hold, is added by the test: README.md) ----

def cornell_box(file_name, scale, offset, what):
    """pt's built-in scene, scenes/cornell-box.gltf, mapped by p -> scale p + offset. The vertices
    and the camera are moved in the file (not by a node transform) so that they are exactly the
    float32 values the test's reference computation (scaledScene) gives."""
    with open(os.path.join(HERE, "..", "cornell-box.gltf")) as f:
        doc = json.load(f)
    blob = bytearray(base64.b64decode(doc["buffers"][0]["uri"].split(",", 1)[1]))

    def place(p):
        return [f32(f32(f32(scale) * f32(p[i])) + f32(offset[i])) for i in range(3)]

    for index in sorted({prim["attributes"]["POSITION"] for mesh in doc["meshes"] for prim in mesh["primitives"]}):
        acc = doc["accessors"][index]
        view = doc["bufferViews"][acc["bufferView"]]
        assert acc["componentType"] == 5126 and "byteStride" not in view
        start = view["byteOffset"] + acc.get("byteOffset", 0)
        values = struct.unpack_from("<%df" % (3 * acc["count"]), blob, start)
        points = [place(values[3 * i:3 * i + 3]) for i in range(acc["count"])]
        struct.pack_into("<%df" % (3 * acc["count"]), blob, start, *[c for p in points for c in p])
        acc["min"] = [short(min(p[i] for p in points)) for i in range(3)]
        acc["max"] = [short(max(p[i] for p in points)) for i in range(3)]
    for node in doc["nodes"]:
        if "camera" in node:
            node["translation"] = [short(c) for c in place(node.get("translation", [0.0, 0.0, 0.0]))]
    doc["asset"]["generator"] = "pt: scenes/hard/make_scenes.py, from scenes/cornell-box.gltf"
    doc["scenes"][0]["name"] = file_name[:-len(".gltf")]
    doc["scenes"][0]["extras"] = {"description": "scenes/cornell-box.gltf " + what + ": its mean radiance must not change.",
                                  "width": 48, "height": 48, "max_depth": 8}
    doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()
    with open(os.path.join(HERE, file_name), "w") as f:
        json.dump(doc, f, indent=1, allow_nan=False)
        f.write("\n")


def sealed_room(file_name, scale):
    """Scaled as the test's scaledScene did: positions f32(scale p); a point light's intensity
    times scale^2, so that the irradiance it gives stays the same."""
    s = f32(scale)

    def at(p):
        return [short(s * f32(c)) for c in p]

    g = Gltf(file_name[:-len(".gltf")],
             "A room that no light can enter: a box without a bottom standing on a floor, closed by a lid 1e-4 thick "
             "whose underside coincides with the walls' top faces, at scale %g. A point light and a sky of radiance 10 "
             "(added by the test: glTF has no sky; --env-colour 10 10 10 by hand) shine only outside; every pixel, "
             "seen from inside, must be exactly 0." % scale, width=32, height=32, max_depth=8)
    # Double-sided, so that light coming in through any gap is reflected on, not absorbed.
    wall = g.material("wall", base=0.8, double_sided=True)
    g.mesh("floor", wall, [at(p) for p in quad([-5, 0, 5], [10, 0, 0], [0, 0, -10])], QUAD)
    corners, triangles = box([-1, 0, -1], [1, 1, 1], inward=True)
    g.mesh("walls", wall, [at(p) for p in corners], triangles[:4] + triangles[6:])  # no bottom: it stands on the floor
    corners, triangles = box([-1, 1, -1], [1, f32(1.0001), 1])
    g.mesh("lid", wall, [at(p) for p in corners], triangles)
    g.point_light("sun", short(100 * f32(s * s)), at([0.5, 3.0, 0.3]))
    eye, target = [0.3, 0.5, 0.9], [-0.4, 0.3, -1.0]
    g.camera("inside", 1.6, at(eye), look_at_rotation(eye, target))
    g.write(file_name)


def grid(corner, u, v, n):
    """n x n quads on corner + [0,1]^2 (u, v), as the tests' makeGrid built them before these
    files, their diagonals alternating so that vertices are shared by 4, 6 and 8 triangles."""
    points = [[corner[k] + u[k] * (i / n) + v[k] * (j / n) for k in range(3)] for j in range(n + 1) for i in range(n + 1)]
    triangles = []
    for j in range(n):
        for i in range(n):
            a, b, c, d = j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i
            triangles += [[a, b, c], [a, c, d]] if (i + j) % 2 else [[a, b, d], [b, c, d]]
    return points, triangles


def watertight_cube():
    g = Gltf("watertight-cube",
             "A closed cube of 6 x 32 x 32 grids, one-sided and emitting 1 outwards, in a sky of radiance 5 (added by the "
             "test: glTF has no sky; --env-colour 5 5 5 by hand). Camera 0 looks at the face z = 1 so that its 32 x 32 "
             "pixels' corners fall on the grid's vertices, edges and diagonals; camera 1 at a general angle. Every ray "
             "must find a front face (1), never slip through to the back of the far face (0) or to the sky (5).",
             width=32, height=32, max_depth=1)
    glow = g.material("glow", base=0.0, emission=1.0)
    faces = {"+z": ([-1, -1, 1], [2, 0, 0], [0, 2, 0]), "-z": ([1, -1, -1], [-2, 0, 0], [0, 2, 0]),
             "-x": ([-1, -1, -1], [0, 0, 2], [0, 2, 0]), "+x": ([1, -1, 1], [0, 0, -2], [0, 2, 0]),
             "+y": ([-1, 1, 1], [2, 0, 0], [0, 0, -2]), "-y": ([-1, -1, -1], [2, 0, 0], [0, 0, 2])}
    for name, (corner, u, v) in faces.items():
        points, triangles = grid(corner, u, v, 32)
        g.mesh("face " + name, glow, points, triangles, short_indices=True)
    # tan(yfov / 2) = 1/2 from z = 2: the image spans [-1/2, 1/2]^2 of the face z = 1.
    g.camera("grid-aligned", short(2 * f32(math.atan(0.5))), [0, 0, 2], [0, 0, 0, 1])
    eye, target = [1.2, 1.4, 1.7], [0.01, -0.02, 0.03]
    g.camera("general angle", 1.2, eye, look_at_rotation(eye, target))
    g.write("watertight-cube.gltf")


def png_rgb8(width, height, texels):
    """A lossless 8-bit RGB PNG of `texels` ([r, g, b] row by row, top row first), with no gAMA,
    sRGB or iCCP chunk: a decoder gives back exactly these bytes."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    rows = b"".join(b"\0" + bytes(c for t in texels[y * width:(y + 1) * width] for c in t) for y in range(height))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


def normal_mapped_plane(file_name, what, sun_elevation_degrees=None, emitter_below=False):
    """The plane x, z in [-1, 1] facing +y (u along +x), its normal map 8 x 1 texels sampled
    nearest: stripes (+-0.87, 0, 0.5) in tangent space, stored as (n + 1) / 2, i.e. the bytes
    (239 or 16, 128, 191), tilting the shading normal by about 60 degrees towards +u and -u in
    turn. The camera looks down at its centre from (0, 2, 0.01), 0.005 rad off the vertical.
    Either a directional light of irradiance pi from `sun_elevation_degrees` above the horizon
    (towards +x; negative: below the plane) or, with `emitter_below`, a 20 x 20 emitter of
    radiance 1 0.5 below the plane facing it, which only BSDF-sampled rays can find."""
    g = Gltf(file_name[:-len(".gltf")],
             "A white Lambertian plane whose normal map tilts its shading normal by about 60 degrees in alternating "
             "stripes, seen from above, " + what, width=32, height=32, max_depth=2)
    stripes = png_rgb8(8, 1, [[16 if i % 2 else 239, 128, 191] for i in range(8)])
    white = g.material("white, normal-mapped", normal_texture=g.texture("stripes", stripes))
    g.mesh("plane", white, quad([-1, 0, 1], [2, 0, 0], [0, 0, -2]), QUAD, uvs=[[0, 1], [1, 1], [1, 0], [0, 0]])
    # The test's camera, lookAt((0, 2, 0.01), (0, 0, 0), 0.9) (tests/support/hard_case_support.cpp),
    # as floats: a node matrix whose columns the loader turns back into exactly its forward and up.
    eye = [0.0, 2.0, f32(0.01)]
    forward = f32_normalize([f32(0.0 - eye[i]) for i in range(3)])
    up = f32_normalize(f32_cross(f32_cross(forward, [0.0, 1.0, 0.0]), forward))
    back = f32_preimage([-c for c in forward], f32_normalize)  # the loader: forward = normalize(-z)

    def loaded_up(y):  # the loader: y made orthogonal to forward, normalised
        d = f32_dot(y, forward)
        return f32_normalize([f32(y[i] - f32(d * forward[i])) for i in range(3)])

    y = f32_preimage(up, loaded_up)
    g.camera("above", 0.9, matrix=columns(f32_normalize(f32_cross(y, back)), y, back, eye))
    if sun_elevation_degrees is not None:
        # The test's sun: direction -(cos e, sin e, 0) in float, e = glm::radians(float degrees).
        # It travels along the node's -z; the z column is -direction, renormalised by the loader.
        e = f32(f32(sun_elevation_degrees) * RADIANS_PER_DEGREE)
        to_light = [f32(math.cos(e)), f32(math.sin(e)), 0.0]
        z = f32_preimage(to_light, f32_normalize)
        g.directional_light("sun", math.pi, matrix=columns([0.0, 0.0, -1.0], [-z[1], z[0], 0.0], z))
    if emitter_below:
        lamp = g.material("lamp", base=0.0, emission=1.0)
        g.mesh("lamp below", lamp, quad([-10, -0.5, -10], [0, 0, 20], [20, 0, 0]), QUAD)
    g.write(file_name)


# ---- CENG795 XML: analytic spheres, glass and a sky ----

RADIANS_PER_DEGREE = f32(math.pi / 180)  # glm::radians' factor, a float
ALL_ON = "NextEventEstimation ImportanceSampling RussianRoulette"


def fovy_degrees(yfov):
    """FovY text that the loader (glm::radians on the float read) turns into exactly float32 yfov."""
    target = f32(yfov)
    bits = struct.unpack("<I", struct.pack("<f", f32(math.degrees(target))))[0]
    for k in sorted(range(-8, 9), key=abs):
        degrees = struct.unpack("<f", struct.pack("<I", bits + k))[0]
        if f32(degrees * RADIANS_PER_DEGREE) == target:
            return text(degrees)
    raise ValueError(yfov)


class CourseScene:
    """A CENG795 course scene (../shared/ceng795/FORMAT.md), written as indented XML text."""

    def __init__(self, description):
        self.description = description
        self.cameras, self.materials, self.vertices, self.objects = [], [], [], []
        self.sky = False
        self.max_recursion = None

    def camera(self, eye, target, yfov, size, params=ALL_ON):
        """A lookAt camera, path tracing with the course's RendererParams (it leaves a camera with
        RussianRoulette uncapped: MaxRecursionDepth only applies without)."""
        self.cameras.append(
            '        <Camera id="%d" type="lookAt">\n' % (len(self.cameras) + 1) +
            "            <Position>%s</Position>\n" % vec(eye) +
            "            <GazePoint>%s</GazePoint>\n" % vec(target) +
            "            <Up>0 1 0</Up>\n"
            "            <FovY>%s</FovY>\n" % fovy_degrees(yfov) +
            "            <ImageResolution>%d %d</ImageResolution>\n" % (size, size) +
            "            <Renderer>PathTracing</Renderer>\n"
            "            <RendererParams>%s</RendererParams>\n" % params +
            "        </Camera>")

    def _material(self, body, kind=None):
        self.materials.append('        <Material id="%d"%s>%s</Material>' % (
            len(self.materials) + 1, ' type="%s"' % kind if kind else "", body))
        return len(self.materials)

    def diffuse(self, albedo):
        return self._material("<DiffuseReflectance>%s</DiffuseReflectance>" % vec([albedo] * 3))

    def glass(self, ior):
        return self._material("<RefractionIndex>%s</RefractionIndex>" % text(ior), "dielectric")

    def _vertex(self, p):
        self.vertices.append("        " + vec(p))
        return len(self.vertices)

    def sphere(self, material, centre, radius, radiance=None):
        """A sphere; with `radiance`, a LightSphere (emitting on both sides, as course lights do)."""
        kind = "LightSphere" if radiance is not None else "Sphere"
        light = "<Radiance>%s</Radiance>" % vec([radiance] * 3) if radiance is not None else ""
        self.objects.append('        <%s id="%d"><Material>%d</Material><Center>%d</Center><Radius>%s</Radius>%s</%s>' % (
            kind, len(self.objects) + 1, material, self._vertex(centre), text(radius), light, kind))

    def mesh(self, material, points, triangles):
        ids = [self._vertex(p) for p in points]
        faces = "\n".join("                %d %d %d" % tuple(ids[i] for i in t) for t in triangles)
        self.objects.append('        <Mesh id="%d">\n            <Material>%d</Material>\n            <Faces>\n%s\n'
                            "            </Faces>\n        </Mesh>" % (len(self.objects) + 1, material, faces))

    def write(self, file_name):
        out = ["<!-- Written by scenes/hard/make_scenes.py (README.md there). " + self.description + " -->", "<Scene>"]
        if self.max_recursion is not None:
            out.append("    <MaxRecursionDepth>%d</MaxRecursionDepth>" % self.max_recursion)
        out += ["    <Cameras>"] + self.cameras + ["    </Cameras>"]
        if self.sky:
            out += ["    <Textures><Images><Image id=\"1\">white-sky.hdr</Image></Images></Textures>",
                    "    <Lights><SphericalDirectionalLight id=\"1\"><ImageId>1</ImageId></SphericalDirectionalLight></Lights>"]
        out += ["    <Materials>"] + self.materials + ["    </Materials>"]
        out += ["    <VertexData>"] + self.vertices + ["    </VertexData>"]
        out += ["    <Objects>"] + self.objects + ["    </Objects>", "</Scene>"]
        with open(os.path.join(HERE, file_name), "w") as f:
            f.write("\n".join(out) + "\n")


def white_sky():
    """white-sky.hdr: radiance 1 in every direction, as a Radiance RGBE lat-long map of 8 x 16
    texels, the size pt gives a constant environment (flat_scene.cpp), so that it is sampled
    exactly as --env-colour 1 1 1 is. RGBE (128, 128, 128, 129) is 128 * 2^(129 - 136) = 1."""
    header = b"#?RADIANCE\n# pt: scenes/hard/make_scenes.py, a white sky\nFORMAT=32-bit_rle_rgbe\n\n-Y 16 +X 8\n"
    with open(os.path.join(HERE, "white-sky.hdr"), "wb") as f:
        f.write(header + bytes([128, 128, 128, 129]) * (8 * 16))


def ground_sphere():
    x = CourseScene("A diffuse sphere of radius 1e5 (albedo 0.5) as the ground under a white sky: every point on it sees "
                    "the sky over its whole hemisphere, so every pixel is 0.5 (1 - 1e-5 for the curvature); acne darkens "
                    "pixels. The test renders with --max-depth 8.")
    x.camera([0.3, 1.0, 0.2], [0.3, 0.0, -1.0], 0.8, 32)
    x.sky = True
    x.sphere(x.diffuse(0.5), [0, -1e5, 0], 1e5)
    x.write("ground-sphere.xml")


def inside_sphere(file_name, radius):
    r = f32(radius)
    centre = [f32(f32(c) * r) for c in [0.3, -0.2, 0.1]]
    eye = [f32(centre[i] + f32(f32(c) * r)) for i, c in enumerate([0.5, 0.2, 0.0])]
    target = [f32(centre[0] - r), centre[1], centre[2]]
    x = CourseScene("The camera inside an emissive diffuse sphere of radius %g (Le 1, albedo 0.5), off centre: "
                    "L = Le (1 - rho^D) / (1 - rho) for D = 6 ray segments, no Russian roulette." % radius)
    x.max_recursion = 4  # with NEE the course counts MaxRecursionDepth + 2 = 6 segments, camera ray included
    x.camera(eye, target, 1.5, 24, "NextEventEstimation ImportanceSampling")
    x.sphere(x.diffuse(0.5), centre, r, radiance=1.0)
    x.write(file_name)


def tiny_far_sphere(file_name, direction, radius):
    d, r = 1e4, f32(radius)
    centre = [f32(d * c) for c in direction]
    x = CourseScene("An emissive sphere of radius %g at distance 1e4 along (%s), filling a quarter of the image: the "
                    "image integrates to its solid angle pi r^2 / d^2, and nothing lights up beyond its silhouette. "
                    "The test renders with --max-depth 2." % (radius, vec(direction)))
    x.camera([0, 0, 0], centre, 2 * f32(f32(4 * r) / d), 32)  # half-angle 4 r / d
    x.sphere(x.diffuse(0.0), centre, r, radiance=1.0)
    x.write(file_name)


def sphere_light(file_name, what, centre, radius, radiance):
    x = CourseScene("A white diffuse floor (albedo 1) under a sphere light, %s: E = pi L r^2 cos(alpha) / d^2 on the "
                    "floor. The test renders with --max-depth 2 (direct light only)." % what)
    x.camera([0.0, 1.5, 2.0], [0.0, 0.0, 0.2], 1.0, 32)
    x.mesh(x.diffuse(1.0), quad([-20, 0, 20], [40, 0, 0], [0, 0, -40]), QUAD)
    x.sphere(x.diffuse(0.0), centre, radius, radiance=radiance)
    x.write(file_name)


def glass_sphere_from_inside():
    x = CourseScene("The camera inside a glass sphere (radius 1, ior 1.5) under a white sky: rays whose line passes the "
                    "centre closer than 1 / 1.5 leave carrying 2.25 (the sky's radiance inside glass), farther ones are "
                    "totally internally reflected forever (0). The test renders with --max-depth 64.")
    x.camera([0.8, 0.0, 0.0], [-0.2, 0.0, -1.0], 1.6, 32)
    x.sky = True
    x.sphere(x.glass(1.5), [0, 0, 0], 1.0)
    x.write("glass-sphere-from-inside.xml")


def clear_glass(file_name, what, eye, yfov, boxes=(), spheres=()):
    x = CourseScene("Clear glass (ior 1.5) under a white sky, %s: every path that leaves carries exactly 1, so no pixel "
                    "may be above 1 and the mean is near 1. The test renders with --max-depth 64." % what)
    x.camera(eye, [0.0, 0.0, 0.0], yfov, 16)
    x.sky = True
    glass = x.glass(1.5)
    for lo, hi in boxes:
        x.mesh(glass, *box([f32(c) for c in lo], [f32(c) for c in hi]))
    for centre, radius in spheres:
        x.sphere(glass, centre, radius)
    x.write(file_name)


if __name__ == "__main__":
    degenerate_input()
    smooth_icosphere()
    for name, scale, offset, what in [("scale-1", 1.0, [0, 0, 0], "as it is"), ("scale-1e-3", 1e-3, [0, 0, 0], "scaled by 1e-3"),
                                      ("scale-1e3", 1e3, [0, 0, 0], "scaled by 1e3"),
                                      ("moved-1e4", 1.0, [1e4] * 3, "moved by (1e4, 1e4, 1e4)")]:
        cornell_box("cornell-box-%s.gltf" % name, scale, offset, what)
    for name, scale in [("1", 1.0), ("1e-3", 1e-3), ("1e3", 1e3)]:
        sealed_room("sealed-room-scale-%s.gltf" % name, scale)
    watertight_cube()
    normal_mapped_plane("normal-mapped-plane-light-below.gltf", "lit from 40 degrees below by a directional light of "
                        "irradiance pi: no light may come through, whatever the shading normal says.", -40.0)
    normal_mapped_plane("normal-mapped-plane-light-grazing.gltf", "lit from 10 degrees above by a directional light of "
                        "irradiance pi: every pixel within 0 <= L <= E / pi, the stripes tilted towards the light lit.", 10.0)
    normal_mapped_plane("normal-mapped-plane-emitter-below.gltf", "over a 20 x 20 emitter of radiance 1 0.5 below it: "
                        "reflections the normal map tilts below the plane must end there, so every pixel is 0.",
                        emitter_below=True)
    white_sky()
    ground_sphere()
    for name, radius in [("1e-3", 1e-3), ("1e-2", 1e-2), ("1", 1.0), ("1e4", 1e4)]:
        inside_sphere("inside-sphere-r%s.xml" % name, radius)
    tiny_far_sphere("tiny-far-sphere-ahead.xml", [0.0, 0.0, -1.0], 1e-3)
    # Along a diagonal the float ray directions are 6e-8 rad apart, more than half the angular
    # radius 1e-7 of a 1e-3 sphere: there it has radius 1e-2.
    tiny_far_sphere("tiny-far-sphere-diagonal.xml", f32_normalize([1.0, 1.0, 1.0]), 1e-2)
    sun_distance = 1000.0
    sun_radius = f32(sun_distance * f32(math.sin(f32(f32(0.265) * RADIANS_PER_DEGREE))))
    sun_centre = [f32(sun_distance * c) for c in f32_normalize([f32(0.3), f32(0.8), f32(0.2)])]
    sphere_light("sphere-light-sun.xml", "sun-sized (0.53 degrees across) at 1000", sun_centre, sun_radius, 20000.0)
    sphere_light("sphere-light-almost-touching.xml", "of radius 0.5, 1e-3 above the floor", [0.0, 0.501, 0.0], 0.5, 1.0)
    glass_sphere_from_inside()
    clear_glass("clear-glass-grazing-slab.xml", "a slab 0.1 thick seen at 2 degrees", [0.0, 0.15, 4.0], 0.3,
                boxes=[([-3, -0.05, -3], [3, 0.05, 3])])
    clear_glass("clear-glass-nested-spheres.xml", "a sphere inside another", [0.0, 0.0, 3.5], 0.7,
                spheres=[([0, 0, 0], 1.0), ([0.1, 0.2, 0.0], 0.5)])
    clear_glass("clear-glass-adjacent-blocks.xml", "two blocks 1e-4 apart", [0.5, 0.7, 3.5], 0.9,
                boxes=[([-1, -1, -1], [0, 1, 1]), ([0.0001, -1, -1], [1, 1, 1])])
