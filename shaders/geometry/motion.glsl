// Motion blur (the course's MotionBlur): an object translates by motions[i].xyz over the shutter
// interval, and every ray of one camera sample carries that sample's time in [0, 1). Rather than
// storing a time in every ray, the path's time is one per-invocation global, set before tracing.
#ifndef PT_GEOMETRY_MOTION_GLSL
#define PT_GEOMETRY_MOTION_GLSL
#include "common/buffers.glsl"
#include "shared/features.glsl"

float pathTime = 0.0;

// Where an object with motion `index` has moved at the current time.
vec3 motionOffset(uint index) { return Vec4Ref(scene.motions).v[index].xyz * pathTime; }

// A triangle where it is at the current time (unchanged unless it moves).
GpuTriangle placedTriangle(GpuTriangle tri) {
    if (HAS_MOTION && (tri.flags & TRIANGLE_FLAG_MOVING) != 0u) {
        vec3 offset = motionOffset(tri.flags >> TRIANGLE_MOTION_SHIFT);
        tri.p0 += offset;
        tri.p1 += offset;
        tri.p2 += offset;
    }
    return tri;
}

#endif
