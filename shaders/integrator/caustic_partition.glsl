// Which paths the light tracer (integrator/light_tracer.glsl) takes over from the path tracer.
// Caustics, paths whose last bounces before an area light are delta ("... D S+ L": light through
// glass or off a mirror onto a diffuse surface), are found by the path tracer only when a BSDF
// sample happens to reach the light through the specular chain (light sampling cannot): rare,
// bright samples that dominate the error of scenes with glass or mirrors, on the caustic itself
// and on every surface it lights. Light tracing finds them from the light's end and connects
// each receiver it reaches to the camera. The light tracer takes exactly the paths
//   camera -> receiver -> (receivers and delta bounces) -> receiver -> delta bounce(s) -> area light
// with every vertex one it can follow back (the predicates below); the path tracer drops the
// emission it finds at the end of such a path and keeps every other. Each path is counted by
// exactly one of the two (a partition, so no MIS weights are needed).
#ifndef PT_INTEGRATOR_CAUSTIC_PARTITION_GLSL
#define PT_INTEGRATOR_CAUSTIC_PARTITION_GLSL
#include "shared/features.glsl"
#include "bsdf/surface_bsdf.glsl"
#include "common/buffers.glsl"
#include "lights/emitter_sampling.glsl"

// On at run time: the kernel was specialised for it, renders radiance, and has a pinhole
// camera (a thin lens would need the connection to sample the lens).
bool lightTracingActive() { return LIGHT_TRACING && DEBUG_VIEW == DEBUG_VIEW_NONE && scene.camera.lensRadius == 0.0; }

// Vertices of the specular chain: materials whose every lobe is a delta.
bool isSpecularChainMaterial(GpuMaterial m) {
    return (HAS_MIRROR && m.type == MATERIAL_MIRROR && !isRoughConductor(m)) ||
           (HAS_DIELECTRIC && m.type == MATERIAL_DIELECTRIC && !isRoughDielectric(m)) ||
           (HAS_CONDUCTOR && m.type == MATERIAL_CONDUCTOR && !isRoughConductor(m));
}

// Receivers, where a light path meets the camera: opaque surfaces with no delta lobe (rough
// conductors include rough mirrors, the glTF metals).
bool isCausticReceiver(GpuMaterial m) {
    bool shaded = !HAS_UNLIT || (m.flags & MATERIAL_FLAG_UNLIT) == 0u;
    return shaded && ((HAS_DIFFUSE && m.type == MATERIAL_DIFFUSE) || (HAS_GLOSSY && m.type == MATERIAL_GLOSSY) ||
                         isRoughConductor(m));
}

// A delta bounce between directions a and b (both pointing away from the surface) that the
// other end reproduces exactly: a reflection keeps both on one geometric side (so the opaque
// surface's side test and the dielectric's entering flag agree from either end), a refraction
// crosses. With shading normals a grazing bounce can break this; such paths stay with the path
// tracer.
bool isReversibleDeltaBounce(vec3 ng, vec3 ns, vec3 a, vec3 b) {
    bool reflection = (dot(ns, a) > 0.0) == (dot(ns, b) > 0.0);
    bool sameGeometricSide = (dot(ng, a) > 0.0) == (dot(ng, b) > 0.0);
    return reflection == sameGeometricSide;
}

// A BSDF-sampled bounce at an opaque receiver the light path can follow back: both directions
// on one geometric side (the side the camera path's frame and back-face test use).
bool isReversibleOpaqueBounce(vec3 ng, vec3 a, vec3 b) { return (dot(ng, a) > 0.0) == (dot(ng, b) > 0.0); }

#endif
