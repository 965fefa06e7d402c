// Moving a ray origin off a surface without a scene-scale epsilon: Waechter and Binder,
// "A Fast and Robust Method for Avoiding Self-Intersection", Ray Tracing Gems ch. 6 (2019).
// The offset is a few ulps in integer space, so it scales with the magnitude of the
// coordinates; near the origin, where ulps are tiny, a small fixed offset is used instead.
// That fixed offset is for primitives of about unit size: a smaller primitive sitting near the
// origin has rounding errors in proportion to its own size, so its offset shrinks with it (a
// fixed 1/65536 made a sphere of radius 1e-3 0.24% too bright).
#ifndef PT_COMMON_RAY_OFFSET_GLSL
#define PT_COMMON_RAY_OFFSET_GLSL

const float OFFSET_ORIGIN = 1.0 / 32.0; // below this magnitude use the float offset
const float OFFSET_FLOAT_SCALE = 1.0 / 65536.0;
const float OFFSET_INT_SCALE = 256.0;

// p: point on the surface; n: geometric normal on the side the new ray leaves through;
// magnitude: the largest coordinate magnitude of the primitive p lies on (its vertices, or its
// centre plus radius), which bounds the rounding error of p.
vec3 offsetRayOrigin(vec3 p, vec3 n, float magnitude) {
    // 2^-16 of the primitive's size is still 128 ulps of its largest coordinate.
    float fixedOffset = OFFSET_FLOAT_SCALE * clamp(magnitude, 1e-30, 1.0);
    ivec3 of = ivec3(OFFSET_INT_SCALE * n);
    vec3 pInt = vec3(intBitsToFloat(floatBitsToInt(p.x) + (p.x < 0.0 ? -of.x : of.x)),
        intBitsToFloat(floatBitsToInt(p.y) + (p.y < 0.0 ? -of.y : of.y)),
        intBitsToFloat(floatBitsToInt(p.z) + (p.z < 0.0 ? -of.z : of.z)));
    return vec3(abs(p.x) < OFFSET_ORIGIN ? p.x + fixedOffset * n.x : pInt.x,
        abs(p.y) < OFFSET_ORIGIN ? p.y + fixedOffset * n.y : pInt.y,
        abs(p.z) < OFFSET_ORIGIN ? p.z + fixedOffset * n.z : pInt.z);
}

// Hanika's shadow-terminator offset ("Hacking the Shadow Terminator", Ray Tracing Gems II,
// ch. 4, 2021): a triangle with smooth vertex normals stands for a curved surface; near the
// terminator a shadow ray leaving the flat triangle below its plane re-enters the mesh and
// shadows points the smooth normal says are lit. Move the origin onto the smooth surface: the
// barycentric blend of p projected onto the tangent plane of each vertex, projected only where
// p lies below that plane (convex parts; concave ones keep p). p0..p2 the corners, n0..n2 their
// unit normals on the side of the geometric normal (zero where the file had none valid), b the
// barycentric weights of p0, p1, p2.
vec3 shadowTerminatorPoint(vec3 p, vec3 p0, vec3 p1, vec3 p2, vec3 n0, vec3 n1, vec3 n2, vec3 b) {
    vec3 lift = b.x * min(0.0, dot(p - p0, n0)) * n0 + b.y * min(0.0, dot(p - p1, n1)) * n1 +
                b.z * min(0.0, dot(p - p2, n2)) * n2;
    return p - lift;
}

// Offset to the side of the surface that direction d points to.
vec3 spawnOrigin(vec3 p, vec3 ng, vec3 d, float magnitude) {
    return offsetRayOrigin(p, dot(ng, d) >= 0.0 ? ng : -ng, magnitude);
}

#endif
