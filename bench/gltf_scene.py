"""Small helpers the scene generators share: quads and boxes as (positions, indices), and a glTF
2.0 file of world-space meshes with an embedded buffer (make_near_light_scene.py,
make_many_lights_scene.py; make_ajar_scene.py takes `merge`)."""
import base64
import json
import struct


def quad(corner, u, v):
    """Two triangles over corner, corner+u, corner+u+v, corner+v; the front faces u x v."""
    p = [corner, [corner[i] + u[i] for i in range(3)], [corner[i] + u[i] + v[i] for i in range(3)],
         [corner[i] + v[i] for i in range(3)]]
    return p, [0, 1, 2, 0, 2, 3]


def merge(parts):
    """One mesh of several (positions, indices)."""
    pos, idx = [], []
    for p, i in parts:
        idx += [len(pos) + k for k in i]
        pos += p
    return pos, idx


def box(lo, hi):
    """An axis-aligned box standing on the floor (no bottom face), every face outwards."""
    x0, y0, z0 = lo
    x1, y1, z1 = hi
    return merge([quad([x0, y1, z1], [x1 - x0, 0, 0], [0, 0, z0 - z1]),   # top (+y)
                  quad([x0, y0, z1], [x1 - x0, 0, 0], [0, y1 - y0, 0]),   # front (+z)
                  quad([x1, y0, z0], [x0 - x1, 0, 0], [0, y1 - y0, 0]),   # back (-z)
                  quad([x1, y0, z1], [0, 0, z0 - z1], [0, y1 - y0, 0]),   # right (+x)
                  quad([x0, y0, z0], [0, 0, z1 - z0], [0, y1 - y0, 0])])  # left (-x)


def write_gltf(path, meshes, materials, camera_node, camera, scene_extras, generator, extensions_used=()):
    """meshes: (name, (positions, indices), material index); camera_node: the camera's node (its
    "camera" is 0); camera: the glTF camera; scene_extras: pt's hints (width, height, max_depth)."""
    blob = bytearray()
    views, accessors, gmeshes, nodes = [], [], [], []
    for name, (pos, idx), material in meshes:
        off = len(blob)
        blob += b"".join(struct.pack("<3f", *p) for p in pos)
        views.append({"buffer": 0, "byteOffset": off, "byteLength": 12 * len(pos)})
        lo = [min(p[i] for p in pos) for i in range(3)]
        hi = [max(p[i] for p in pos) for i in range(3)]
        accessors.append({"bufferView": len(views) - 1, "componentType": 5126, "count": len(pos), "type": "VEC3",
                          "min": lo, "max": hi})
        off = len(blob)
        blob += b"".join(struct.pack("<I", i) for i in idx)
        views.append({"buffer": 0, "byteOffset": off, "byteLength": 4 * len(idx)})
        accessors.append({"bufferView": len(views) - 1, "componentType": 5125, "count": len(idx), "type": "SCALAR"})
        gmeshes.append({"name": name, "primitives": [{"attributes": {"POSITION": len(accessors) - 2},
                                                      "indices": len(accessors) - 1, "material": material}]})
        nodes.append({"name": name, "mesh": len(gmeshes) - 1})
    nodes.append(camera_node)
    gltf = {"asset": {"version": "2.0", "generator": generator}, "scene": 0}
    if extensions_used:
        gltf["extensionsUsed"] = list(extensions_used)
    gltf.update({"scenes": [{"nodes": list(range(len(nodes))), "extras": scene_extras}], "nodes": nodes,
                 "cameras": [camera], "materials": materials, "meshes": gmeshes, "accessors": accessors,
                 "bufferViews": views,
                 "buffers": [{"byteLength": len(blob),
                              "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}]})
    with open(path, "w") as f:
        json.dump(gltf, f, indent=1)
