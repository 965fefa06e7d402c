#!/usr/bin/env python3
"""Writes a hard-lighting benchmark scene of the "Veach Ajar" kind: two closed rooms joined by a
doorway whose door stands ajar (12 degrees by default), lit by one small one-sided area light in
the far room. The camera stands in the near room looking at the door wall and the floor by the
gap; nothing it sees in its room is lit directly, every light path reaches it through the narrow
slot between the door's free edge and the jamb (or the thin wedge above the door).

Why: next event estimation from room A is almost always occluded (the lamp is behind the door
and the wall), and BSDF-sampled paths rarely find a lamp 0.3 m across through a slot 0.15 m
wide (a few centimetres as the lamp sees it), so unidirectional path tracing stays noisy for a long time; light subpaths
leave the lamp, pass the gap and land on room A's floor, where a connection to the camera
finds them: bidirectional path tracing's territory.

Layout (metres, +y up; building x in [-2, 2], y in [0, 2.6]):
  room A (camera): z in [0, 4.5]; room B (light): z in [-4.1, -0.1]; between them a wall 0.1
  thick (z in [-0.1, 0]) with a doorway x in [0.2, 1.1], y in [0, 2.0]. The door (0.04 thick,
  wood) hangs on a vertical hinge at (0.2, -0.1) and is swung into room B, its free edge near
  x = 1.1; its hinge end is buried in the wall so the hinge side is light-tight. The lamp is a
  0.3 m square on room B's back wall (z = -4.1), centre (1.5, 1.2), facing +z. A blue box stands
  in room A left of the door, a grey-green box in room B away from the lamp's beam. Camera at
  (-0.85, 1.3, 3.7) looking at (0.55, 0.65, 0), +y up, vertical field of view 50 degrees.
  Albedos: walls and ceiling 0.7 grey, floor (0.58, 0.5, 0.42), door (0.6, 0.42, 0.26), boxes
  (0.15, 0.3, 0.65) and (0.45, 0.55, 0.4); lamp radiance 5000 (white; mean of the image ~0.13).
All surfaces are Lambertian (KHR_materials_specular specularFactor 0, double-sided; Mitsuba
`twosided` `diffuse`); the lamp is single-sided (front = counter-clockwise winding, both files).
The enclosing box is closed and the wall pieces overlap it and each other (no coplanar seams
that a ray could slip through).

Writes, from one list of triangles and one camera (origin/target/up) in this script:
  OUT_DIR/scene.gltf            glTF 2.0, embedded base64 buffer, world-space meshes, camera node
  OUT_DIR/mitsuba/scene.xml     Mitsuba 3 (scene version 3.0.0) + one binary PLY per mesh, the
                                conventions of tests/references/cbox-diffuse/mitsuba
  OUT_DIR/meta.json             image size, camera, materials, triangles (bench_vs_mitsuba.py)

    python3 bench/make_ajar_scene.py OUT_DIR [--width 320 --height 180] [--max-depth 16]
        [--door-angle 12] [--radiance 5000] [--sky RADIANCE]
    build/pt render OUT_DIR/scene.gltf --spp 64 -o OUT_DIR/pt.exr
    mitsuba OUT_DIR/mitsuba/scene.xml -Dspp=64

--sky RADIANCE: daylight instead of the lamp. Room B has no back wall (its far end opens onto a
uniform sky of that radiance) and no lamp; room A still sees only what comes through the gap.
glTF has no environment, so pt takes the sky from its command line (--env-colour R R R); the
Mitsuba file has a `constant` emitter.
"""
import argparse
import base64
import json
import math
import os
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gltf_scene import merge  # noqa: E402

# ---- layout ----
X0, X1 = -2.0, 2.0          # side walls
Y0, Y1 = 0.0, 2.6           # floor, ceiling
ZB, ZA = -4.1, 4.5          # room B's back wall, room A's back wall (behind the camera)
WALL_Z0, WALL_Z1 = -0.1, 0.0  # the wall between the rooms
DOOR_X0, DOOR_X1, DOOR_TOP = 0.2, 1.1, 2.0  # the doorway
DOOR_THICK = 0.04
OVER = 0.05                  # how far wall pieces reach past what they meet (no coplanar seams)
LIGHT_CENTRE, LIGHT_SIZE = (1.5, 1.2), 0.3

CAMERA = {"origin": [-0.85, 1.3, 3.7], "target": [0.55, 0.65, 0.0], "up": [0.0, 1.0, 0.0], "yfov_deg": 50.0}

MATERIALS = {  # name: linear RGB albedo (Lambertian)
    "wall": [0.7, 0.7, 0.7],
    "floor": [0.58, 0.5, 0.42],
    "door": [0.6, 0.42, 0.26],
    "blue": [0.15, 0.3, 0.65],
    "sage": [0.45, 0.55, 0.4],
}


def add(a, b):
    return [a[i] + b[i] for i in range(3)]


def scale(a, s):
    return [a[i] * s for i in range(3)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def normalize(a):
    n = math.sqrt(sum(x * x for x in a))
    return [x / n for x in a]


def quad(corner, u, v):
    """Two triangles over corner, corner+u, corner+u+v, corner+v; front (counter-clockwise) side
    faces u x v."""
    return [corner, add(corner, u), add(add(corner, u), v), add(corner, v)], [0, 1, 2, 0, 2, 3]


def frame_box(o, ex, ey, ez, bottom=True):
    """The box {o + a ex + b ey + c ez : a, b, c in [0, 1]} (ex, ey, ez right-handed), every face
    counter-clockwise seen from outside; bottom=False leaves out the -ey face (a box standing on
    the floor)."""
    faces = [quad(o, ez, ey),                  # -ex
             quad(add(o, ex), ey, ez),         # +ex
             quad(add(o, ey), ez, ex),         # +ey
             quad(o, ey, ex),                  # -ez
             quad(add(o, ez), ex, ey)]         # +ez
    if bottom:
        faces.append(quad(o, ex, ez))          # -ey
    return merge(faces)


def box(lo, hi, bottom=True):
    return frame_box(lo, [hi[0] - lo[0], 0, 0], [0, hi[1] - lo[1], 0], [0, 0, hi[2] - lo[2]], bottom)


def build(door_angle_deg, daylight=False):
    """[(name, material, (positions, indices))], all in world space. daylight: room B's back wall
    and the lamp left out."""
    dx, dy, dz = [X1 - X0, 0, 0], [0, Y1 - Y0, 0], [0, 0, ZA - ZB]
    # The enclosing box, faces towards the inside.
    faces = [quad([X0, Y1, ZB], [X1 - X0, 0, 0], [0, 0, ZA - ZB]),   # ceiling (-y)
             quad([X0, Y0, ZB], dy, dz),                              # x = X0 (+x)
             quad([X1, Y0, ZB], dz, dy),                              # x = X1 (-x)
             quad([X0, Y0, ZB], dx, dy),                              # room B's back wall (+z)
             quad([X0, Y0, ZA], dy, dx)]                              # room A's back wall (-z)
    if daylight:
        del faces[3]  # room B opens onto the sky
    room = merge(faces)
    floor = quad([X0, Y0, ZB], dz, dx)                                     # (+y)
    # The wall between the rooms: left and right of the doorway and the lintel above it, each
    # reaching OVER past the enclosing box and into its neighbours.
    lo_y, hi_y = Y0 - OVER, Y1 + OVER
    wall = merge([box([X0 - OVER, lo_y, WALL_Z0], [DOOR_X0, hi_y, WALL_Z1]),
                  box([DOOR_X1, lo_y, WALL_Z0], [X1 + OVER, hi_y, WALL_Z1]),
                  box([DOOR_X0 - OVER, DOOR_TOP, WALL_Z0], [DOOR_X1 + OVER, hi_y, WALL_Z1])])
    # The door: closed, it would fill the doorway's room-B half (z in [-0.1, -0.06]); it turns
    # about the vertical line through (DOOR_X0, WALL_Z0) so that its free edge swings into room B.
    # Its hinge end reaches OVER back into the wall and its top and bottom 0.02 and 0.01 past the
    # lintel and floor, so the only openings are the slot at the free edge and the wedge above.
    t = math.radians(door_angle_deg)
    c, s = math.cos(t), math.sin(t)
    along = [c, 0, -s]                  # from hinge to free edge
    through = [s, 0, c]                 # from the room-B face to the room-A face
    width = DOOR_X1 - DOOR_X0 - 0.01    # a little narrower than the doorway
    hinge = [DOOR_X0, -0.01, WALL_Z0]
    o = add(hinge, scale(along, -OVER))
    door = frame_box(o, scale(along, width + OVER), [0, DOOR_TOP + 0.02 + 0.01, 0], scale(through, DOOR_THICK))
    box_a = box([-1.3, Y0, 0.9], [-0.6, 0.6, 1.6], bottom=False)
    box_b = box([-1.2, Y0, -2.6], [-0.4, 0.9, -1.8], bottom=False)
    h = LIGHT_SIZE / 2
    light = quad([LIGHT_CENTRE[0] - h, LIGHT_CENTRE[1] - h, ZB + 0.002], [LIGHT_SIZE, 0, 0], [0, LIGHT_SIZE, 0])  # +z
    return [("room", "wall", room), ("floor", "floor", floor), ("door_wall", "wall", wall), ("door", "door", door),
            ("box_a", "blue", box_a), ("box_b", "sage", box_b)] + ([] if daylight else [("light", "light", light)])


def camera_rotation(origin, target, up):
    """Unit quaternion [x, y, z, w] turning the glTF camera (looking down -Z, +Y up) to look from
    origin at target with up as up: the same frame as Mitsuba's <lookat>."""
    f = normalize([target[i] - origin[i] for i in range(3)])
    z = scale(f, -1.0)
    x = normalize(cross(up, z))
    y = cross(z, x)
    m = [[x[0], y[0], z[0]], [x[1], y[1], z[1]], [x[2], y[2], z[2]]]  # columns x, y, z
    tr = m[0][0] + m[1][1] + m[2][2]
    if tr > 0:
        w = math.sqrt(1.0 + tr) * 2
        q = [(m[2][1] - m[1][2]) / w, (m[0][2] - m[2][0]) / w, (m[1][0] - m[0][1]) / w, 0.25 * w]
    elif m[0][0] > m[1][1] and m[0][0] > m[2][2]:
        w = math.sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]) * 2
        q = [0.25 * w, (m[0][1] + m[1][0]) / w, (m[0][2] + m[2][0]) / w, (m[2][1] - m[1][2]) / w]
    elif m[1][1] > m[2][2]:
        w = math.sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]) * 2
        q = [(m[0][1] + m[1][0]) / w, 0.25 * w, (m[1][2] + m[2][1]) / w, (m[0][2] - m[2][0]) / w]
    else:
        w = math.sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]) * 2
        q = [(m[0][2] + m[2][0]) / w, (m[1][2] + m[2][1]) / w, 0.25 * w, (m[1][0] - m[0][1]) / w]
    return q


def f32(v):
    """v rounded to float32, as both files store it."""
    return struct.unpack("<f", struct.pack("<f", v))[0]


def meta(a, meshes):
    tris = {name: len(idx) // 3 for name, _, (_, idx) in meshes}
    mats = {k: {"type": "diffuse", "rgb": v} for k, v in MATERIALS.items()}
    if a.sky is None:
        mats["light"] = {"type": "emitter", "rgb": [a.radiance] * 3, "one_sided": True}
        description = ("Two closed rooms, a door ajar %g degrees between them, a %g m square one-sided lamp in "
                       "room B; the camera in room A sees only light that came through the gap. All Lambertian."
                       % (a.door_angle, LIGHT_SIZE))
    else:
        description = ("Two rooms, a door ajar %g degrees between them; room B's far end is open to a uniform sky "
                       "of radiance %g (pt: --env-colour %g %g %g); the camera in room A sees only light that came "
                       "through the gap. All Lambertian." % ((a.door_angle, a.sky) + (a.sky,) * 3))
    return {"name": "ajar" if a.sky is None else "ajar-daylight", "description": description,
            "width": a.width, "height": a.height,
            "camera": dict(CAMERA, model="pinhole", fov_axis="vertical"),
            "integrator": "path (unidirectional, NEE + BSDF sampling with MIS)", "max_depth": a.max_depth,
            "max_depth_meaning": "maximum number of ray segments per camera path INCLUDING the primary camera ray "
                                 "(Mitsuba 3 `path` max_depth)",
            "rr_depth": 1000, "rr_note": "rr_depth > max_depth: no Russian roulette",
            "pixel_filter": "box (uniform over the pixel footprint)",
            "output": "linear RGB radiance, float32 EXR, no tonemapping",
            "triangles": tris, "triangles_total": sum(tris.values()), "materials": mats,
            **({} if a.sky is None else {"sky_radiance": a.sky})}


def write_gltf(path, a, meshes, info):
    names = list(MATERIALS) + (["light"] if a.sky is None else [])
    spec0 = {"KHR_materials_specular": {"specularFactor": 0.0, "specularColorFactor": [1.0, 1.0, 1.0]}}
    materials = []
    for name in MATERIALS:
        materials.append({"name": name, "doubleSided": True,
                          "pbrMetallicRoughness": {"baseColorFactor": MATERIALS[name] + [1.0], "metallicFactor": 0.0,
                                                   "roughnessFactor": 1.0},
                          "extensions": spec0})
    if a.sky is None:
        materials.append({"name": "light", "doubleSided": False,
                              "pbrMetallicRoughness": {"baseColorFactor": [0.0, 0.0, 0.0, 1.0],
                                                       "metallicFactor": 0.0, "roughnessFactor": 1.0},
                              "emissiveFactor": [1.0, 1.0, 1.0],
                              "extensions": dict(spec0, KHR_materials_emissive_strength={
                                  "emissiveStrength": a.radiance})})
    blob = bytearray()
    views, accessors, gmeshes, nodes = [], [], [], []
    for name, material, (pos, idx) in meshes:
        off = len(blob)
        blob += b"".join(struct.pack("<3f", *p) for p in pos)
        views.append({"buffer": 0, "byteOffset": off, "byteLength": 12 * len(pos), "target": 34962})
        lo = [min(f32(p[i]) for p in pos) for i in range(3)]
        hi = [max(f32(p[i]) for p in pos) for i in range(3)]
        accessors.append({"bufferView": len(views) - 1, "componentType": 5126, "count": len(pos), "type": "VEC3",
                          "min": lo, "max": hi})
        off = len(blob)
        blob += b"".join(struct.pack("<I", i) for i in idx)
        views.append({"buffer": 0, "byteOffset": off, "byteLength": 4 * len(idx), "target": 34963})
        accessors.append({"bufferView": len(views) - 1, "componentType": 5125, "count": len(idx), "type": "SCALAR"})
        gmeshes.append({"name": name, "primitives": [{"attributes": {"POSITION": len(accessors) - 2},
                                                      "indices": len(accessors) - 1,
                                                      "material": names.index(material), "mode": 4}]})
        nodes.append({"name": name, "mesh": len(gmeshes) - 1})
    nodes.append({"name": "camera", "camera": 0, "translation": CAMERA["origin"],
                  "rotation": camera_rotation(CAMERA["origin"], CAMERA["target"], CAMERA["up"])})
    gltf = {"asset": {"version": "2.0", "generator": "pt bench/make_ajar_scene.py"},
            "extensionsUsed": ["KHR_materials_emissive_strength", "KHR_materials_specular"],
            "scene": 0,
            "scenes": [{"name": "ajar", "nodes": list(range(len(nodes))), "extras": info}],
            "nodes": nodes,
            "cameras": [{"type": "perspective", "name": "camera",
                         "perspective": {"yfov": math.radians(CAMERA["yfov_deg"]), "aspectRatio": a.width / a.height,
                                         "znear": 0.001, "zfar": 1000.0}}],
            "materials": materials, "meshes": gmeshes, "accessors": accessors, "bufferViews": views,
            "buffers": [{"byteLength": len(blob),
                         "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}]}
    with open(path, "w") as f:
        json.dump(gltf, f, indent=1)


def write_ply(path, pos, idx):
    """Binary little-endian PLY as in tests/references/cbox-diffuse/mitsuba: float x y z, faces as
    uchar-counted int lists."""
    header = ("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty float x\nproperty float y\n"
              "property float z\nelement face %d\nproperty list uchar int vertex_indices\nend_header\n"
              % (len(pos), len(idx) // 3))
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(b"".join(struct.pack("<3f", *p) for p in pos))
        f.write(b"".join(struct.pack("<B3i", 3, *idx[k:k + 3]) for k in range(0, len(idx), 3)))


def vec(v):
    return ", ".join("%.9g" % x for x in v)


def write_mitsuba(directory, a, meshes):
    os.makedirs(directory, exist_ok=True)
    cam = CAMERA
    lines = ['<?xml version="1.0" encoding="utf-8"?>',
             "<!-- ajar: generated by bench/make_ajar_scene.py; same triangles and camera as ../scene.gltf -->",
             '<scene version="3.0.0">',
             '  <default name="spp" value="64"/>',
             '  <default name="max_depth" value="%d"/>' % a.max_depth,
             '  <default name="rr_depth" value="1000"/>',
             '  <integrator type="path">',
             '    <integer name="max_depth" value="$max_depth"/>',
             '    <integer name="rr_depth" value="$rr_depth"/>',
             "  </integrator>",
             '  <sensor type="perspective">',
             '    <string name="fov_axis" value="y"/>',
             '    <float name="fov" value="%.9g"/>' % cam["yfov_deg"],
             '    <float name="near_clip" value="0.001"/>',
             '    <float name="far_clip" value="1000"/>',
             '    <transform name="to_world">',
             '      <lookat origin="%s" target="%s" up="%s"/>'
             % (vec(cam["origin"]), vec(cam["target"]), vec(cam["up"])),
             "    </transform>",
             '    <sampler type="independent">',
             '      <integer name="sample_count" value="$spp"/>',
             "    </sampler>",
             '    <film type="hdrfilm">',
             '      <integer name="width" value="%d"/>' % a.width,
             '      <integer name="height" value="%d"/>' % a.height,
             '      <string name="pixel_format" value="rgb"/>',
             '      <string name="component_format" value="float32"/>',
             '      <rfilter type="box"/>',
             "    </film>",
             "  </sensor>"]
    for name, rgb in MATERIALS.items():
        lines += ['  <bsdf type="twosided" id="mat-%s">' % name,
                  '    <bsdf type="diffuse">',
                  '      <rgb name="reflectance" value="%s"/>' % vec(rgb),
                  "    </bsdf>",
                  "  </bsdf>"]
    if a.sky is not None:
        lines += ['  <emitter type="constant">',
                  '    <rgb name="radiance" value="%s"/>' % vec([a.sky] * 3),
                  "  </emitter>"]
    if a.sky is None:
        lines += ['  <bsdf type="diffuse" id="mat-light">',
                  '    <rgb name="reflectance" value="0, 0, 0"/>',
                  "  </bsdf>"]
    for name, material, (pos, idx) in meshes:
        write_ply(os.path.join(directory, name + ".ply"), pos, idx)
        lines += ['  <shape type="ply" id="%s">' % name,
                  '    <string name="filename" value="%s.ply"/>' % name,
                  '    <boolean name="face_normals" value="true"/>',
                  '    <ref id="mat-%s"/>' % material]
        if material == "light":
            lines += ['    <emitter type="area">',
                      '      <rgb name="radiance" value="%s"/>' % vec([a.radiance] * 3),
                      "    </emitter>"]
        lines.append("  </shape>")
    lines.append("</scene>")
    with open(os.path.join(directory, "scene.xml"), "w") as f:
        f.write("\n".join(lines) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out_dir")
    ap.add_argument("--width", type=int, default=320)
    ap.add_argument("--height", type=int, default=180)
    ap.add_argument("--max-depth", type=int, default=16,
                    help="ray segments per path including the camera ray (glTF extras and Mitsuba's path)")
    ap.add_argument("--door-angle", type=float, default=12.0, help="how far the door stands open, degrees")
    ap.add_argument("--radiance", type=float, default=5000.0, help="the lamp's radiance (white)")
    ap.add_argument("--sky", type=float, default=None,
                    help="daylight: no lamp, room B open at its far end to a uniform sky of this radiance")
    a = ap.parse_args()
    if a.sky is not None and not a.sky > 0.0:
        ap.error("--sky must be positive")
    if not 0.0 < a.door_angle < 60.0:
        ap.error("--door-angle must be in (0, 60)")
    os.makedirs(a.out_dir, exist_ok=True)
    meshes = build(a.door_angle, daylight=a.sky is not None)
    info = meta(a, meshes)
    write_gltf(os.path.join(a.out_dir, "scene.gltf"), a, meshes, info)
    write_mitsuba(os.path.join(a.out_dir, "mitsuba"), a, meshes)
    with open(os.path.join(a.out_dir, "meta.json"), "w") as f:
        json.dump(info, f, indent=1)
    print("%s: %d triangles" % (a.out_dir, info["triangles_total"]))


if __name__ == "__main__":
    main()
