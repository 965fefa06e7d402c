// What bidirectional connections need of a surface vertex: its BSDF between the direction
// towards the camera's end of the path and the direction towards the light's end, shaded the
// way the path tracer shades it (one-sided opaque surfaces black from behind, light below an
// opaque surface's own normal refused), and the densities of sampling either direction from
// the other, for MIS.
#ifndef PT_INTEGRATOR_BDPT_VERTEX_GLSL
#define PT_INTEGRATOR_BDPT_VERTEX_GLSL
#include "geometry/interaction.glsl"
#include "bsdf/surface_bsdf.glsl"
#include "common/ray_offset.glsl"
#include "integrator/shadow_ray.glsl"
#include "integrator/ray_counts.glsl"

struct VertexEval {
    vec3 fCos;              // f(wCamera, wLight) |wLight . ns|
    float pdfTowardsLight;  // of sampling wLight from wCamera (the camera path's direction)
    float pdfTowardsCamera; // of sampling wCamera from wLight (the light path's direction)
};

// The same in the frame the vertex already shades in (surfaceFrame: a camera path's vertex, its
// opaque surface turned to the camera's side and the material oriented). False where the path
// has no contribution through si.
bool evalInFrame(SurfaceInteraction si, GpuMaterial mat, Frame frame, vec3 wCamera, vec3 wLight, out VertexEval e) {
    if (!isTransmissiveSurface(mat) && dot(wLight, si.nSurface) <= 0.0) return false;
    vec3 a = toLocal(frame, wCamera), b = toLocal(frame, wLight);
    e.fCos = surfaceEvalPdf(mat, a, b, e.pdfTowardsLight);
    e.pdfTowardsCamera = surfacePdf(mat, b, a);
    return maxComponent(e.fCos) > 0.0;
}

// A light subpath's vertex as the camera's side would shade it: opaque surfaces are turned to
// the side wCamera is on (si is changed as the path tracer changes it, for the shadow ray's
// origin), and a one-sided one seen from behind has no contribution.
bool evalVertex(inout SurfaceInteraction si, GpuMaterial mat, vec3 wCamera, vec3 wLight, out VertexEval e) {
    Frame frame;
    if (isTransmissiveSurface(mat)) {
        frame = makeFrame(si.ns);
    } else {
        bool front = dot(wCamera, si.ng) > 0.0;
        if (!front && (mat.flags & MATERIAL_FLAG_DOUBLE_SIDED) == 0u) return false;
        frame = makeFrame(front ? si.ns : -si.ns);
        if (!front) turnToBackSide(si);
    }
    orientMaterialFrame(frame, mat);
    return evalInFrame(si, mat, frame, wCamera, wLight, e);
}

// Whether anything lies between two surface points (as evalVertex left them): each end offset
// off its own surface towards the other, from the smooth surface where the ray leaves on the
// side of the surface's own normal (Hanika), and the ray stops just short of the far end.
bool segmentOccluded(SurfaceInteraction a, SurfaceInteraction b, vec3 dirAB) {
    countShadowRay();
    Ray shadow;
    shadow.origin = spawnOrigin(dot(dirAB, a.nSurface) > 0.0 ? a.pSmooth : a.p, a.ng, dirAB, a.magnitude);
    vec3 target = spawnOrigin(dot(-dirAB, b.nSurface) > 0.0 ? b.pSmooth : b.p, b.ng, -dirAB, b.magnitude);
    shadow.direction = target - shadow.origin;
    return traceAny(shadow, SHADOW_RAY_FAR);
}

#endif
