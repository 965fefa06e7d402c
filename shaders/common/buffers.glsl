// Typed views of the scene arrays through their device addresses (GL_EXT_buffer_reference):
// no 128 MiB per-binding limit (lavapipe's maxStorageBufferRange). The descriptors are the
// uniform buffer of a tiny scene's triangles and the texel buffers of the triangle tree and the
// triangles (below).
#ifndef PT_COMMON_BUFFERS_GLSL
#define PT_COMMON_BUFFERS_GLSL
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_samplerless_texture_functions : require
#include "shared/layout.h"
#include "shared/features.glsl"

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer SceneParamsRef { GpuSceneParams p; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer ShadingRef { GpuTriangleShading v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer Bvh4Ref { GpuBvh4Node v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer MaterialRef { GpuMaterial v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer LightRef { GpuLight v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer FloatRef { float v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer Vec4Ref { vec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer UVec4Ref { uvec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer TestRayRef { GpuTestRay v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer SphereRef { GpuSphere v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer InstanceRef { GpuInstance v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer TextureRef { GpuTexture v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer UintRef { uint v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer TangentRef { GpuTriangleTangents v[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) readonly buffer Uint64Ref { uint64_t v[]; };

// The scene of the current dispatch; set once at the top of main().
GpuSceneParams scene;
ShadingRef sceneShading;
MaterialRef sceneMaterials;
LightRef sceneLights;
FloatRef sceneLightCdf;

// The two 32-bit words of a 64-bit one (little-endian: the low word first, as in memory).
uvec2 wordsOf(uint64_t w) { return uvec2(uint(w), uint(w >> 32)); }
vec2 floatsOf(uint64_t w) { return uintBitsToFloat(wordsOf(w)); }

// The arrays read in the traversal's inner loops are read as 64-bit words: lavapipe gathers each
// loaded component separately for the 8 lanes of a SIMD vector, and a gather costs about the
// same per element whatever its width, so 64-bit words bring a record in with half the gathers
// (they were the kernel's hottest instructions; bench/RESULTS.md, "Loads of 64-bit words").

// The four steps q of one axis' child planes (the bytes of `bytes`), as floats.
vec4 planeSteps(uint bytes) { return vec4((uvec4(bytes) >> uvec4(0u, 8u, 16u, 24u)) & 0xffu); }

// Child planes of one axis: origin + q * scale (exact: the origin is a multiple of the scale,
// so this is the decoding src/accel/quantized_bvh.cpp does, bit for bit).
vec4 dequantizePlanes(uint bytes, float origin, float scale) { return origin + planeSteps(bytes) * scale; }

// Node `index` of a four-wide BVH of float nodes (GpuBvh4Node) at `nodes`.
GpuBvh4Node loadBvh4Node(uint64_t nodes, uint index) {
    Uint64Ref w = Uint64Ref(nodes + uint64_t(index) * uint64_t(BVH4_NODE_WORDS64 * 8u));
    GpuBvh4Node n;
    n.loX = vec4(floatsOf(w.v[0]), floatsOf(w.v[1]));
    n.hiX = vec4(floatsOf(w.v[2]), floatsOf(w.v[3]));
    n.loY = vec4(floatsOf(w.v[4]), floatsOf(w.v[5]));
    n.hiY = vec4(floatsOf(w.v[6]), floatsOf(w.v[7]));
    n.loZ = vec4(floatsOf(w.v[8]), floatsOf(w.v[9]));
    n.hiZ = vec4(floatsOf(w.v[10]), floatsOf(w.v[11]));
    n.child = uvec4(wordsOf(w.v[12]), wordsOf(w.v[13]));
    return n;
}

// The triangle tree's nodes and the triangles as 16-byte texels (set 0, TEXEL_BINDING_* in
// shared/layout.h), read instead of their addresses where TEXEL_LOADS: lavapipe fetches a texel
// with one 16-byte load per lane and transposes the vector, where a load through an address is a
// gather per 64-bit word (1.16x the paths per second on the 1 M-triangle mesh; the materials, read
// once a hit, gained nothing this way: bench/RESULTS.md, "Geometry read through texel buffers").
// The views are the same bytes as the buffers at scene.nodes and scene.triangles.
layout(set = 0, binding = TEXEL_BINDING_NODES) uniform utextureBuffer triangleTreeTexels;
layout(set = 0, binding = TEXEL_BINDING_TRIANGLES) uniform utextureBuffer triangleTexels;

// Texel `k` of record `index` of `texelsPerRecord` texels.
uvec4 nodeTexel(uint index, uint texelsPerRecord, uint k) {
    return texelFetch(triangleTreeTexels, int(index * texelsPerRecord + k));
}

// Float node `index` (GpuBvh4Node, BVH4_NODE_TEXELS texels) of the tree in `texels`.
GpuBvh4Node floatNodeOfTexels(utextureBuffer texels, uint index) {
    int first = int(index * BVH4_NODE_TEXELS);
    GpuBvh4Node n;
    n.loX = uintBitsToFloat(texelFetch(texels, first));
    n.hiX = uintBitsToFloat(texelFetch(texels, first + 1));
    n.loY = uintBitsToFloat(texelFetch(texels, first + 2));
    n.hiY = uintBitsToFloat(texelFetch(texels, first + 3));
    n.loZ = uintBitsToFloat(texelFetch(texels, first + 4));
    n.hiZ = uintBitsToFloat(texelFetch(texels, first + 5));
    n.child = texelFetch(texels, first + 6);
    return n;
}

// Node `index` of the triangle tree in float nodes (GpuBvh4Node).
GpuBvh4Node loadTriangleTreeFloatNode(uint index) {
    if (!TEXEL_LOADS) return loadBvh4Node(scene.nodes, index);
    return floatNodeOfTexels(triangleTreeTexels, index);
}

// The sphere tree's nodes and the spheres, likewise (the same gain: 7 texels a float node or a
// sphere where an address load gathers 14 words).
layout(set = 0, binding = TEXEL_BINDING_SPHERE_NODES) uniform utextureBuffer sphereTreeTexels;
layout(set = 0, binding = TEXEL_BINDING_SPHERES) uniform utextureBuffer sphereTexels;

// Node `index` of the sphere tree (float nodes).
GpuBvh4Node loadSphereTreeNode(uint index) {
    if (!TEXEL_LOADS) return loadBvh4Node(scene.sphereNodes, index);
    return floatNodeOfTexels(sphereTreeTexels, index);
}

// Sphere `index`. The traversal uses its world-to-object rows (and its motion, in scenes that
// move): the compiler drops the fetches of the texels a caller leaves unused.
GpuSphere loadSphere(uint index) {
    if (!TEXEL_LOADS) return SphereRef(scene.spheres).v[index];
    int first = int(index * SPHERE_TEXELS);
    GpuSphere s;
    for (int k = 0; k < 3; ++k) {
        s.worldToObject[k] = uintBitsToFloat(texelFetch(sphereTexels, first + k));
        s.objectToWorld[k] = uintBitsToFloat(texelFetch(sphereTexels, first + 3 + k));
    }
    uvec4 words = texelFetch(sphereTexels, first + 6);
    s.materialIndex = words.x;
    s.lightIndex = words.y;
    s.motion = words.z;
    s.pad1 = words.w;
    return s;
}

// A quantised node's (GpuBvh4QNode) words: per axis the origin and scale, the child words, and
// per axis the four children's low and high plane bytes. Only the triangle tree is quantised.
struct QuantizedNodeWords {
    vec3 origin;
    vec3 scale;
    uvec4 child;
    uvec3 lo; // child i's q in bits 8i..8i+7
    uvec3 hi;
};

// Node `index` of the triangle tree in quantised nodes: four texels, or seven 64-bit loads.
QuantizedNodeWords loadTriangleTreeQuantizedWords(uint index) {
    uvec4 originExponents, child, loHiX, hiYZ;
    if (TEXEL_LOADS) {
        originExponents = nodeTexel(index, BVH4_QNODE_TEXELS, 0u);
        child = nodeTexel(index, BVH4_QNODE_TEXELS, 1u);
        loHiX = nodeTexel(index, BVH4_QNODE_TEXELS, 2u);
        hiYZ = nodeTexel(index, BVH4_QNODE_TEXELS, 3u);
    } else {
        Uint64Ref w = Uint64Ref(scene.nodes + uint64_t(index) * uint64_t(BVH4_QNODE_WORDS64 * 8u));
        originExponents = uvec4(wordsOf(w.v[0]), wordsOf(w.v[1]));
        child = uvec4(wordsOf(w.v[2]), wordsOf(w.v[3]));
        loHiX = uvec4(wordsOf(w.v[4]), wordsOf(w.v[5]));
        hiYZ = uvec4(wordsOf(w.v[6]), 0u, 0u); // the eighth word is padding
    }
    QuantizedNodeWords q;
    q.origin = uintBitsToFloat(originExponents.xyz);
    uint e = originExponents.w;
    q.scale = uintBitsToFloat(((uvec3(e) >> uvec3(0u, 8u, 16u)) & 0xffu) << 23u);
    q.child = child;
    q.lo = loHiX.xyz;
    q.hi = uvec3(loHiX.w, hiYZ.xy);
    return q;
}

// Node `index` of the triangle tree in quantised nodes, decoded.
GpuBvh4Node loadTriangleTreeQNode(uint index) {
    QuantizedNodeWords q = loadTriangleTreeQuantizedWords(index);
    GpuBvh4Node n;
    n.loX = dequantizePlanes(q.lo.x, q.origin.x, q.scale.x);
    n.loY = dequantizePlanes(q.lo.y, q.origin.y, q.scale.y);
    n.loZ = dequantizePlanes(q.lo.z, q.origin.z, q.scale.z);
    n.hiX = dequantizePlanes(q.hi.x, q.origin.x, q.scale.x);
    n.hiY = dequantizePlanes(q.hi.y, q.origin.y, q.scale.y);
    n.hiZ = dequantizePlanes(q.hi.z, q.origin.z, q.scale.z);
    n.child = q.child;
    return n;
}

// A GpuTriangle from its three 16-byte texels (each a vertex and one id).
GpuTriangle triangleOfTexels(uvec4 a, uvec4 b, uvec4 c) {
    GpuTriangle t;
    t.p0 = uintBitsToFloat(a.xyz);
    t.materialIndex = a.w;
    t.p1 = uintBitsToFloat(b.xyz);
    t.lightIndex = b.w;
    t.p2 = uintBitsToFloat(c.xyz);
    t.flags = c.w;
    return t;
}

// Triangle `index` of the scene: three texels, or six 64-bit loads.
GpuTriangle loadTriangle(uint index) {
    uvec4 a, b, c;
    if (TEXEL_LOADS) {
        int first = int(index * TRIANGLE_TEXELS);
        a = texelFetch(triangleTexels, first);
        b = texelFetch(triangleTexels, first + 1);
        c = texelFetch(triangleTexels, first + 2);
    } else {
        Uint64Ref w = Uint64Ref(scene.triangles + uint64_t(index) * uint64_t(TRIANGLE_WORDS64 * 8u));
        a = uvec4(wordsOf(w.v[0]), wordsOf(w.v[1]));
        b = uvec4(wordsOf(w.v[2]), wordsOf(w.v[3]));
        c = uvec4(wordsOf(w.v[4]), wordsOf(w.v[5]));
    }
    return triangleOfTexels(a, b, c);
}

// A tiny scene's triangles again, as a uniform buffer (set 0, binding 0; every pipeline's layout
// has it, src/gpu/compute_pipeline.cpp), for the traversal that tests them all
// (UNIFORM_TRIANGLE_COUNT, geometry/traverse.glsl). Read at an index the compiler knows, a
// uniform buffer's word is loaded once for all lanes of lavapipe's SIMD vector and broadcast;
// storage buffers and device addresses are gathered lane by lane inside any branch or loop.
layout(set = 0, binding = 0, std140) uniform UniformTriangleBlock {
    uvec4 words[UNIFORM_TRIANGLES_MAX * UNIFORM_TRIANGLE_VEC4S];
}
uniformTriangles;

GpuTriangle loadUniformTriangle(uint index) {
    uvec4 a = uniformTriangles.words[index * UNIFORM_TRIANGLE_VEC4S];
    uvec4 b = uniformTriangles.words[index * UNIFORM_TRIANGLE_VEC4S + 1u];
    uvec4 c = uniformTriangles.words[index * UNIFORM_TRIANGLE_VEC4S + 2u];
    return triangleOfTexels(a, b, c);
}

void bindScene(uint64_t paramsAddress) {
    scene = SceneParamsRef(paramsAddress).p;
    sceneShading = ShadingRef(scene.shading);
    sceneMaterials = MaterialRef(scene.materials);
    sceneLights = LightRef(scene.lights);
    sceneLightCdf = FloatRef(scene.lightCdf);
}

#endif
