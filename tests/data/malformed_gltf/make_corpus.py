#!/usr/bin/env python3
"""Generate the malformed glTF corpus used by the renderer's error-handling tests.

Every file is a minimal scene (one triangle where geometry is needed) with
exactly one defect, so a test can assert that loading it fails with a
specific, readable message. Output is deterministic: re-running the script
must reproduce the committed files byte for byte.

Usage: make_corpus.py [OUTPUT_DIR]   (default: the directory of this script)
"""

import base64
import copy
import json
import math
import struct
import sys
import zlib
from pathlib import Path

# One triangle in the z=0 plane, plus its indices.
TRIANGLE = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)]
INDICES = [0, 1, 2]

FLOAT = 5126
UNSIGNED_SHORT = 5123
ARRAY_BUFFER = 34962
ELEMENT_ARRAY_BUFFER = 34963


def pad4(data: bytes, fill: bytes = b"\0") -> bytes:
    return data + fill * (-len(data) % 4)


def geometry_bytes(positions, indices) -> bytes:
    """POSITION floats followed by uint16 indices, each 4-byte aligned."""
    pos = b"".join(struct.pack("<3f", *p) for p in positions)
    idx = struct.pack("<%dH" % len(indices), *indices)
    return pad4(pos) + pad4(idx)


def data_uri(data: bytes) -> str:
    return "data:application/octet-stream;base64," + base64.b64encode(data).decode("ascii")


def triangle_doc(positions=TRIANGLE, indices=INDICES, uri="embed"):
    """A valid glTF 2.0 document for one indexed triangle.

    uri="embed" stores the buffer as a base64 data: URI; None omits the uri
    (GLB BIN chunk); any other string is used verbatim (external file).
    Returns (document, buffer bytes).
    """
    data = geometry_bytes(positions, indices)
    pos_len = len(positions) * 12
    buffer = {"byteLength": len(data)}
    if uri == "embed":
        buffer["uri"] = data_uri(data)
    elif uri is not None:
        buffer["uri"] = uri
    position_accessor = {
        "bufferView": 0,
        "componentType": FLOAT,
        "count": len(positions),
        "type": "VEC3",
    }
    # min/max are required for POSITION, but JSON cannot express NaN/Inf;
    # emitting them would make the file invalid JSON instead of carrying the
    # intended defect, so they are left out when the data is non-finite.
    coords = [c for p in positions for c in p]
    if all(math.isfinite(c) for c in coords):
        position_accessor["min"] = [min(p[i] for p in positions) for i in range(3)]
        position_accessor["max"] = [max(p[i] for p in positions) for i in range(3)]
    doc = {
        "asset": {"version": "2.0", "generator": "pt malformed corpus"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "accessors": [
            position_accessor,
            {
                "bufferView": 1,
                "componentType": UNSIGNED_SHORT,
                "count": len(indices),
                "type": "SCALAR",
            },
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": pos_len, "target": ARRAY_BUFFER},
            {
                "buffer": 0,
                "byteOffset": len(pad4(b"\0" * pos_len)),
                "byteLength": len(indices) * 2,
                "target": ELEMENT_ARRAY_BUFFER,
            },
        ],
        "buffers": [buffer],
    }
    return doc, data


def png_header(width: int, height: int) -> bytes:
    """A PNG signature and IHDR chunk (8-bit RGBA) with no image data."""
    ihdr = struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)
    chunk = struct.pack(">I", len(ihdr)) + b"IHDR" + ihdr + struct.pack(">I", zlib.crc32(b"IHDR" + ihdr))
    return b"\x89PNG\r\n\x1a\n" + chunk


def to_json(doc) -> bytes:
    # allow_nan=False: a stray NaN must fail here, not leak into a file
    # whose defect is supposed to be something else.
    return (json.dumps(doc, indent=2, allow_nan=False) + "\n").encode("utf-8")


def glb(doc, bin_data: bytes) -> bytes:
    json_chunk = pad4(json.dumps(doc, allow_nan=False).encode("utf-8"), b" ")
    bin_chunk = pad4(bin_data)
    body = struct.pack("<I4s", len(json_chunk), b"JSON") + json_chunk
    body += struct.pack("<I4s", len(bin_chunk), b"BIN\0") + bin_chunk
    return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body


def build():
    """Return {file name: bytes} for the whole corpus."""
    files = {}

    valid_text = to_json(triangle_doc()[0])
    files["truncated_json.gltf"] = valid_text[: len(valid_text) // 2]
    files["not_json.gltf"] = b"This is not a glTF file, just plain text.\n"
    files["empty.gltf"] = b""

    doc, _ = triangle_doc()
    del doc["asset"]
    files["no_asset.gltf"] = to_json(doc)

    doc, data = triangle_doc(uri=None)
    good_glb = glb(doc, data)
    files["bad_magic.glb"] = b"glTX" + good_glb[4:]
    # Header (12) + JSON chunk header (8) + part of the JSON: the declared
    # lengths now exceed the file.
    files["truncated_json_chunk.glb"] = good_glb[: 20 + 24]

    doc, _ = triangle_doc(uri="missing_triangle.bin")
    files["missing_bin.gltf"] = to_json(doc)

    doc, data = triangle_doc(uri="short.bin")
    files["short.bin"] = data[:20]  # byteLength says 44
    files["short_bin.gltf"] = to_json(doc)

    doc, _ = triangle_doc()
    doc["accessors"][0]["count"] = 100  # bufferView holds 3 vertices
    files["accessor_overflow.gltf"] = to_json(doc)

    doc, _ = triangle_doc()
    doc["accessors"][0]["count"] = 4000000000
    files["huge_count.gltf"] = to_json(doc)

    doc, _ = triangle_doc()
    doc["accessors"][0]["count"] = -1
    files["negative_count.gltf"] = to_json(doc)

    doc, _ = triangle_doc(indices=[0, 1, 7])
    files["index_out_of_range.gltf"] = to_json(doc)

    nan = float("nan")
    doc, _ = triangle_doc(positions=[(0.0, 0.0, 0.0), (1.0, nan, 0.0), (0.0, 1.0, 0.0)])
    files["position_nan.gltf"] = to_json(doc)

    inf = float("inf")
    doc, _ = triangle_doc(positions=[(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, inf, 0.0)])
    files["position_inf.gltf"] = to_json(doc)

    doc, _ = triangle_doc()
    # Same bytes reinterpreted as 3 x VEC2 (fits in the view): only the
    # declared type is wrong.
    doc["accessors"][0]["type"] = "VEC2"
    doc["accessors"][0]["min"] = doc["accessors"][0]["min"][:2]
    doc["accessors"][0]["max"] = doc["accessors"][0]["max"][:2]
    files["position_vec2.gltf"] = to_json(doc)

    # The triangle's outline as three index pairs: well-formed, but a path
    # tracer has nothing to intersect.
    doc, _ = triangle_doc(indices=[0, 1, 1, 2, 2, 0])
    doc["meshes"][0]["primitives"][0]["mode"] = 1  # LINES
    files["lines_only.gltf"] = to_json(doc)

    doc, _ = triangle_doc()
    doc["nodes"] = [{"mesh": 0, "children": [1]}, {"children": [0]}]
    files["cyclic_nodes.gltf"] = to_json(doc)

    doc, _ = triangle_doc()
    doc["cameras"] = [
        {"type": "perspective", "perspective": {"yfov": 0.0, "znear": 0.01, "aspectRatio": 1.0}}
    ]
    doc["nodes"].append({"camera": 0, "translation": [0.0, 0.0, 3.0]})
    doc["scenes"][0]["nodes"].append(1)
    files["camera_yfov_zero.gltf"] = to_json(doc)

    doc, _ = triangle_doc()
    doc["buffers"][0]["uri"] = "data:application/octet-stream;base64,!!not*base64!!"
    files["bad_base64.gltf"] = to_json(doc)

    doc, _ = triangle_doc()
    doc["nodes"][0]["mesh"] = 5  # only mesh 0 exists
    files["mesh_index_out_of_range.gltf"] = to_json(doc)

    doc, _ = triangle_doc()
    doc["accessors"][0]["bufferView"] = 9  # only views 0 and 1 exist
    files["bufferview_index_out_of_range.gltf"] = to_json(doc)

    # 40 nodes that each list the next one twice: 2^40 instances of the last node's mesh from a
    # file of a few kilobytes (glTF forbids shared children; a loader must not trust that).
    doc, _ = triangle_doc()
    doc["nodes"] = [{"children": [i + 1, i + 1]} for i in range(40)] + [{"mesh": 0}]
    files["exponential_instances.gltf"] = to_json(doc)

    # A chain of 1100 nodes (more than the 1024 levels a loader follows), each the only child of the previous one.
    doc, _ = triangle_doc()
    doc["nodes"] = [{"children": [i + 1]} for i in range(1100)] + [{"mesh": 0}]
    files["deep_hierarchy.gltf"] = to_json(doc)

    doc, _ = triangle_doc()
    doc["scenes"][0]["extras"] = {"width": 100000, "height": 100000}
    files["absurd_resolution.gltf"] = to_json(doc)

    doc, _ = triangle_doc()
    doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.01, "aspectRatio": 1e-9}}]
    doc["nodes"].append({"camera": 0, "translation": [0.0, 0.0, 3.0]})
    doc["scenes"][0]["nodes"].append(1)
    files["absurd_aspect_ratio.gltf"] = to_json(doc)

    # A PNG whose header claims 100000 x 100000 pixels (40 GB decoded), as a data URI.
    doc, _ = triangle_doc()
    doc["images"] = [{"uri": "data:image/png;base64," + base64.b64encode(png_header(100000, 100000)).decode("ascii")}]
    doc["textures"] = [{"source": 0}]
    doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
    doc["meshes"][0]["primitives"][0]["material"] = 0
    files["texture_100000x100000.gltf"] = to_json(doc)

    doc, _ = triangle_doc()
    doc["images"] = [{"uri": "missing_texture.png"}]
    doc["textures"] = [{"source": 0}]
    doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
    doc["meshes"][0]["primitives"][0]["material"] = 0
    files["missing_image.gltf"] = to_json(doc)

    doc, _ = triangle_doc()
    doc["accessors"][1]["componentType"] = FLOAT  # indices must be unsigned integers
    doc["accessors"][1]["bufferView"] = 0  # the positions' view: three floats fit there
    files["float_indices.gltf"] = to_json(doc)

    doc, _ = triangle_doc()
    doc["accessors"][0]["count"] = "three"
    files["count_is_a_string.gltf"] = to_json(doc)

    # A mesh name with bytes that are not UTF-8 (JSON must be UTF-8).
    files["non_utf8_json.gltf"] = to_json(triangle_doc()[0]).replace(b'"asset": {', b'"asset": {\n    "copyright": "\xff\xfe",', 1)

    # A buffer that is a character device: endless zeros, not a file.
    doc, _ = triangle_doc(uri="/dev/zero")
    files["buffer_is_a_device.gltf"] = to_json(doc)

    # A buffer that is a folder (this one): tinygltf's own reader asked for 2^63 bytes.
    doc, _ = triangle_doc(uri=".")
    files["buffer_is_a_directory.gltf"] = to_json(doc)

    return files


def main():
    out = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent
    out.mkdir(parents=True, exist_ok=True)
    for name, data in sorted(build().items()):
        (out / name).write_bytes(data)
        print(f"{name}: {len(data)} bytes")


if __name__ == "__main__":
    main()
