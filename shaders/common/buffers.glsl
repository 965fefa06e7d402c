// Typed views of the scene arrays through their device addresses (GL_EXT_buffer_reference):
// no 128 MiB per-binding limit (lavapipe's maxStorageBufferRange). The one descriptor is the
// uniform buffer of a tiny scene's triangles (below).
#ifndef PT_COMMON_BUFFERS_GLSL
#define PT_COMMON_BUFFERS_GLSL
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "shared/layout.h"

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

// A quantised node's (GpuBvh4QNode) words, read as seven 64-bit loads: per axis the origin and
// scale, the child words, and per axis the four children's low and high plane bytes.
struct QuantizedNodeWords {
    vec3 origin;
    vec3 scale;
    uvec4 child;
    uvec3 lo; // child i's q in bits 8i..8i+7
    uvec3 hi;
};

QuantizedNodeWords loadQuantizedNodeWords(uint64_t nodes, uint index) {
    Uint64Ref w = Uint64Ref(nodes + uint64_t(index) * uint64_t(BVH4_QNODE_WORDS64 * 8u));
    uvec2 originZExponents = wordsOf(w.v[1]);
    uvec2 loXY = wordsOf(w.v[4]), loZhiX = wordsOf(w.v[5]), hiYZ = wordsOf(w.v[6]);
    QuantizedNodeWords q;
    q.origin = vec3(floatsOf(w.v[0]), uintBitsToFloat(originZExponents.x));
    uint e = originZExponents.y;
    q.scale = uintBitsToFloat(((uvec3(e) >> uvec3(0u, 8u, 16u)) & 0xffu) << 23u);
    q.child = uvec4(wordsOf(w.v[2]), wordsOf(w.v[3]));
    q.lo = uvec3(loXY, loZhiX.x);
    q.hi = uvec3(loZhiX.y, hiYZ);
    return q;
}

// Node `index` of a four-wide BVH of quantised nodes (GpuBvh4QNode) at `nodes`, decoded.
GpuBvh4Node loadBvh4QNode(uint64_t nodes, uint index) {
    QuantizedNodeWords q = loadQuantizedNodeWords(nodes, index);
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

// Triangle `index` of the scene.
GpuTriangle loadTriangle(uint index) {
    Uint64Ref w = Uint64Ref(scene.triangles + uint64_t(index) * uint64_t(TRIANGLE_WORDS64 * 8u));
    uvec2 w1 = wordsOf(w.v[1]), w3 = wordsOf(w.v[3]), w5 = wordsOf(w.v[5]);
    GpuTriangle t;
    t.p0 = vec3(floatsOf(w.v[0]), uintBitsToFloat(w1.x));
    t.materialIndex = w1.y;
    t.p1 = vec3(floatsOf(w.v[2]), uintBitsToFloat(w3.x));
    t.lightIndex = w3.y;
    t.p2 = vec3(floatsOf(w.v[4]), uintBitsToFloat(w5.x));
    t.flags = w5.y;
    return t;
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
    GpuTriangle t;
    t.p0 = uintBitsToFloat(a.xyz);
    t.materialIndex = a.w;
    t.p1 = uintBitsToFloat(b.xyz);
    t.lightIndex = b.w;
    t.p2 = uintBitsToFloat(c.xyz);
    t.flags = c.w;
    return t;
}

void bindScene(uint64_t paramsAddress) {
    scene = SceneParamsRef(paramsAddress).p;
    sceneShading = ShadingRef(scene.shading);
    sceneMaterials = MaterialRef(scene.materials);
    sceneLights = LightRef(scene.lights);
    sceneLightCdf = FloatRef(scene.lightCdf);
}

#endif
