// Instances of shared meshes (GpuInstance): rays taken into a placement's object space, where
// its mesh's tree and triangles live, and hits brought back to world space.
#ifndef PT_GEOMETRY_INSTANCE_GLSL
#define PT_GEOMETRY_INSTANCE_GLSL
#include "common/buffers.glsl"
#include "common/math.glsl"
#include "common/ray.glsl"

GpuInstance loadInstance(uint index) { return InstanceRef(scene.instances).v[index]; }

vec3 instanceTranslation(GpuInstance instance) {
    return vec3(instance.objectToWorld[0].w, instance.objectToWorld[1].w, instance.objectToWorld[2].w);
}

// The ray in the instance's object space. The origin is taken relative to the placement's own
// origin first (as spheres do): near a placement far from the world's origin that difference is
// exact, where mapping the raw point would cancel its digits away. t stays the same: the
// direction is mapped, not renormalised.
Ray toInstanceSpace(GpuInstance instance, Ray ray) {
    Ray r;
    r.origin = transformVector(instance.worldToObject, ray.origin - instanceTranslation(instance));
    r.direction = transformVector(instance.worldToObject, ray.direction);
    return r;
}

// A bound on the world coordinates a point of the instance was computed from (the terms of
// objectToWorld * p), given its object-space magnitude: it scales the ray offset as a
// world-space primitive's vertex magnitude does.
float instanceMagnitude(GpuInstance instance, float objectMagnitude) {
    vec3 rowSums = vec3(dot(abs(instance.objectToWorld[0].xyz), vec3(1.0)),
        dot(abs(instance.objectToWorld[1].xyz), vec3(1.0)), dot(abs(instance.objectToWorld[2].xyz), vec3(1.0)));
    return maxComponent(rowSums * objectMagnitude + abs(instanceTranslation(instance)));
}

#endif
