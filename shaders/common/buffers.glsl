// Typed views of the scene arrays through their device addresses (GL_EXT_buffer_reference):
// no descriptor sets, and no 128 MiB per-binding limit (lavapipe's maxStorageBufferRange).
#ifndef PT_COMMON_BUFFERS_GLSL
#define PT_COMMON_BUFFERS_GLSL
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "shared/layout.h"

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer SceneParamsRef { GpuSceneParams p; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer TriangleRef { GpuTriangle v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer ShadingRef { GpuTriangleShading v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer Bvh4Ref { GpuBvh4Node v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer MaterialRef { GpuMaterial v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer LightRef { GpuLight v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer FloatRef { float v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer Vec4Ref { vec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) buffer UVec4Ref { uvec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer TestRayRef { GpuTestRay v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer SphereRef { GpuSphere v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer TextureRef { GpuTexture v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer UintRef { uint v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer TangentRef { GpuTriangleTangents v[]; };

// The scene of the current dispatch; set once at the top of main().
GpuSceneParams scene;
TriangleRef sceneTriangles;
ShadingRef sceneShading;
Bvh4Ref sceneNodes;
MaterialRef sceneMaterials;
LightRef sceneLights;
FloatRef sceneLightCdf;

void bindScene(uint64_t paramsAddress) {
    scene = SceneParamsRef(paramsAddress).p;
    sceneTriangles = TriangleRef(scene.triangles);
    sceneShading = ShadingRef(scene.shading);
    sceneNodes = Bvh4Ref(scene.nodes);
    sceneMaterials = MaterialRef(scene.materials);
    sceneLights = LightRef(scene.lights);
    sceneLightCdf = FloatRef(scene.lightCdf);
}

#endif
