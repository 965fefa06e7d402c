// Unidirectional path tracing: next event estimation, BSDF sampling, multiple importance
// sampling with the power heuristic, and Russian roulette; each switchable by specialization.
// Depth counts ray segments including the camera ray (Mitsuba 3's max_depth): emitters seen
// directly need depth 1, direct lighting depth 2.
#ifndef PT_INTEGRATOR_PATH_GLSL
#define PT_INTEGRATOR_PATH_GLSL
#include "common/math.glsl"
#include "common/rng.glsl"
#include "common/ray_offset.glsl"
#include "geometry/interaction.glsl"
#include "lights/light_sampling.glsl"
#include "bsdf/surface_bsdf.glsl"
#include "bsdf/mirror.glsl"
#include "bsdf/conductor.glsl"
#include "bsdf/dielectric.glsl"
#include "shared/features.glsl"
#include "material/material_textures.glsl"
#include "integrator/background.glsl"
#include "integrator/shadow_ray.glsl"
#include "integrator/ray_counts.glsl"
#include "integrator/classic.glsl"
#include "integrator/caustic_partition.glsl"
#include "common/spectrum.glsl"

// Dielectrics (smooth or rough, and PBR transmission with a volume) absorb inside, behind
// their geometric front face.
bool hasInteriorAbsorption(GpuMaterial mat) {
    return (mat.type == MATERIAL_DIELECTRIC || mat.type == MATERIAL_PBR) && (mat.flags & MATERIAL_FLAG_ABSORBING) != 0u;
}

// Direct light at a non-delta vertex (isSurfaceBsdf) by sampling the light table. Transmissive
// surfaces reach lights on either side: the shadow ray leaves on the side of wi.
vec3 estimateDirect(SurfaceInteraction si, Frame frame, vec3 woLocal, GpuMaterial mat, Rng rng, uint depth) {
    float uSelect = rng1(rng, bounceDimension(depth, DIM_LIGHT_SELECT));
    vec2 uPoint = rng2(rng, bounceDimension(depth, DIM_LIGHT_POINT));
    LightSample ls = sampleLight(si.p, si.ng, uSelect, uPoint);
    if (ls.pdf <= 0.0 || maxComponent(ls.radiance) <= 0.0) return vec3(0.0);
    // An opaque surface is lit from its own side only, whatever a normal map says: light
    // below it would come through (si.nSurface faces wo here; smooth vertex normals count as
    // the surface, whose terminator Hanika's offset then handles).
    if (!isTransmissiveSurface(mat) && dot(ls.wi, si.nSurface) <= 0.0) return vec3(0.0);
    vec3 wiLocal = toLocal(frame, ls.wi);
    float pdfBsdf;
    vec3 fCos = surfaceEvalPdf(mat, woLocal, wiLocal, pdfBsdf);
    if (maxComponent(fCos) <= 0.0) return vec3(0.0);
    if (lightOccluded(si, ls)) return vec3(0.0);
    // A shadow ray into an absorbing interior (a light inside the glass) is attenuated like
    // the path segments that reach it.
    if (HAS_ABSORPTION && ls.distance != FLOAT_MAX && dot(ls.wi, si.ng) < 0.0 && isTransmissiveSurface(mat) &&
        hasInteriorAbsorption(mat))
        fCos *= exp(-mat.sigmaA * ls.distance);
    float weight = (USE_MIS && !ls.isDelta) ? powerHeuristic(ls.pdf, pdfBsdf) : 1.0;
    return fCos * ls.radiance * (weight / ls.pdf);
}

// One camera path in flight: what a path vertex needs from the ones before it. The path is
// advanced one segment at a time (pathStep) so that the kernel can start a new sample in an
// invocation whose path ended while its neighbours' go on (integrator/pixel_samples.glsl).
struct PathState {
    Ray ray;           // the segment to trace next
    Rng rng;           // the sample's random numbers
    vec3 L;            // radiance gathered so far
    vec3 beta;         // throughput
    float etaScale;    // radiance scaling by refractions, undone for Russian roulette
    float prevPdfBsdf; // pdf of the BSDF sample that made this segment, for MIS
    vec3 prevNormal;   // geometric normal where it left, for the light tree's pmf (lights/light_tree.glsl)
    uint depth;        // segments so far, this one included
    uint deltaRun;     // delta bounces the light-traceable path ends with
    bool prevDelta;    // the segment came from a delta bounce (or is the camera ray)
    // With light tracing (integrator/caustic_partition.glsl): the path so far is one the light
    // tracer can follow back (camera -> receiver -> receivers and delta bounces). Emission found
    // after one or more delta bounces is the light tracer's.
    bool lightTraceable;
    float wavelength; // nm, from the first dispersive vertex on (common/spectrum.glsl); 0 before
};

PathState pathStart(Ray ray, Rng rng) {
    PathState st;
    st.ray = ray;
    st.rng = rng;
    st.L = vec3(0.0);
    st.beta = vec3(1.0);
    st.etaScale = 1.0;
    st.prevPdfBsdf = 0.0;
    st.prevNormal = vec3(0.0);
    st.depth = 1u;
    st.deltaRun = 0u;
    st.prevDelta = true; // the camera ray counts as specular: emitters it sees are added fully
    st.lightTraceable = false;
    st.wavelength = 0.0;
    return st;
}

// Traces st.ray, adds what its hit contributes to st.L and sets up the next segment. Returns
// false when the path has ended (st.L is then its radiance).
bool pathStep(inout PathState st) {
    Hit hit;
    countClosestRay();
    if (!traceClosest(st.ray, FLOAT_MAX, hit)) {
        // Escaped: the environment, weighted against its light sampling like any emitter.
        if (HAS_ENVIRONMENT && scene.envWidth > 0u) {
            vec3 Le = envRadiance(st.ray.direction);
            float pdfLight = environmentPdf(st.ray.direction);
            if (!USE_NEE || st.prevDelta || pdfLight == 0.0)
                st.L += st.beta * Le;
            else if (USE_MIS)
                st.L += st.beta * Le * powerHeuristic(st.prevPdfBsdf, pdfLight);
        } else {
            st.L += st.beta * backgroundRadiance(st.ray.direction, st.depth == 1u);
        }
        return false;
    }
    SurfaceInteraction si = makeInteraction(st.ray, hit);
    GpuMaterial mat = sceneMaterials.v[si.materialIndex];
    applyTextures(mat, si);
    bool doubleSided = (mat.flags & MATERIAL_FLAG_DOUBLE_SIDED) != 0u;

    // Beer-Lambert absorption along the segment just travelled inside a dielectric.
    if (HAS_ABSORPTION && !si.frontFace && hasInteriorAbsorption(mat)) st.beta *= exp(-mat.sigmaA * hit.t);

    // Emission found by the BSDF-sampled ray, weighted against light sampling. Emitters
    // outside the light table (pdfLight 0) can only be found this way and count fully.
    bool lightTraced = st.lightTraceable && st.deltaRun > 0u && isLightTracedEmitter(si.lightIndex);
    if (HAS_EMITTERS && maxComponent(mat.emission) > 0.0 && !lightTraced) {
        vec3 Le = emittedRadiance(mat, si.frontFace);
        float pdfLight = si.lightIndex != NO_LIGHT ? lightPdf(si.lightIndex, st.ray.origin, st.prevNormal, si.p, si.ng,
                                                         hit.t, st.ray.direction)
                                                   : 0.0;
        if (!USE_NEE || st.prevDelta || pdfLight == 0.0) {
            st.L += st.beta * Le;
        } else if (USE_MIS) {
            st.L += st.beta * Le * powerHeuristic(st.prevPdfBsdf, pdfLight);
        }
    }
    // The course's replace_all: the texture shown as is, unshaded (an emitter that no light
    // sampling knows of, so found by BSDF rays only and counted fully).
    if (HAS_UNLIT && (mat.flags & MATERIAL_FLAG_UNLIT) != 0u) {
        if (si.frontFace || doubleSided) st.L += st.beta * mat.baseColor;
        return false;
    }
    if (st.depth >= scene.maxDepth) return false;
    bool receiver = false;
    if (LIGHT_TRACING) {
        receiver = isCausticReceiver(mat);
        if (st.depth == 1u)
            st.lightTraceable = lightTracingActive() && receiver;
        else if (!receiver && !isSpecularChainMaterial(mat))
            st.lightTraceable = false;
    }

    // Dispersive glass: the path takes a wavelength at its first such vertex (weighted by its
    // RGB, common/spectrum.glsl) and keeps it; the material's index is the one at it. Emission
    // found at this vertex came before the wavelength and is not weighted.
    if (HAS_DISPERSION && mat.dispersion > 0.0) {
        if (st.wavelength == 0.0) {
            st.wavelength = mix(WAVELENGTH_MIN, WAVELENGTH_MAX, rng1(st.rng, DIM_WAVELENGTH));
            st.beta *= wavelengthWeight(st.wavelength);
        }
        mat.ior = dispersedIor(mat.ior, mat.dispersion, st.wavelength);
    }

    uint depth = st.depth;
    vec3 wo = -st.ray.direction;
    BsdfSample bs = invalidBsdfSample();
    bool neeSkipped = false;
    if (HAS_DIELECTRIC && mat.type == MATERIAL_DIELECTRIC && !isRoughDielectric(mat)) {
        Frame frame = makeFrame(dot(si.ns, wo) < 0.0 ? -si.ns : si.ns);
        float uLobe = rng1(st.rng, bounceDimension(depth, DIM_BSDF_LOBE));
        bs = dielectricSample(mat.baseColor, mat.ior, si.frontFace, frame, toLocal(frame, wo), uLobe);
    } else {
        // Rough dielectrics and PBR transmission (transmissive): both sides shade, light crosses
        // the surface (NEE too), and the frame keeps the front-side normal, wo.z < 0 inside.
        // Opaque surfaces: one-sided ones are black from behind, double-sided ones flip. Both
        // kinds share the calls below, so the driver inlines each BSDF's code once, not twice.
        bool transmissive = isTransmissiveSurface(mat);
        Frame frame;
        if (!surfaceFrame(si, mat, frame)) return false;
        vec3 woLocal = toLocal(frame, wo);
        if (isSmoothReflector(mat)) {
            bs = smoothReflectorSample(mat, frame, woLocal);
        } else if (isSurfaceBsdf(mat)) {
            // Inside a rough dielectric a shadow ray to a light outside always meets the
            // object's own boundary (shadow rays do not refract): light sampling is skipped
            // there, and emission the BSDF sample finds counts fully (prevDelta), which keeps
            // lights inside glass correct.
            neeSkipped = isRoughDielectric(mat) && woLocal.z < 0.0;
            if (USE_NEE && scene.numLights > 0u && !neeSkipped)
                st.L += st.beta * estimateDirect(si, frame, woLocal, mat, st.rng, depth);
            bs = surfaceSample(mat, frame, woLocal, rng1(st.rng, bounceDimension(depth, DIM_BSDF_LOBE)),
                rng2(st.rng, bounceDimension(depth, DIM_BSDF_DIRECTION)));
        }
        // A normal map tilts the sampling hemisphere; a reflection it sends below an opaque
        // surface's own normal would pass through it. End it there, as direct light from that
        // side is refused (shadow_ray.glsl), so both strategies agree.
        if (HAS_NORMAL_MAPS && !transmissive && dot(bs.wi, si.nSurface) <= 0.0) return false;
    }
    if (!bs.valid || maxComponent(bs.weight) <= 0.0) return false;
    if (st.lightTraceable) {
        // (An opaque back face seen from a double-sided receiver has ng flipped already;
        // both tests compare sides, so the flip does not change them.)
        bool reversible =
            receiver ? isReversibleOpaqueBounce(si.ng, wo, bs.wi) : isReversibleDeltaBounce(si.ng, si.ns, wo, bs.wi);
        if (!reversible) st.lightTraceable = false;
        st.deltaRun = receiver ? 0u : st.deltaRun + 1u;
    }
    st.beta *= bs.weight;
    st.etaScale *= bs.etaScale;
    st.prevDelta = bs.isDelta || neeSkipped;
    st.prevPdfBsdf = bs.pdf;
    st.prevNormal = si.ng;

    // Russian roulette on throughput with the radiance scaling of refractions undone, so a
    // path inside glass is not killed just for having entered it (pbrt-v4's etaScale).
    // Throughput at or above scene.rrThreshold always continues.
    if (USE_RR && depth >= scene.rrStartDepth) {
        float m = maxComponent(st.beta * st.etaScale) / scene.rrThreshold;
        if (m < 1.0) {
            float q = max(0.0, 1.0 - m);
            if (rng1(st.rng, bounceDimension(depth, DIM_ROULETTE)) < q) return false;
            st.beta /= 1.0 - q;
        }
    }
    st.ray.origin = spawnOrigin(si.p, si.ng, bs.wi, si.magnitude);
    st.ray.direction = bs.wi;
    st.depth = depth + 1u;
    return true;
}

// The radiance of one camera path, traced to its end.
vec3 tracePath(Ray ray, Rng rng) {
    if (CLASSIC) return traceClassic(ray, rng);
    PathState st = pathStart(ray, rng);
    while (pathStep(st)) {}
    return st.L;
}

#endif
