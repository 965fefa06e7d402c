#!/usr/bin/env python3
"""Writes the malformed CENG795 XML corpus and its README table (deterministic)."""
import struct
import zlib

CAM = ('<Cameras><Camera id="1"><Position>0 0 5</Position><Gaze>0 0 -1</Gaze><Up>0 1 0</Up>'
       '<NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance><ImageResolution>8 8</ImageResolution>'
       '<ImageName>x.png</ImageName></Camera></Cameras>')
MAT = '<Materials><Material id="1"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance></Material></Materials>'
VERTS = '<VertexData>-1 -1 0  1 -1 0  0 1 0</VertexData>'
TRI = '<Mesh id="1"><Material>1</Material><Faces>1 2 3</Faces></Mesh>'


def scene(objects, materials=MAT, vertices=VERTS, textures=''):
    return f'<Scene>{CAM}{materials}{textures}{vertices}<Objects>{objects}</Objects></Scene>\n'


def image_texture(path):
    return (f'<Textures><Images><Image id="1">{path}</Image></Images><TextureMap id="1" type="image"><ImageId>1</ImageId>'
            '<DecalMode>replace_kd</DecalMode></TextureMap></Textures>')


def png_header(width, height):
    """A PNG signature and IHDR chunk (8-bit RGBA) with no image data."""
    ihdr = struct.pack('>IIBBBBB', width, height, 8, 6, 0, 0, 0)
    return b'\x89PNG\r\n\x1a\n' + struct.pack('>I', 13) + b'IHDR' + ihdr + struct.pack('>I', zlib.crc32(b'IHDR' + ihdr))


# file: (contents, problem, substring the error must contain after the file's path)
CASES = {
    'not_xml.xml': ('plain text, not XML at all\n', 'not XML', 'xml'),
    'truncated.xml': (scene(TRI)[:150], 'XML cut off mid-element', 'xml'),
    'no_scene_root.xml': ('<World></World>\n', 'root element is not Scene', 'scene'),
    'face_index_out_of_range.xml': (scene('<Mesh id="1"><Material>1</Material><Faces>1 2 9</Faces></Mesh>'),
                                    'a face refers to vertex 9 of 3', 'out of range'),
    'unknown_material.xml': (scene('<Mesh id="1"><Material>7</Material><Faces>1 2 3</Faces></Mesh>'),
                             'mesh material id 7 does not exist', 'material'),
    'negative_radius.xml': (scene('<Sphere id="1"><Material>1</Material><Center>1</Center><Radius>-2</Radius></Sphere>'),
                            'sphere radius -2', 'radius'),
    'missing_ply.xml': (scene('<Mesh id="1"><Material>1</Material><Faces plyFile="nowhere.ply"/></Mesh>'),
                        'plyFile does not exist', 'not found'),
    'truncated_ply.xml': (scene('<Mesh id="1"><Material>1</Material><Faces plyFile="truncated.ply"/></Mesh>'),
                          'PLY shorter than its header says', 'truncated.ply'),
    'zero_area_light_mesh.xml': (scene('<LightMesh id="1"><Material>1</Material><Radiance>5 5 5</Radiance>'
                                       '<Faces>1 1 2</Faces></LightMesh>'),
                                 'LightMesh whose only triangle has zero area', 'lightmesh'),
    'cyclic_instances.xml': (scene(TRI + '<MeshInstance id="2" baseMeshId="3"><Material>1</Material></MeshInstance>'
                                   '<MeshInstance id="3" baseMeshId="2"><Material>1</Material></MeshInstance>'),
                             'MeshInstances 2 and 3 refer to each other', 'cycl'),
    'unknown_transformation.xml': (scene('<Mesh id="1"><Material>1</Material><Transformations>t4</Transformations>'
                                         '<Faces>1 2 3</Faces></Mesh>'),
                                   'transformation t4 does not exist', 't4'),
    'nan_vertex.xml': (scene(TRI, vertices='<VertexData>-1 -1 0  1 nan 0  0 1 0</VertexData>'),
                       'NaN in VertexData', 'vertexdata'),
    'absurd_resolution.xml': (scene(TRI).replace('<ImageResolution>8 8</ImageResolution>',
                                                 '<ImageResolution>100000 100000</ImageResolution>'),
                              'ImageResolution 100000x100000', '100000'),
    'unknown_brdf.xml': (scene(TRI, materials='<Materials><Material id="1" BRDF="9"><DiffuseReflectance>0.5 0.5 0.5'
                                              '</DiffuseReflectance></Material></Materials>'),
                         'material refers to BRDF 9', 'brdf'),
    'radius_not_a_number.xml': (scene('<Sphere id="1"><Material>1</Material><Center>1</Center><Radius>abc</Radius></Sphere>'),
                                'sphere radius is text, not a number', 'not a number'),
    'binary_negative_count.xml': (scene('<Mesh id="1"><Material>1</Material><Faces binaryFile="negative_count.bin"/></Mesh>'),
                                  'binaryFile whose count is -1', 'negative count'),
    'binary_huge_count.xml': (scene('<Mesh id="1"><Material>1</Material><Faces binaryFile="huge_count.bin"/></Mesh>'),
                              'binaryFile whose count 2147483647 needs 24 GB; it holds 12 bytes', 'needs'),
    'missing_image.xml': (scene(TRI.replace('<Faces>', '<Textures>1</Textures><Faces>'), textures=image_texture('nowhere.png')),
                          'texture image does not exist', 'not found'),
    'non_utf8_path.xml': (scene('<Mesh id="1"><Material>1</Material><Faces plyFile="m\xe9sh\xff.ply"/></Mesh>'),
                          'plyFile name with bytes that are not UTF-8 (Latin-1 and 0xff); no such file', 'not found'),
    'texture_100000x100000.xml': (scene(TRI.replace('<Faces>', '<Textures>1</Textures><Faces>'),
                                        textures=image_texture('header_100000x100000.png')),
                                  'texture PNG whose header claims 100000x100000 pixels', '100000x100000'),
    'image_is_a_device.xml': (scene(TRI.replace('<Faces>', '<Textures>1</Textures><Faces>'), textures=image_texture('/dev/zero')),
                              'texture image is /dev/zero (endless, not a file)', 'not a regular file'),
    'resolution_over_pixel_limit.xml': (scene(TRI).replace('<ImageResolution>8 8</ImageResolution>',
                                                           '<ImageResolution>60000 60000</ImageResolution>'),
                                        'ImageResolution 60000x60000: within the format, over the renderer\'s pixel limit',
                                        'image size'),
    'huge_sample_count.xml': (scene(TRI).replace('</ImageName>', '</ImageName><NumSamples>1000000000</NumSamples>'),
                              'NumSamples 1000000000', 'numsamples'),
    'negative_recursion_depth.xml': (scene(TRI).replace('<Scene>', '<Scene><MaxRecursionDepth>-1</MaxRecursionDepth>'),
                                     'MaxRecursionDepth -1', 'maxrecursiondepth'),
    'vertex_data_not_triples.xml': (scene(TRI, vertices='<VertexData>-1 -1 0  1 -1 0  0 1</VertexData>'),
                                    'VertexData holds 8 numbers, not whole xyz triples', 'vertexdata'),
    'faces_not_triples.xml': (scene('<Mesh id="1"><Material>1</Material><Faces>1 2 3 1</Faces></Mesh>'),
                              'Faces holds 4 indices, not whole triangles', 'faces'),
}

if __name__ == '__main__':
    for name, (text, _, _) in CASES.items():
        # Latin-1 keeps the non-UTF-8 bytes of non_utf8_path.xml as single raw bytes.
        with open(name, 'wb') as f:
            f.write(text.encode('latin-1'))
    # Data files the cases refer to (binaryFile: an int32 count, then the data).
    with open('negative_count.bin', 'wb') as f:
        f.write(struct.pack('<i', -1) + struct.pack('<3i', 0, 1, 2))
    with open('huge_count.bin', 'wb') as f:
        f.write(struct.pack('<i', 2147483647) + struct.pack('<3i', 0, 1, 2))
    with open('header_100000x100000.png', 'wb') as f:
        f.write(png_header(100000, 100000))
    # A PLY whose header promises more vertices than the file holds (used by truncated_ply.xml).
    with open('truncated.ply', 'wb') as f:
        f.write(b'ply\nformat binary_little_endian 1.0\nelement vertex 100\nproperty float x\nproperty float y\n'
                b'property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n' + b'\x00' * 20)
    with open('README.md', 'w') as f:
        f.write('# Malformed CENG795 XML scenes\n\nEach file must make `pt render` exit 1 with one line naming the '
                'file and the problem; the\nproblem text (after the file path) must contain the lowercase substring '
                'below. Generated by\n`make_corpus.py`.\n\n| file | problem | substring |\n|---|---|---|\n')
        for name, (_, problem, substring) in CASES.items():
            f.write(f'| `{name}` | {problem} | `{substring}` |\n')
