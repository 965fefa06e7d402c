// Bidirectional path tracing (Veach 1997, ch. 10). Each sample traces a light subpath from an
// emitter and a camera subpath from the pixel, and adds every way of forming a path from them:
//   s = 0: the camera path hits an emitter;
//   s = 1: light sampling at a camera vertex (next event estimation);
//   s >= 2: a camera vertex connected to light subpath vertex s - 1 by a shadow ray: one light
//           vertex per camera vertex, chosen uniformly among those that make a path no longer
//           than the maximum depth, its contribution times their count;
//   t = 1: a light subpath vertex connected to the camera, splatted to the pixel it lands in
//          (integrator/splat.glsl; one light subpath per pixel and sample, as the caustic light
//          tracer does).
// Each is weighted by the power heuristic over all strategies that could have made the path,
// computed from two running sums per subpath (dVCM and dVC, Georgiev 2012, "Implementing vertex
// connection and merging", without the merging terms), so no subpath is walked twice. Strategies
// that cannot make a path (hitting a light no ray can hit, sampling through a delta bounce, a
// light that starts no light subpath) have density 0 there and drop out of the sums.
//
// One connection per camera vertex instead of all of them (as the light vertex cache of
// Davidovic et al. 2014 does) halves the shadow rays of a deep path, and where light arrives
// through a gap most connections are occluded anyway. MIS then weighs each connection strategy
// as a sampler of its density times the share of connections a sample takes (connectionShare,
// the same whichever strategy evaluates the weights, so they still sum to one); the sums carry
// the terms of connections and of the strategies a sample takes whole (s = 0, s = 1, t = 1)
// apart for this.
//
// Light subpaths carry importance, not radiance (Veach 1997, ch. 5): refraction does not scale
// them by 1/eta^2, and shading normals get the adjoint's correction |wL.ns| |wC.ng| /
// (|wL.ng| |wC.ns|) at every vertex. Area densities are taken with geometric cosines.
//
// Left to the path tracer (src/flatten/feature_set.cpp): dispersive glass (a wavelength per
// path would have to agree between the subpaths).
#ifndef PT_INTEGRATOR_BDPT_GLSL
#define PT_INTEGRATOR_BDPT_GLSL
#include "shared/features.glsl"
#include "common/math.glsl"
#include "common/rng.glsl"
#include "common/ray_offset.glsl"
#include "geometry/interaction.glsl"
#include "lights/light_emission.glsl"
#include "lights/light_sampling.glsl"
#include "bsdf/surface_bsdf.glsl"
#include "bsdf/mirror.glsl"
#include "bsdf/conductor.glsl"
#include "bsdf/dielectric.glsl"
#include "material/material_textures.glsl"
#include "integrator/background.glsl"
#include "integrator/camera.glsl"
#include "integrator/caustic_partition.glsl"
#include "integrator/path.glsl"
#include "integrator/splat.glsl"
#include "integrator/bdpt_vertex.glsl"
#include "integrator/ray_counts.glsl"

// Which light vertex each camera vertex connects to: a block of dimensions of its own (as the
// light subpath's, lights/emitter_sampling.glsl), so that the camera path's numbers stay the path
// tracer's.
const uint DIM_CONNECTION = 0x20000000u;
// Whether the merge grid keeps light vertex i (integrator/vcm.glsl, mergeKeep), likewise.
const uint DIM_MERGE_KEEP = 0x30000000u;

// The power heuristic's square; without MIS, 1 for every strategy that can make the path, so
// the weights become 1 / (number of such strategies).
float misPower(float x) { return USE_MIS ? x * x : (x > 0.0 ? 1.0 : 0.0); }

// The MIS sums of a subpath (file comment), split by the kind of strategy each term stands for:
// c for connections of a camera and a light vertex (s >= 2, t >= 2), e for the strategies every
// sample takes whole: an emitter hit (s = 0), light sampling (s = 1) and light tracing (t = 1);
// m for merges at a vertex (integrator/vcm.glsl), 0 where the kernel does not merge.
// The endpoint terms only enter at a subpath's start; every later bounce adds a connection's
// and a merge's.
struct MisSums {
    float cVCM;
    float cVC;
    float eVCM;
    float eVC;
    float mVC;
};

// The kinds of strategy, each sampled at its own rate (otherStrategies).
const uint STRATEGY_ENDPOINT = 0u;
const uint STRATEGY_CONNECTION = 1u;
const uint STRATEGY_MERGE = 2u;

// A merge's density over a connection's at the same vertex, beside the density of the
// direction that makes the merged vertex: pi r^2 times the light subpaths a round holds
// (Georgiev et al. 2012's eta_VCM). 0 in a kernel or dispatch that does not merge.
float mergeEta = 0.0;

// The share of the connections at a camera vertex one sample takes: one over the light vertices
// it could connect to, on average over a path's camera vertices. Without roulette a light subpath
// reaches the depth, and a camera vertex at depth d has maxDepth - d - 1 of them, half of
// maxDepth - 2 on average; with roulette most light subpaths end soon after it starts, after the
// rrStartDepth - 1 vertices it leaves. A constant for the whole render, so that every strategy
// computes the same weights (the Ajar scenes measured it: bench/RESULTS.md).
float connectionShare() {
    float expected = 0.5 * float(scene.maxDepth - 2u);
    if (USE_RR) expected = min(expected, float(max(scene.rrStartDepth, 2u) - 1u));
    return 1.0 / clamp(expected, 1.0, float(BDPT_MAX_LIGHT_VERTICES));
}

// The power heuristic's sum of the other strategies over the one evaluated: `terms` holds the
// terms of each kind (connections, endpoints, merges) at their own densities, which the rate
// each kind is taken at scales (a connection's share, a merge's eta), over the evaluated one's.
float otherStrategies(vec3 terms, uint evaluated) {
    float share = misPower(connectionShare()), merge = misPower(mergeEta);
    float sum = terms.x * share + terms.y + terms.z * merge;
    return sum / (evaluated == STRATEGY_CONNECTION ? share : evaluated == STRATEGY_MERGE ? merge : 1.0);
}

// A subpath's sums as the evaluated strategy sees them: the terms of the strategy that takes this
// vertex from the other side (atVertex, the density of that side's making it), of merging at
// this vertex (mergeHere, mergeTerm) and those further back (times furtherBack, the density of
// the reverse sampling at this vertex).
vec3 sideTerms(MisSums m, float atVertex, float furtherBack, float mergeHere) {
    float a = misPower(atVertex), b = misPower(furtherBack);
    return a * vec3(m.cVCM + m.cVC * b, m.eVCM + m.eVC * b, m.mVC * b + mergeHere);
}

// The sums across a surface hit at distance `dist` with geometric cosine cosIn.
void arriveMisSums(inout MisSums m, float dist, float cosIn) {
    float toArea = misPower(dist * dist) / misPower(cosIn), cosOnly = 1.0 / misPower(cosIn);
    m.cVCM *= toArea;
    m.eVCM *= toArea;
    m.cVC *= cosOnly;
    m.eVC *= cosOnly;
    m.mVC *= cosOnly;
}

// The weight of strategy s for a path of `segments` segments: `mis`, or in a kernel that keeps
// one strategy alone (BDPT_STRATEGY, tests), 1 for it and 0 for every other.
float strategyWeight(uint s, uint segments, float mis) {
    if (BDPT_STRATEGY == BDPT_ALL_STRATEGIES) return mis;
    return BDPT_STRATEGY == BDPT_ONE_STRATEGY(segments, s) ? 1.0 : 0.0;
}

// The MIS sums of a subpath carried across the bounce `bs` (either subpath's: the recursion is
// the same): cosOut, the new direction's geometric cosine here; pdfReverse, the density of the
// other subpath's sampling the direction this one arrived from; mergeHere, the vertex's merge
// term (mergeTerm). A delta bounce's forward and
// reverse lobe probabilities are equal and cancel, and no strategy connects at it.
void advanceMisSums(BsdfSample bs, float cosOut, float pdfReverse, float mergeHere, inout MisSums m) {
    if (bs.isDelta) {
        m.cVCM = 0.0;
        m.eVCM = 0.0;
        m.cVC *= misPower(cosOut);
        m.eVC *= misPower(cosOut);
        m.mVC *= misPower(cosOut);
    } else {
        // The vertex left is one a merge can take (non-delta): its term joins the merges'.
        float scale = misPower(cosOut / bs.pdf), reverse = misPower(pdfReverse);
        m.cVC = scale * (m.cVC * reverse + m.cVCM);
        m.eVC = scale * (m.eVC * reverse + m.eVCM);
        m.mVC = scale * (m.mVC * reverse + mergeHere);
        m.cVCM = misPower(1.0 / bs.pdf);
        m.eVCM = 0.0;
    }
}

// A light subpath vertex a camera vertex can connect to. Its interaction is rebuilt from the
// segment that found it (cheaper to keep than the shaded material).
struct LightVertex {
    Ray ray;
    Hit hit;
    vec3 p;        // the hit point, to reject connections before rebuilding the rest
    vec3 beta;     // emitted radiance over the density of the light subpath up to here
    MisSums mis;   // at this vertex
    uint segments; // light subpath segments up to this vertex
};

LightVertex lightVertices[BDPT_MAX_LIGHT_VERTICES];
uint lightVertexCount = 0u;
#include "integrator/vcm.glsl"

// This invocation's pixel, row-major (vertex merging's stored light subpaths are per pixel).
uint bdptPixelIndex = 0u;

bool mergingPhase(uint phase) { return MERGING && vcm.phase == phase; }

// The merge term a non-delta vertex at p adds to the MIS sums: the probability that the grid
// keeps a light vertex there (mergeKeep), through the heuristic; 0 in a dispatch that does not merge.
// The light reaches the vertex from direction toLight (towards the path's next vertex on the
// light's side), which picks the side of the surface whose pilot cell counts.
float mergeTerm(vec3 p, vec3 ng, vec3 toLight) {
    if (!(mergingPhase(VCM_PHASE_LIGHT) || mergingPhase(VCM_PHASE_CAMERA))) return 0.0;
    return misPower(mergeKeep(p, dot(toLight, ng) >= 0.0 ? ng : -ng));
}

// Light vertex i of this sample's light subpath: kept in the invocation, or (vertex merging's
// camera phase) stored by the light phase.
LightVertex lightVertexAt(uint i) {
    if (mergingPhase(VCM_PHASE_CAMERA)) return loadVcmVertex(bdptPixelIndex * vcm.verticesPerPixel + i);
    return lightVertices[i];
}

struct ShadedVertex {
    SurfaceInteraction si;
    GpuMaterial mat;
};

ShadedVertex shadeLightVertex(LightVertex v) {
    ShadedVertex sv;
    sv.si = makeInteraction(v.ray, v.hit);
    sv.mat = sceneMaterials.v[sv.si.materialIndex];
    applyTextures(sv.mat, sv.si);
    return sv;
}

// Beer-Lambert absorption along a connection leaving si in direction d into an absorbing
// transmissive surface's interior (as light sampling does, integrator/path.glsl).
bool entersAbsorbingInterior(SurfaceInteraction si, GpuMaterial mat, vec3 d) {
    return HAS_ABSORPTION && isTransmissiveSurface(mat) && hasInteriorAbsorption(mat) && dot(d, si.ng) < 0.0;
}

// ---- t = 1: a light subpath vertex seen by the camera ----

void connectLightVertexToCamera(
    SurfaceInteraction si, GpuMaterial mat, vec3 wLight, vec3 beta, MisSums mis, uint segments) {
    CameraView view;
    if (!viewFromPinhole(scene.camera, scene.imageSize, si.p, view)) return;
    VertexEval e;
    if (!evalVertex(si, mat, view.wCamera, wLight, e)) return;
    float cosLightIn = abs(dot(wLight, si.ng));
    if (cosLightIn < 1e-7) return;
    float cosCamera = abs(dot(view.wCamera, si.ng));
    float cameraPdfArea = view.importance * cosCamera; // over the pixel count
    vec3 lightSide = sideTerms(mis, cameraPdfArea, e.pdfTowardsLight, mergeTerm(si.p, si.ng, wLight));
    float weight =
        strategyWeight(segments + 1u, segments + 1u, 1.0 / (1.0 + otherStrategies(lightSide, STRATEGY_ENDPOINT)));
    if (weight == 0.0) return;
    vec3 contribution = beta * e.fCos * (weight * view.importance * cosCamera / cosLightIn);
    if (entersAbsorbingInterior(si, mat, view.wCamera)) contribution *= exp(-mat.sigmaA * view.distance);
    if (maxComponent(contribution) <= 0.0 || cameraOccluded(si, view)) return;
    splatAdd(view.pixel, contribution);
}

// ---- The light subpath ----

// Traces the light subpath of sample `rng`, splats its camera connections (when the camera can
// take them) and keeps its vertices for the camera path's connections.
void traceLightSubpath(Rng rng, bool cameraConnects) {
    lightVertexCount = 0u;
    if (scene.numLights == 0u || scene.maxDepth < 2u) return;
    uint lightIndex = selectLight(rng1(rng, lightPathDimension(DIM_LT_SELECT)));
    LightEmission em = sampleLightEmission(lightIndex, rng2(rng, lightPathDimension(DIM_LT_POINT)),
        rng2(rng, lightPathDimension(DIM_LT_EMIT)), rng1(rng, lightPathDimension(DIM_LT_SIDE)));
    if (!em.valid) return;
    Ray ray;
    ray.origin = em.magnitude > 0.0 ? offsetRayOrigin(em.p, em.normal, em.magnitude) : em.p;
    ray.direction = em.direction;
    vec3 beta = em.beta;
    vec3 throughput = vec3(1.0); // bounce weights alone, for Russian roulette
    // The first vertex's sums need the density of sampling the light from it, known at the hit.
    MisSums mis = MisSums(0.0, 0.0, 0.0, em.hittable ? misPower(em.cosLight / em.pdfEmit) : 0.0, 0.0);
    uint segments = 1u;
    while (true) {
        Hit hit;
        countClosestRay();
        if (!traceClosest(ray, FLOAT_MAX, hit)) break;
        SurfaceInteraction si = makeInteraction(ray, hit);
        GpuMaterial mat = sceneMaterials.v[si.materialIndex];
        applyTextures(mat, si);
        if (HAS_ABSORPTION && !si.frontFace && hasInteriorAbsorption(mat)) beta *= exp(-mat.sigmaA * hit.t);
        vec3 wLight = -ray.direction;
        float cosIn = max(abs(dot(wLight, si.ng)), 1e-12);
        // The first hit's term is light sampling's (s = 1); it and the emitter hit's (s = 0) are the
        // only endpoint terms of a light subpath.
        arriveMisSums(mis, hit.t, cosIn);
        if (segments == 1u && em.infinite) {
            // Both densities are of directions, so the first segment's length does not enter.
            mis.eVCM = misPower(directLightPdfInfinite(lightIndex, ray.direction) / (em.pdfEmit * cosIn));
        } else if (segments == 1u) {
            vec3 d = si.p - em.p;
            float dist2 = dot(d, d);
            mis.eVCM =
                misPower(directLightPdfArea(lightIndex, si.p, si.ng, em.p, em.normal) * dist2 / (em.pdfEmit * cosIn));
        }
        if (HAS_UNLIT && (mat.flags & MATERIAL_FLAG_UNLIT) != 0u) break;

        bool connectible = isSurfaceBsdf(mat);
        if (connectible) {
            // Kept for connections (a camera segment and one more) or, when merging, for merges
            // (the camera's segments end at it).
            bool merging = mergingPhase(VCM_PHASE_LIGHT) || mergingPhase(VCM_PHASE_PILOT);
            uint limit = merging ? min(vcm.verticesPerPixel, BDPT_MAX_LIGHT_VERTICES) : BDPT_MAX_LIGHT_VERTICES;
            if (segments + (merging ? 1u : 2u) <= scene.maxDepth && lightVertexCount < limit) {
                LightVertex v;
                v.ray = ray;
                v.hit = hit;
                v.p = si.p;
                v.beta = beta;
                v.mis = mis;
                v.segments = segments;
                if (merging)
                    storeVcmVertex(bdptPixelIndex, lightVertexCount, v, dot(wLight, si.ng) >= 0.0 ? si.ng : -si.ng,
                        rng1(rng, DIM_MERGE_KEEP + lightVertexCount));
                else
                    lightVertices[lightVertexCount] = v;
                lightVertexCount += 1u;
            }
            if (cameraConnects && segments + 1u <= scene.maxDepth)
                connectLightVertexToCamera(si, mat, wLight, beta, mis, segments);
        }
        // Another bounce needs one more segment before the camera's.
        if (segments + 2u > scene.maxDepth) break;

        uint bounce = segments - 1u;
        float uLobe = rng1(rng, lightBounceDimension(bounce, DIM_LT_LOBE));
        vec2 uDirection = rng2(rng, lightBounceDimension(bounce, DIM_LT_DIRECTION));
        BsdfSample bs = invalidBsdfSample();
        float pdfReverse = 0.0; // of the camera path sampling wLight from the new direction
        vec3 weight = vec3(0.0);
        if (HAS_DIELECTRIC && mat.type == MATERIAL_DIELECTRIC && !isRoughDielectric(mat)) {
            Frame frame = makeFrame(dot(si.ns, wLight) < 0.0 ? -si.ns : si.ns);
            bs = dielectricSample(mat.baseColor, mat.ior, si.frontFace, frame, toLocal(frame, wLight), uLobe);
        } else {
            bool transmissive = isTransmissiveSurface(mat);
            Frame frame;
            if (!surfaceFrame(si, mat, frame)) break;
            if (!transmissive && dot(wLight, si.nSurface) <= 0.0) break;
            vec3 wLightLocal = toLocal(frame, wLight);
            if (isSmoothReflector(mat))
                bs = smoothReflectorSample(mat, frame, wLightLocal);
            else if (connectible)
                bs = surfaceSample(mat, frame, wLightLocal, uLobe, uDirection);
            if (!bs.valid) break;
            // The camera path decides an opaque surface's side by its own direction: both on one
            // geometric side, so that it shades this bounce as the light path did.
            if (!transmissive && !isReversibleOpaqueBounce(si.ng, wLight, bs.wi)) break;
            if (!bs.isDelta) {
                vec3 wCameraLocal = toLocal(frame, bs.wi);
                float cosLightGeometric = max(abs(dot(wLight, si.ng)), 1e-7);
                // The adjoint: f(wC, wL) |wL.ns| |wC.ng| / |wL.ng|, over the density.
                weight = surfaceEval(mat, wCameraLocal, wLightLocal) *
                         (abs(dot(bs.wi, si.ng)) / (cosLightGeometric * bs.pdf));
                pdfReverse = surfacePdf(mat, wCameraLocal, wLightLocal);
            }
        }
        if (!bs.valid || !(bs.pdf > 0.0)) break;
        vec3 wCamera = bs.wi;
        if (bs.isDelta) {
            if (!isReversibleDeltaBounce(si.ng, si.ns, wLight, wCamera)) break;
            float denominator = abs(dot(wLight, si.ng)) * abs(dot(wCamera, si.ns));
            if (denominator < 1e-7) break;
            // Importance is not compressed by refraction: the radiance scaling is undone.
            weight = bs.weight * bs.etaScale * (abs(dot(wLight, si.ns)) * abs(dot(wCamera, si.ng)) / denominator);
        }
        if (!allFinite(weight) || maxComponent(weight) <= 0.0) break;
        advanceMisSums(
            bs, abs(dot(wCamera, si.ng)), pdfReverse, bs.isDelta ? 0.0 : mergeTerm(si.p, si.ng, wLight), mis);
        beta *= weight;
        throughput *= weight;
        if (USE_RR && segments + 1u >= scene.rrStartDepth) {
            float m = maxComponent(throughput) / scene.rrThreshold;
            if (m < 1.0) {
                if (rng1(rng, lightBounceDimension(bounce, DIM_LT_ROULETTE)) >= m) break;
                beta /= m;
                throughput /= m;
            }
        }
        ray.origin = spawnOrigin(si.p, si.ng, wCamera, si.magnitude);
        ray.direction = wCamera;
        segments += 1u;
    }
}

// ---- The camera subpath and its connections ----

// s = 1: light sampling at camera vertex si, weighted against every other strategy.
vec3 bdptLightSample(
    SurfaceInteraction si, Frame frame, vec3 woLocal, GpuMaterial mat, Rng rng, uint depth, MisSums mis) {
    // Chosen as the path tracer chooses (by the light tree where the scene has one); the light
    // subpaths start from lights chosen by power (emissionPdf).
    uint lightIndex;
    GpuLight chosen;
    if (!chooseLightEntry(si.p, si.ng, rng1(rng, bounceDimension(depth, DIM_LIGHT_SELECT)), lightIndex, chosen))
        return vec3(0.0);
    LightSample ls = sampleLightEntry(chosen, si.p, rng2(rng, bounceDimension(depth, DIM_LIGHT_POINT)));
    if (ls.pdf <= 0.0 || maxComponent(ls.radiance) <= 0.0) return vec3(0.0);
    if (!isTransmissiveSurface(mat) && dot(ls.wi, si.nSurface) <= 0.0) return vec3(0.0);
    vec3 wiLocal = toLocal(frame, ls.wi);
    float pdfForward;
    vec3 fCos = surfaceEvalPdf(mat, woLocal, wiLocal, pdfForward);
    if (maxComponent(fCos) <= 0.0) return vec3(0.0);
    float hitTerm = ls.isDelta ? 0.0 : misPower(pdfForward / ls.pdf); // s = 0: a BSDF ray hits it
    vec3 cameraSide = vec3(0.0);
    float pdfEmit = emissionPdf(lightIndex, ls.point, ls.normal, -ls.wi);
    if (pdfEmit > 0.0) {
        // s >= 2: the light subpath starts here and reaches si.
        bool positionDelta = isPositionDeltaLight(chosen);
        float cosAtLight = positionDelta || isInfiniteLight(chosen) ? 1.0 : abs(dot(ls.normal, ls.wi));
        float directPdfW = positionDelta ? ls.pdf * ls.distance * ls.distance : ls.pdf;
        float cosHere = abs(dot(ls.wi, si.ng));
        float pdfReverse = surfacePdf(mat, wiLocal, woLocal);
        cameraSide =
            sideTerms(mis, pdfEmit * cosHere / (directPdfW * cosAtLight), pdfReverse, mergeTerm(si.p, si.ng, ls.wi));
    }
    float others = otherStrategies(cameraSide + vec3(0.0, hitTerm, 0.0), STRATEGY_ENDPOINT);
    float weight = strategyWeight(1u, depth + 1u, 1.0 / (1.0 + others));
    if (weight == 0.0 || lightOccluded(si, ls)) return vec3(0.0);
    if (HAS_ABSORPTION && ls.distance != FLOAT_MAX && entersAbsorbingInterior(si, mat, ls.wi))
        fCos *= exp(-mat.sigmaA * ls.distance);
    return fCos * ls.radiance * (weight / ls.pdf);
}

// s >= 2: camera vertex si (shading in `frame`, reached from direction wo, MIS sums `mis`,
// `depth` segments) connected to light subpath vertex lv.
vec3 connectToLightVertex(
    SurfaceInteraction si, GpuMaterial mat, Frame frame, vec3 wo, uint depth, MisSums mis, LightVertex lv) {
    vec3 d = lv.p - si.p;
    float dist2 = dot(d, d);
    if (!(dist2 > 0.0)) return vec3(0.0);
    float dist = sqrt(dist2);
    vec3 dir = d / dist; // camera vertex -> light vertex
    VertexEval c, l;
    if (!evalInFrame(si, mat, frame, wo, dir, c)) return vec3(0.0);
    ShadedVertex light = shadeLightVertex(lv);
    vec3 wLight = -lv.ray.direction;
    if (!evalVertex(light.si, light.mat, -dir, wLight, l)) return vec3(0.0);
    float cosLightIn = abs(dot(wLight, light.si.ng));
    if (cosLightIn < 1e-7) return vec3(0.0);
    float cosCamera = abs(dot(dir, si.ng)), cosLight = abs(dot(dir, light.si.ng));
    // Densities of each side's path making the other side's vertex, per unit area.
    float cameraMakesLightVertex = c.pdfTowardsLight * cosLight / dist2;
    float lightMakesCameraVertex = l.pdfTowardsCamera * cosCamera / dist2;
    vec3 lightSide = sideTerms(lv.mis, cameraMakesLightVertex, l.pdfTowardsLight, mergeTerm(lv.p, light.si.ng, wLight));
    vec3 cameraSide = sideTerms(mis, lightMakesCameraVertex, c.pdfTowardsCamera, mergeTerm(si.p, si.ng, dir));
    uint s = lv.segments + 1u;
    float weight =
        strategyWeight(s, depth + s, 1.0 / (1.0 + otherStrategies(lightSide + cameraSide, STRATEGY_CONNECTION)));
    if (weight == 0.0) return vec3(0.0);
    // The light vertex's adjoint correction |wC.ng| / |wL.ng| with the geometry term's |wC.ns|
    // leaves cosLight / cosLightIn; the camera vertex's cosine is in c.fCos.
    vec3 contribution = lv.beta * l.fCos * c.fCos * (weight * cosLight / (cosLightIn * dist2));
    if (entersAbsorbingInterior(si, mat, dir))
        contribution *= exp(-mat.sigmaA * dist);
    else if (entersAbsorbingInterior(light.si, light.mat, -dir))
        contribution *= exp(-light.mat.sigmaA * dist);
    if (maxComponent(contribution) <= 0.0 || segmentOccluded(si, light.si, dir)) return vec3(0.0);
    return contribution;
}

// The radiance the camera path of `ray` gathers through every strategy but t = 1. The camera's
// own sums start with light tracing's share (0 where the camera takes no connections).
vec3 traceBdptCameraPath(Ray ray, Rng rng, bool cameraConnects) {
    vec3 L = vec3(0.0), beta = vec3(1.0);
    float etaScale = 1.0;
    uint depth = 1u;
    vec3 prevNormal = vec3(0.0); // where the ray left, for the light tree's pmf
    // The camera's first term is light tracing's (t = 1), its only endpoint term.
    MisSums mis = MisSums(
        0.0, 0.0, cameraConnects ? misPower(cameraDirectionWeight(scene.camera, ray.direction)) : 0.0, 0.0, 0.0);
    while (true) {
        Hit hit;
        countClosestRay();
        if (!traceClosest(ray, FLOAT_MAX, hit)) {
            // Escaped: the environment, against light sampling (s = 1) and the light subpaths that
            // start from it (s >= 2; at infinity the sums take no last segment's length).
            if (HAS_ENVIRONMENT && scene.envWidth > 0u) {
                float pdfDirection = environmentPdf(ray.direction);
                // The last camera vertex's term is light sampling's (s = 1), an endpoint's.
                float lightSampling = depth > 1u && USE_NEE ? misPower(pdfDirection) * (mis.cVCM + mis.eVCM) : 0.0;
                float fromDisc = misPower(pdfDirection * infiniteLightDiscPdf());
                float others =
                    otherStrategies(vec3(fromDisc * mis.cVC, lightSampling + fromDisc * mis.eVC, fromDisc * mis.mVC),
                        STRATEGY_ENDPOINT);
                L += beta * envRadiance(ray.direction) * strategyWeight(0u, depth, 1.0 / (1.0 + others));
            } else {
                L += beta * backgroundRadiance(ray.direction, depth == 1u) * strategyWeight(0u, depth, 1.0);
            }
            break;
        }
        SurfaceInteraction si = makeInteraction(ray, hit);
        GpuMaterial mat = sceneMaterials.v[si.materialIndex];
        applyTextures(mat, si);
        bool doubleSided = (mat.flags & MATERIAL_FLAG_DOUBLE_SIDED) != 0u;
        if (HAS_ABSORPTION && !si.frontFace && hasInteriorAbsorption(mat)) beta *= exp(-mat.sigmaA * hit.t);
        float cosIn = max(abs(dot(ray.direction, si.ng)), 1e-12);
        arriveMisSums(mis, hit.t, cosIn);

        // s = 0: an emitter found by the camera path.
        if (HAS_EMITTERS && maxComponent(mat.emission) > 0.0) {
            vec3 Le = emittedRadiance(mat, si.frontFace);
            float others = 0.0;
            if (depth > 1u && si.lightIndex != NO_LIGHT) {
                // The last camera vertex's term is light sampling's (s = 1), an endpoint's.
                float lightSampling = misPower(directLightPdfArea(si.lightIndex, ray.origin, prevNormal, si.p, si.ng)) *
                                      (mis.cVCM + mis.eVCM);
                float fromEmitter = misPower(emissionPdf(si.lightIndex, si.p, si.ng, -ray.direction));
                others = otherStrategies(
                    vec3(fromEmitter * mis.cVC, lightSampling + fromEmitter * mis.eVC, fromEmitter * mis.mVC),
                    STRATEGY_ENDPOINT);
            }
            L += beta * Le * strategyWeight(0u, depth, 1.0 / (1.0 + others));
        }
        if (HAS_UNLIT && (mat.flags & MATERIAL_FLAG_UNLIT) != 0u) {
            if (si.frontFace || doubleSided) L += beta * mat.baseColor * strategyWeight(0u, depth, 1.0);
            break;
        }
        if (depth >= scene.maxDepth) break;

        vec3 wo = -ray.direction;
        BsdfSample bs = invalidBsdfSample();
        float pdfReverse = 0.0; // of the light path sampling wo from the new direction
        bool transmissive = isTransmissiveSurface(mat);
        if (HAS_DIELECTRIC && mat.type == MATERIAL_DIELECTRIC && !isRoughDielectric(mat)) {
            Frame frame = makeFrame(dot(si.ns, wo) < 0.0 ? -si.ns : si.ns);
            float uLobe = rng1(rng, bounceDimension(depth, DIM_BSDF_LOBE));
            bs = dielectricSample(mat.baseColor, mat.ior, si.frontFace, frame, toLocal(frame, wo), uLobe);
        } else {
            Frame frame;
            if (!surfaceFrame(si, mat, frame)) break;
            vec3 woLocal = toLocal(frame, wo);
            if (isSmoothReflector(mat)) {
                bs = smoothReflectorSample(mat, frame, woLocal);
            } else if (isSurfaceBsdf(mat)) {
                if (USE_NEE && scene.numLights > 0u)
                    L += beta * bdptLightSample(si, frame, woLocal, mat, rng, depth, mis);
                // The light vertices that make a path no longer than the depth: a prefix.
                // (Vertex i has at least i + 1 segments, so the count is bounded without a load.)
                uint eligible = 0u;
                while (eligible < lightVertexCount && depth + eligible + 2u <= scene.maxDepth &&
                       depth + lightVertexAt(eligible).segments + 1u <= scene.maxDepth)
                    eligible += 1u;
                if (eligible > 0u) {
                    float u = rng1(rng, DIM_CONNECTION + depth);
                    LightVertex lv = lightVertexAt(min(uint(u * float(eligible)), eligible - 1u));
                    L += beta * float(eligible) * connectToLightVertex(si, mat, frame, wo, depth, mis, lv);
                }
                if (mergingPhase(VCM_PHASE_CAMERA)) L += beta * mergeAtVertex(si, mat, frame, wo, depth, mis);
                bs = surfaceSample(mat, frame, woLocal, rng1(rng, bounceDimension(depth, DIM_BSDF_LOBE)),
                    rng2(rng, bounceDimension(depth, DIM_BSDF_DIRECTION)));
                if (bs.valid && !bs.isDelta) pdfReverse = surfacePdf(mat, toLocal(frame, bs.wi), woLocal);
            }
            if (HAS_NORMAL_MAPS && !transmissive && dot(bs.wi, si.nSurface) <= 0.0) break;
        }
        if (!bs.valid || maxComponent(bs.weight) <= 0.0 || !(bs.pdf > 0.0)) break;
        advanceMisSums(bs, abs(dot(bs.wi, si.ng)), pdfReverse, bs.isDelta ? 0.0 : mergeTerm(si.p, si.ng, bs.wi), mis);
        beta *= bs.weight;
        etaScale *= bs.etaScale;
        if (USE_RR && depth >= scene.rrStartDepth) {
            float m = maxComponent(beta * etaScale) / scene.rrThreshold;
            if (m < 1.0) {
                float q = max(0.0, 1.0 - m);
                if (rng1(rng, bounceDimension(depth, DIM_ROULETTE)) < q) break;
                beta /= 1.0 - q;
            }
        }
        ray.origin = spawnOrigin(si.p, si.ng, bs.wi, si.magnitude);
        ray.direction = bs.wi;
        prevNormal = si.ng;
        depth += 1u;
    }
    return L;
}

#endif
