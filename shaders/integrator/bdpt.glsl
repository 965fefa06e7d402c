// Bidirectional path tracing (Veach 1997, ch. 10). Each sample traces a light subpath from an
// emitter and a camera subpath from the pixel, and adds every way of forming a path from them:
//   s = 0: the camera path hits an emitter;
//   s = 1: light sampling at a camera vertex (next event estimation);
//   s >= 2: a camera vertex connected to light subpath vertex s - 1 by a shadow ray;
//   t = 1: a light subpath vertex connected to the camera, splatted to the pixel it lands in
//          (integrator/splat.glsl; one light subpath per pixel and sample, as the caustic light
//          tracer does).
// Each is weighted by the power heuristic over all strategies that could have made the path,
// computed from two running sums per subpath (dVCM and dVC, Georgiev 2012, "Implementing vertex
// connection and merging", without the merging terms), so no subpath is walked twice. Strategies
// that cannot make a path (hitting a light no ray can hit, sampling through a delta bounce, a
// light that starts no light subpath) have density 0 there and drop out of the sums.
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

// The power heuristic's square; without MIS, 1 for every strategy that can make the path, so
// the weights become 1 / (number of such strategies).
float misPower(float x) { return USE_MIS ? x * x : (x > 0.0 ? 1.0 : 0.0); }

// The weight of strategy s for a path of `segments` segments: `mis`, or in a kernel that keeps
// one strategy alone (BDPT_STRATEGY, tests), 1 for it and 0 for every other.
float strategyWeight(uint s, uint segments, float mis) {
    if (BDPT_STRATEGY == BDPT_ALL_STRATEGIES) return mis;
    return BDPT_STRATEGY == BDPT_ONE_STRATEGY(segments, s) ? 1.0 : 0.0;
}

// The MIS sums of a subpath carried across the bounce `bs` (either subpath's: the recursion is
// the same): cosOut, the new direction's geometric cosine here; pdfReverse, the density of the
// other subpath's sampling the direction this one arrived from. A delta bounce's forward and
// reverse lobe probabilities are equal and cancel, and no strategy connects at it.
void advanceMisSums(BsdfSample bs, float cosOut, float pdfReverse, inout float dVCM, inout float dVC) {
    if (bs.isDelta) {
        dVCM = 0.0;
        dVC *= misPower(cosOut);
    } else {
        dVC = misPower(cosOut / bs.pdf) * (dVC * misPower(pdfReverse) + dVCM);
        dVCM = misPower(1.0 / bs.pdf);
    }
}

// A light subpath vertex a camera vertex can connect to. Its interaction is rebuilt from the
// segment that found it (cheaper to keep than the shaded material).
struct LightVertex {
    Ray ray;
    Hit hit;
    vec3 p;     // the hit point, to reject connections before rebuilding the rest
    vec3 beta;  // emitted radiance over the density of the light subpath up to here
    float dVCM; // MIS sums at this vertex (file comment)
    float dVC;
    uint segments; // light subpath segments up to this vertex
};

LightVertex lightVertices[BDPT_MAX_LIGHT_VERTICES];
uint lightVertexCount = 0u;

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
    SurfaceInteraction si, GpuMaterial mat, vec3 wLight, vec3 beta, float dVCM, float dVC, uint segments) {
    CameraView view;
    if (!viewFromPinhole(scene.camera, scene.imageSize, si.p, view)) return;
    VertexEval e;
    if (!evalVertex(si, mat, view.wCamera, wLight, e)) return;
    float cosLightIn = abs(dot(wLight, si.ng));
    if (cosLightIn < 1e-7) return;
    float cosCamera = abs(dot(view.wCamera, si.ng));
    float cameraPdfArea = view.importance * cosCamera; // over the pixel count
    float others = misPower(cameraPdfArea) * (dVCM + dVC * misPower(e.pdfTowardsLight));
    float weight = strategyWeight(segments + 1u, segments + 1u, 1.0 / (1.0 + others));
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
    float dVC = em.hittable ? misPower(em.cosLight / em.pdfEmit) : 0.0;
    float dVCM = 0.0;
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
        if (segments == 1u && em.infinite) {
            // Both densities are of directions, so the first segment's length does not enter.
            dVCM = misPower(directLightPdfInfinite(lightIndex, ray.direction) / (em.pdfEmit * cosIn));
        } else if (segments == 1u) {
            vec3 d = si.p - em.p;
            float dist2 = dot(d, d);
            dVCM = misPower(directLightPdfArea(lightIndex, si.p, em.p, em.normal) * dist2 / (em.pdfEmit * cosIn));
        } else {
            dVCM *= misPower(hit.t * hit.t) / misPower(cosIn);
        }
        dVC /= misPower(cosIn);
        if (HAS_UNLIT && (mat.flags & MATERIAL_FLAG_UNLIT) != 0u) break;

        bool connectible = isSurfaceBsdf(mat);
        if (connectible) {
            if (segments + 2u <= scene.maxDepth && lightVertexCount < BDPT_MAX_LIGHT_VERTICES) {
                LightVertex v;
                v.ray = ray;
                v.hit = hit;
                v.p = si.p;
                v.beta = beta;
                v.dVCM = dVCM;
                v.dVC = dVC;
                v.segments = segments;
                lightVertices[lightVertexCount++] = v;
            }
            if (cameraConnects && segments + 1u <= scene.maxDepth)
                connectLightVertexToCamera(si, mat, wLight, beta, dVCM, dVC, segments);
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
        advanceMisSums(bs, abs(dot(wCamera, si.ng)), pdfReverse, dVCM, dVC);
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
    SurfaceInteraction si, Frame frame, vec3 woLocal, GpuMaterial mat, Rng rng, uint depth, float dVCM, float dVC) {
    uint lightIndex = selectLight(rng1(rng, bounceDimension(depth, DIM_LIGHT_SELECT)));
    LightSample ls = sampleLightIndex(lightIndex, si.p, rng2(rng, bounceDimension(depth, DIM_LIGHT_POINT)));
    if (ls.pdf <= 0.0 || maxComponent(ls.radiance) <= 0.0) return vec3(0.0);
    if (!isTransmissiveSurface(mat) && dot(ls.wi, si.nSurface) <= 0.0) return vec3(0.0);
    vec3 wiLocal = toLocal(frame, ls.wi);
    float pdfForward;
    vec3 fCos = surfaceEvalPdf(mat, woLocal, wiLocal, pdfForward);
    if (maxComponent(fCos) <= 0.0) return vec3(0.0);
    float others = ls.isDelta ? 0.0 : misPower(pdfForward / ls.pdf); // s = 0: a BSDF ray hits it
    float pdfEmit = emissionPdf(lightIndex, ls.point, ls.normal, -ls.wi);
    if (pdfEmit > 0.0) {
        // s >= 2: the light subpath starts here and reaches si.
        GpuLight light = sceneLights.v[lightIndex];
        bool positionDelta = isPositionDeltaLight(light);
        float cosAtLight = positionDelta || isInfiniteLight(light) ? 1.0 : abs(dot(ls.normal, ls.wi));
        float directPdfW = positionDelta ? ls.pdf * ls.distance * ls.distance : ls.pdf;
        float cosHere = abs(dot(ls.wi, si.ng));
        float pdfReverse = surfacePdf(mat, wiLocal, woLocal);
        others += misPower(pdfEmit * cosHere / (directPdfW * cosAtLight)) * (dVCM + dVC * misPower(pdfReverse));
    }
    float weight = strategyWeight(1u, depth + 1u, 1.0 / (1.0 + others));
    if (weight == 0.0 || lightOccluded(si, ls)) return vec3(0.0);
    if (HAS_ABSORPTION && ls.distance != FLOAT_MAX && entersAbsorbingInterior(si, mat, ls.wi))
        fCos *= exp(-mat.sigmaA * ls.distance);
    return fCos * ls.radiance * (weight / ls.pdf);
}

// s >= 2: camera vertex si (shading in `frame`, reached from direction wo, MIS sums dVCM and
// dVC, `depth` segments) connected to light subpath vertex lv.
vec3 connectToLightVertex(
    SurfaceInteraction si, GpuMaterial mat, Frame frame, vec3 wo, uint depth, float dVCM, float dVC, LightVertex lv) {
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
    float lightSide = misPower(cameraMakesLightVertex) * (lv.dVCM + lv.dVC * misPower(l.pdfTowardsLight));
    float cameraSide = misPower(lightMakesCameraVertex) * (dVCM + dVC * misPower(c.pdfTowardsCamera));
    uint s = lv.segments + 1u;
    float weight = strategyWeight(s, depth + s, 1.0 / (lightSide + 1.0 + cameraSide));
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
    float dVCM = cameraConnects ? misPower(cameraDirectionWeight(scene.camera, ray.direction)) : 0.0;
    float dVC = 0.0;
    while (true) {
        Hit hit;
        countClosestRay();
        if (!traceClosest(ray, FLOAT_MAX, hit)) {
            // Escaped: the environment, against light sampling (s = 1) and the light subpaths that
            // start from it (s >= 2; at infinity the sums take no last segment's length).
            if (HAS_ENVIRONMENT && scene.envWidth > 0u) {
                float pdfDirection = environmentPdf(ray.direction);
                float others = depth > 1u && USE_NEE ? misPower(pdfDirection) * dVCM : 0.0;
                others += misPower(pdfDirection * infiniteLightDiscPdf()) * dVC;
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
        dVCM *= misPower(hit.t * hit.t) / misPower(cosIn);
        dVC /= misPower(cosIn);

        // s = 0: an emitter found by the camera path.
        if (HAS_EMITTERS && maxComponent(mat.emission) > 0.0) {
            vec3 Le = emittedRadiance(mat, si.frontFace);
            float others = 0.0;
            if (depth > 1u && si.lightIndex != NO_LIGHT) {
                others = misPower(directLightPdfArea(si.lightIndex, ray.origin, si.p, si.ng)) * dVCM +
                         misPower(emissionPdf(si.lightIndex, si.p, si.ng, -ray.direction)) * dVC;
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
                    L += beta * bdptLightSample(si, frame, woLocal, mat, rng, depth, dVCM, dVC);
                for (uint i = 0u; i < lightVertexCount; ++i) {
                    LightVertex lv = lightVertices[i];
                    if (depth + lv.segments + 1u > scene.maxDepth) break;
                    L += beta * connectToLightVertex(si, mat, frame, wo, depth, dVCM, dVC, lv);
                }
                bs = surfaceSample(mat, frame, woLocal, rng1(rng, bounceDimension(depth, DIM_BSDF_LOBE)),
                    rng2(rng, bounceDimension(depth, DIM_BSDF_DIRECTION)));
                if (bs.valid && !bs.isDelta) pdfReverse = surfacePdf(mat, toLocal(frame, bs.wi), woLocal);
            }
            if (HAS_NORMAL_MAPS && !transmissive && dot(bs.wi, si.nSurface) <= 0.0) break;
        }
        if (!bs.valid || maxComponent(bs.weight) <= 0.0 || !(bs.pdf > 0.0)) break;
        advanceMisSums(bs, abs(dot(bs.wi, si.ng)), pdfReverse, dVCM, dVC);
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
        depth += 1u;
    }
    return L;
}

#endif
