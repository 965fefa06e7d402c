#!/usr/bin/env python3
"""Writes the fuzz seed corpora (tests/fuzz/corpus/<target>/) and the data files their inputs
refer to (tests/fuzz/data/). Deterministic; Python 3 stdlib only. Seeds are small (libFuzzer's
default maximum input length is the largest seed) and each exercises a different code path: the
fuzzer mutates from there. Inputs a fuzzer once crashed on are added by hand as crash-*.

Usage: python3 make_seeds.py   (in this directory)
"""
import base64
import json
import struct
import zlib
from pathlib import Path

HERE = Path(__file__).resolve().parent
CORPUS = HERE / 'corpus'
DATA = HERE / 'data'


def write(path, content):
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(content if isinstance(content, bytes) else content.encode())


# ---- images ---------------------------------------------------------------------------------
def png(width, height, colour_type=6, bit_depth=8, interlace=0):
    channels = {0: 1, 2: 3, 3: 1, 4: 2, 6: 4}[colour_type]
    row_bytes = (width * channels * bit_depth + 7) // 8
    raw = b''.join(bytes([y % 5]) + bytes((x * 37 + y * 11) & 0xff for x in range(row_bytes)) for y in range(height))

    def chunk(kind, data):
        return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data))
    out = b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', width, height, bit_depth, colour_type, 0, 0, interlace))
    if colour_type == 3:
        out += chunk(b'PLTE', bytes(range(48)))
    return out + chunk(b'IDAT', zlib.compress(raw)) + chunk(b'IEND', b'')


def bmp(width, height):
    row = (width * 3 + 3) & ~3
    pixels = b''.join(bytes((x * 40 + y) & 0xff for x in range(width * 3)) + b'\0' * (row - width * 3) for y in range(height))
    header = struct.pack('<2sIHHI', b'BM', 54 + len(pixels), 0, 0, 54)
    info = struct.pack('<IiiHHIIiiII', 40, width, height, 1, 24, 0, len(pixels), 2835, 2835, 0, 0)
    return header + info + pixels


def tga(width, height, rle=False):
    header = struct.pack('<BBBHHBHHHHBB', 0, 0, 10 if rle else 2, 0, 0, 0, 0, 0, width, height, 32, 8)
    if not rle:
        return header + bytes((i * 13) & 0xff for i in range(width * height * 4))
    body = b''
    for _ in range(height):
        body += bytes([0x80 | (width - 1)]) + b'\x10\x20\x30\xff'
    return header + body


def hdr(width, height, rle=False):
    head = b'#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n' + f'-Y {height} +X {width}\n'.encode()
    if not rle:
        return head + b''.join(bytes([10 + i % 50, 20, 30, 128]) for i in range(width * height))
    # New-style RLE scanlines (width 8..32767): 2 2 hi lo, then four channel runs.
    body = b''
    for _ in range(height):
        body += bytes([2, 2, width >> 8, width & 0xff])
        for value in (40, 50, 60, 129):
            body += bytes([128 + width, value])
    return head + body


def ppm(width, height):
    return f'P6\n{width} {height}\n255\n'.encode() + bytes((i * 3) & 0xff for i in range(width * height * 3))


def gif(width, height):
    # A 1-bit GIF with an uncompressed-looking LZW stream for a tiny image (clear, data, end).
    return (b'GIF89a' + struct.pack('<HHBBB', width, height, 0x80, 0, 0) + b'\x00\x00\x00\xff\xff\xff' +
            b',' + struct.pack('<HHHHB', 0, 0, width, height, 0) + b'\x02\x02\x44\x01\x00;')


# ---- PLY ------------------------------------------------------------------------------------
CUBE_V = [(x, y, z) for x in (0, 1) for y in (0, 1) for z in (0, 1)]
CUBE_F = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]


def ply_ascii(normals=False, uvs=None, extra_element=False):
    props = 'property float x\nproperty float y\nproperty float z\n'
    if normals:
        props += 'property float nx\nproperty float ny\nproperty float nz\n'
    if uvs:
        props += f'property float {uvs[0]}\nproperty float {uvs[1]}\n'
    head = f'ply\nformat ascii 1.0\ncomment seed\nelement vertex {len(CUBE_V)}\n{props}'
    if extra_element:
        head += 'element material 1\nproperty uchar red\nproperty list uchar int tags\n'
    head += f'element face {len(CUBE_F)}\nproperty list uchar int vertex_indices\nend_header\n'
    body = ''
    for v in CUBE_V:
        row = list(v) + ([0, 0, 1] if normals else []) + ([v[0], v[1]] if uvs else [])
        body += ' '.join(str(c) for c in row) + '\n'
    if extra_element:
        body += '7 2 1 2\n'
    for f in CUBE_F:
        body += f'{len(f)} ' + ' '.join(map(str, f)) + '\n'
    return head + body


def ply_binary(big_endian=False, index_type='int', count_type='uchar', double=False):
    e = '>' if big_endian else '<'
    ftype, fch = ('double', 'd') if double else ('float', 'f')
    head = (f'ply\nformat binary_{"big" if big_endian else "little"}_endian 1.0\nelement vertex {len(CUBE_V)}\n'
            f'property {ftype} x\nproperty {ftype} y\nproperty {ftype} z\nproperty uchar red\n'
            f'element face {len(CUBE_F)}\nproperty list {count_type} {index_type} vertex_indices\nend_header\n').encode()
    ich = {'int': 'i', 'uint': 'I', 'short': 'h', 'ushort': 'H', 'uchar': 'B', 'int32': 'i', 'uint8': 'B'}[index_type]
    cch = {'uchar': 'B', 'ushort': 'H', 'int': 'i', 'uint8': 'B'}[count_type]
    body = b''.join(struct.pack(e + '3' + fch + 'B', *v, 200) for v in CUBE_V)
    body += b''.join(struct.pack(e + cch + str(len(f)) + ich, len(f), *f) for f in CUBE_F)
    return head + body


# ---- glTF -----------------------------------------------------------------------------------
FLOAT, UBYTE, USHORT, UINT = 5126, 5121, 5123, 5125


def gltf_doc(extra=None, mode=None, index_type=USHORT, with_uv_normal=False, uri='embed'):
    pos = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)]
    idx = [0, 1, 2, 2, 1, 3]
    data = b''.join(struct.pack('<3f', *p) for p in pos)
    views = [{'buffer': 0, 'byteOffset': 0, 'byteLength': 48}]
    accessors = [{'bufferView': 0, 'componentType': FLOAT, 'count': 4, 'type': 'VEC3', 'min': [0, 0, 0], 'max': [1, 1, 0]}]
    fmt = {UBYTE: 'B', USHORT: 'H', UINT: 'I'}[index_type]
    ib = struct.pack('<%d%s' % (len(idx), fmt), *idx)
    ib += b'\0' * (-len(ib) % 4)
    views.append({'buffer': 0, 'byteOffset': len(data), 'byteLength': len(ib)})
    accessors.append({'bufferView': 1, 'componentType': index_type, 'count': len(idx), 'type': 'SCALAR'})
    data += ib
    attributes = {'POSITION': 0}
    if with_uv_normal:
        nb = b''.join(struct.pack('<3f', 0, 0, 1) for _ in pos)
        ub = b''.join(struct.pack('<2f', p[0], p[1]) for p in pos)
        tb = b''.join(struct.pack('<4f', 1, 0, 0, 1) for _ in pos)
        for blob, kind in ((nb, 'VEC3'), (ub, 'VEC2'), (tb, 'VEC4')):
            views.append({'buffer': 0, 'byteOffset': len(data), 'byteLength': len(blob)})
            accessors.append({'bufferView': len(views) - 1, 'componentType': FLOAT, 'count': 4, 'type': kind})
            data += blob
        attributes.update({'NORMAL': 2, 'TEXCOORD_0': 3, 'TANGENT': 4})
    prim = {'attributes': attributes, 'indices': 1, 'material': 0}
    if mode is not None:
        prim['mode'] = mode
    buf = {'byteLength': len(data)}
    if uri == 'embed':
        buf['uri'] = 'data:application/octet-stream;base64,' + base64.b64encode(data).decode()
    elif uri is not None:
        buf['uri'] = uri
    doc = {'asset': {'version': '2.0'}, 'scene': 0, 'scenes': [{'nodes': [0]}],
           'nodes': [{'mesh': 0}], 'meshes': [{'primitives': [prim]}],
           'materials': [{'pbrMetallicRoughness': {'baseColorFactor': [0.8, 0.8, 0.8, 1]}}],
           'accessors': accessors, 'bufferViews': views, 'buffers': [buf]}
    if extra:
        extra(doc)
    return doc, data


def dumps(doc):
    return json.dumps(doc, separators=(',', ':'))


def glb(doc, data):
    doc = json.loads(json.dumps(doc))
    doc['buffers'][0].pop('uri', None)
    js = dumps(doc).encode()
    js += b' ' * (-len(js) % 4)
    data += b'\0' * (-len(data) % 4)
    body = struct.pack('<I4s', len(js), b'JSON') + js + struct.pack('<I4s', len(data), b'BIN\0') + data
    return struct.pack('<4sII', b'glTF', 2, 12 + len(body)) + body


def textured(doc):
    doc['images'] = [{'uri': 'data:image/png;base64,' + base64.b64encode(png(2, 2)).decode()}, {'uri': 'tex.png'}]
    doc['samplers'] = [{'magFilter': 9728, 'wrapS': 33071, 'wrapT': 33648}]
    doc['textures'] = [{'source': 0, 'sampler': 0}, {'source': 1}]
    doc['materials'] = [{'pbrMetallicRoughness': {'baseColorTexture': {'index': 0, 'extensions': {
        'KHR_texture_transform': {'offset': [0.5, 0], 'rotation': 0.3, 'scale': [2, 2]}}},
        'metallicRoughnessTexture': {'index': 1}, 'metallicFactor': 0.5, 'roughnessFactor': 0.5},
        'normalTexture': {'index': 1, 'scale': 0.5}, 'emissiveTexture': {'index': 0},
        'alphaMode': 'MASK', 'alphaCutoff': 0.3, 'doubleSided': True}]
    doc['extensionsUsed'] = ['KHR_texture_transform']


def materials_lights_camera(doc):
    doc['materials'] = [
        {'pbrMetallicRoughness': {'metallicFactor': 0}, 'extensions': {
            'KHR_materials_transmission': {'transmissionFactor': 1}, 'KHR_materials_ior': {'ior': 1.33},
            'KHR_materials_volume': {'thicknessFactor': 1, 'attenuationColor': [0.9, 0.8, 0.7], 'attenuationDistance': 2}}},
        {'pbrMetallicRoughness': {'metallicFactor': 0}, 'extensions': {'KHR_materials_specular': {
            'specularFactor': 0.5, 'specularColorFactor': [1, 0.5, 0.5]}}, 'alphaMode': 'BLEND'},
        {'emissiveFactor': [1, 1, 1], 'extensions': {'KHR_materials_emissive_strength': {'emissiveStrength': 5}}},
        {'pbrMetallicRoughness': {'metallicFactor': 0}, 'extensions': {'KHR_materials_diffuse_transmission': {
            'diffuseTransmissionFactor': 0.5, 'diffuseTransmissionColorFactor': [0.5, 1, 0.5]}}}]
    doc['meshes'][0]['primitives'][0]['extensions'] = {'KHR_materials_variants': {'mappings': [
        {'material': 3, 'variants': [0]}, {'material': 1, 'variants': [1, 0]}]}}
    doc['meshes'][0]['primitives'].append(dict(doc['meshes'][0]['primitives'][0], material=1, mode=5))
    doc['meshes'][0]['primitives'].append(dict(doc['meshes'][0]['primitives'][0], material=2, mode=6))
    doc['cameras'] = [{'type': 'perspective', 'perspective': {'yfov': 0.8, 'znear': 0.1, 'aspectRatio': 1.5}},
                      {'type': 'orthographic', 'orthographic': {'xmag': 1, 'ymag': 1, 'znear': 0.1, 'zfar': 10}}]
    doc['extensions'] = {'KHR_materials_variants': {'variants': [{'name': 'leaf'}, {'name': 'glass'}]},
                         'KHR_lights_punctual': {'lights': [
        {'type': 'point', 'intensity': 10, 'color': [1, 1, 1]},
        {'type': 'spot', 'intensity': 10, 'spot': {'innerConeAngle': 0.2, 'outerConeAngle': 0.5}, 'range': 5},
        {'type': 'directional', 'intensity': 2}]}}
    doc['nodes'] = [
        {'children': [1, 2, 3], 'matrix': [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1]},
        {'mesh': 0, 'translation': [0, 0, -3], 'rotation': [0, 0.3826834, 0, 0.9238795], 'scale': [1, 2, 1]},
        {'camera': 0, 'translation': [0, 0, 3], 'children': [4]},
        {'camera': 1, 'extensions': {'KHR_lights_punctual': {'light': 1}}},
        {'extensions': {'KHR_lights_punctual': {'light': 0}}, 'translation': [0, 2, 0]}]
    doc['scenes'] = [{'nodes': [0], 'extras': {'width': 64, 'height': 48, 'max_depth': 4}}]
    doc['extensionsUsed'] = ['KHR_lights_punctual', 'KHR_materials_transmission', 'KHR_materials_ior',
                             'KHR_materials_volume', 'KHR_materials_specular', 'KHR_materials_emissive_strength',
                             'KHR_materials_diffuse_transmission', 'KHR_materials_variants', 'KHR_materials_unknown']


def no_scene(doc):
    del doc['scene']
    del doc['scenes']
    doc['nodes'] = [{'children': [1]}, {'mesh': 0}]


# ---- CENG795 XML ----------------------------------------------------------------------------
CAM = ('<Cameras><Camera id="1"><Position>0 0 5</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>'
       '<NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance><ImageResolution>8 8</ImageResolution>'
       '<NumSamples>4</NumSamples><ImageName>x.png</ImageName></Camera>'
       '<Camera id="2" type="lookAt"><Position>5 5 5</Position><GazePoint>0 0 0</GazePoint><Up>0 1 0</Up>'
       '<FovY>45</FovY><NearDistance>1</NearDistance><ImageResolution>8 6</ImageResolution><ImageName>y.exr</ImageName>'
       '<FocusDistance>5</FocusDistance><ApertureSize>0.1</ApertureSize>'
       '<Tonemap><TMO>Photographic</TMO><TMOOptions>0.18 1</TMOOptions><Saturation>1.0</Saturation><Gamma>2.2</Gamma></Tonemap>'
       '<Renderer>PathTracing</Renderer><RendererParams>NextEventEstimation ImportanceSampling RussianRoulette</RendererParams>'
       '</Camera></Cameras>')
MATS = ('<Materials><Material id="1"><AmbientReflectance>0.1 0.1 0.1</AmbientReflectance><DiffuseReflectance>0.5 0.5 0.5'
        '</DiffuseReflectance><SpecularReflectance>1 1 1</SpecularReflectance><PhongExponent>10</PhongExponent></Material>'
        '<Material id="2" type="mirror"><DiffuseReflectance>0 0 0</DiffuseReflectance><MirrorReflectance>1 1 1'
        '</MirrorReflectance><Roughness>0.1</Roughness></Material>'
        '<Material id="3" type="conductor"><MirrorReflectance>1 0.8 0.6</MirrorReflectance><RefractionIndex>0.37'
        '</RefractionIndex><AbsorptionIndex>2.82</AbsorptionIndex></Material>'
        '<Material id="4" type="dielectric"><AbsorptionCoefficient>0.01 0.1 0.2</AbsorptionCoefficient>'
        '<RefractionIndex>1.5</RefractionIndex></Material>'
        '<Material id="5" BRDF="1" degamma="true"><DiffuseReflectance>0.5 0.43 0.285</DiffuseReflectance>'
        '<SpecularReflectance>1 0.86 0.57</SpecularReflectance></Material></Materials>'
        '<BRDFs><TorranceSparrow id="1" kdfresnel="true"><Exponent>50</Exponent></TorranceSparrow>'
        '<ModifiedBlinnPhong id="2" normalized="true"><Exponent>20</Exponent></ModifiedBlinnPhong></BRDFs>')
VERTS = '<VertexData>-1 -1 0  1 -1 0  1 1 0  -1 1 0  0 0 -2</VertexData><TexCoordData>0 0 1 0 1 1 0 1 0.5 0.5</TexCoordData>'
XFORMS = ('<Transformations><Translation id="1">0 0 -1</Translation><Scaling id="1">2 2 2</Scaling>'
          '<Rotation id="1">30 0 1 0</Rotation><Composite id="1">1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1</Composite></Transformations>')
LIGHTS = ('<Lights><AmbientLight>25 25 25</AmbientLight><PointLight id="1"><Position>0 4 0</Position><Intensity>100 100 100'
          '</Intensity></PointLight><DirectionalLight id="2"><Direction>0 -1 0</Direction><Radiance>1 1 1</Radiance>'
          '</DirectionalLight><SpotLight id="3"><Position>0 4 0</Position><Direction>0 -1 0</Direction><Intensity>50 50 50'
          '</Intensity><CoverageAngle>40</CoverageAngle><FalloffAngle>20</FalloffAngle></SpotLight><AreaLight id="4">'
          '<Position>0 3 0</Position><Normal>0 -1 0</Normal><Size>1</Size><Radiance>5 5 5</Radiance></AreaLight></Lights>')
TEXTURES = ('<Textures><Images><Image id="1">tex.png</Image><Image id="2">env.hdr</Image></Images>'
            '<TextureMap id="1" type="image"><ImageId>1</ImageId><DecalMode>replace_kd</DecalMode>'
            '<Interpolation>nearest</Interpolation><Normalizer>255</Normalizer></TextureMap>'
            '<TextureMap id="2" type="image"><ImageId>1</ImageId><DecalMode>bump_normal</DecalMode><BumpFactor>2</BumpFactor></TextureMap>'
            '<TextureMap id="3" type="checkerboard"><DecalMode>blend_kd</DecalMode><BlackColor>0 0 0</BlackColor>'
            '<WhiteColor>1 1 1</WhiteColor><Scale>0.5</Scale><Offset>0.1</Offset></TextureMap>'
            '<TextureMap id="4" type="perlin"><DecalMode>replace_normal</DecalMode><NoiseConversion>absval</NoiseConversion>'
            '<NoiseScale>3</NoiseScale></TextureMap></Textures>')


def scene(objects, head='', lights=LIGHTS, textures=''):
    return (f'<Scene><MaxRecursionDepth>6</MaxRecursionDepth><BackgroundColor>0 0 0</BackgroundColor>{head}{CAM}{lights}'
            f'{MATS}{textures}{XFORMS}{VERTS}<Objects>{objects}</Objects></Scene>\n')


XML_SEEDS = {
    'inline_mesh.xml': scene('<Mesh id="1"><Material>1</Material><Transformations>t1 s1 r1 c1</Transformations>'
                             '<Faces>1 2 3 1 3 4</Faces></Mesh><Triangle id="2"><Material>2</Material><Indices>1 2 5</Indices></Triangle>'),
    'zero_based.xml': scene('<Mesh id="1"><Material>3</Material><Faces vertexOffset="1" textureOffset="0">0 1 2</Faces></Mesh>',
                            head='<ZeroBasedIndexing>true</ZeroBasedIndexing>'),
    'ply_meshes.xml': scene('<Mesh id="1" shadingMode="smooth"><Material>4</Material><Faces plyFile="mesh.ply"/></Mesh>'
                            '<Mesh id="2"><Material>1</Material><Transformations>t1</Transformations><Faces plyFile="mesh_binary.ply"/></Mesh>'),
    'binary_files.xml': scene('<Mesh id="1"><Material>1</Material><Faces binaryFile="faces.bin"/></Mesh>').replace(
        VERTS, '<VertexData binaryFile="vertices.bin"/><TexCoordData binaryFile="uvs.bin"/>'),
    'instances.xml': scene('<Mesh id="1"><Material>1</Material><Faces>1 2 3</Faces></Mesh>'
                           '<MeshInstance id="2" baseMeshId="1" resetTransform="true"><Material>2</Material>'
                           '<Transformations>t1</Transformations></MeshInstance>'
                           '<MeshInstance id="3" baseMeshId="2"><Transformations>s1</Transformations>'
                           '<MotionBlur>0 1 0</MotionBlur></MeshInstance>'),
    'spheres_lights.xml': scene('<Sphere id="1"><Material>5</Material><Center>5</Center><Radius>0.5</Radius></Sphere>'
                                '<Sphere id="2"><Material>2</Material><Transformations>s1 r1</Transformations><Center>1</Center>'
                                '<Radius>1</Radius></Sphere><LightSphere id="3"><Material>1</Material><Center>2</Center>'
                                '<Radius>0.2</Radius><Radiance>10 10 10</Radiance></LightSphere>'
                                '<LightMesh id="4"><Material>1</Material><Faces>1 2 3</Faces><Radiance>4 4 4</Radiance></LightMesh>'),
    'textures.xml': scene('<Mesh id="1"><Material>1</Material><Textures>1 2</Textures><Faces>1 2 3 1 3 4</Faces></Mesh>'
                          '<Sphere id="2"><Material>1</Material><Textures>3 4</Textures><Center>5</Center><Radius>1</Radius></Sphere>',
                          textures=TEXTURES),
    'environment.xml': scene('<Sphere id="1"><Material>1</Material><Center>5</Center><Radius>1</Radius></Sphere>',
                             lights='<Lights><SphericalDirectionalLight id="1"><ImageId>2</ImageId></SphericalDirectionalLight></Lights>',
                             textures=TEXTURES),
    'comma_numbers.xml': scene('<Mesh id="1"><Material>1</Material><Faces>1,2,3</Faces></Mesh>').replace(
        '-1 -1 0  1 -1 0', '-1,-1,0, 1,-1,0'),
}


def main():
    # Data files the seeds refer to (relative references resolve against tests/fuzz/data).
    write(DATA / 'tex.png', png(4, 4))
    write(DATA / 'env.hdr', hdr(4, 2))
    write(DATA / 'mesh.ply', ply_ascii(normals=True, uvs=('u', 'v')))
    write(DATA / 'mesh_binary.ply', ply_binary())
    write(DATA / 'vertices.bin', struct.pack('<i', 4) + b''.join(struct.pack('<3f', *v) for v in
                                                                 [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)]))
    write(DATA / 'uvs.bin', struct.pack('<i', 4) + b''.join(struct.pack('<2f', *v) for v in [(0, 0), (1, 0), (1, 1), (0, 1)]))
    write(DATA / 'faces.bin', struct.pack('<i', 2) + struct.pack('<6i', 0, 1, 2, 0, 2, 3))
    doc, data = gltf_doc()
    write(DATA / 'triangles.bin', data)

    seeds = {
        'texture_image': {
            'rgba.png': png(3, 2), 'grey.png': png(2, 2, colour_type=0), 'palette.png': png(4, 1, colour_type=3),
            'grey16.png': png(2, 2, colour_type=0, bit_depth=16), 'interlaced.png': png(5, 3, colour_type=2, interlace=1),
            'rgb.bmp': bmp(3, 2), 'rgba.tga': tga(2, 2), 'rle.tga': tga(3, 2, rle=True),
            'flat.hdr': hdr(3, 2), 'rle.hdr': hdr(8, 2, rle=True), 'image.ppm': ppm(2, 2), 'image.gif': gif(2, 2),
        },
        'ply': {
            'ascii.ply': ply_ascii(), 'ascii_normals_uv.ply': ply_ascii(normals=True, uvs=('s', 't')),
            'ascii_extra_element.ply': ply_ascii(uvs=('texture_u', 'texture_v'), extra_element=True),
            'binary_le.ply': ply_binary(), 'binary_be.ply': ply_binary(big_endian=True, index_type='uint', count_type='ushort'),
            'binary_double.ply': ply_binary(double=True, index_type='uint8', count_type='uint8'),
            'binary_short.ply': ply_binary(index_type='short'),
        },
        'gltf': {
            'triangles.gltf': dumps(gltf_doc()[0]),
            'triangles_ubyte.gltf': dumps(gltf_doc(index_type=UBYTE)[0]),
            'strip_uint.gltf': dumps(gltf_doc(mode=5, index_type=UINT, with_uv_normal=True)[0]),
            'external_buffer.gltf': dumps(gltf_doc(uri='triangles.bin')[0]),
            'textured.gltf': dumps(gltf_doc(textured, with_uv_normal=True)[0]),
            'materials_lights_camera.gltf': dumps(gltf_doc(materials_lights_camera)[0]),
            'no_scene.gltf': dumps(gltf_doc(no_scene)[0]),
            'binary.glb': glb(*gltf_doc(with_uv_normal=True)),
        },
        'ceng795': XML_SEEDS,
    }
    for target, files in seeds.items():
        for name, content in files.items():
            write(CORPUS / target / name, content)


if __name__ == '__main__':
    main()
