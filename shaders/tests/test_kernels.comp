#version 460
// Test kernel: runs the production sampling, light and traversal code on inputs the host
// chooses, so host-side tests (tests/shaders/) can check samplers against their pdfs and the BVH
// against brute force with exactly the arithmetic the renderer uses.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "shared/layout.h"
#include "integrator/path.glsl"

layout(local_size_x = 64) in;
layout(push_constant) uniform PushBlock { GpuTestPush push; };
// The mode this pipeline runs (TEST_MODE_*), a specialization constant: a test process compiles
// only the modes it uses, each without the others' code (lavapipe compiles every pipeline anew in
// every process, and the whole kernel took 2 s of each test's time).
layout(constant_id = TEST_MODE_CONSTANT_ID) const uint TEST_MODE = 0u;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= push.count) return;
    if (push.sceneParams != 0ul) bindScene(push.sceneParams);
    Vec4Ref outputs = Vec4Ref(push.outputs);
    Rng rng = rngCreate(uvec2(i, i >> 16u), 0u, push.seed);
    vec2 u = rng2(rng, 0u);
    if (TEST_MODE == TEST_MODE_COSINE_HEMISPHERE || TEST_MODE == TEST_MODE_UNIFORM_HEMISPHERE) {
        if (push.inputs != 0ul) u = Vec4Ref(push.inputs).v[i].xy; // the host's own numbers
        vec3 w = TEST_MODE == TEST_MODE_COSINE_HEMISPHERE ? sampleCosineHemisphere(u) : sampleUniformHemisphere(u);
        float pdf = TEST_MODE == TEST_MODE_COSINE_HEMISPHERE ? cosineHemispherePdf(w.z) : uniformHemispherePdf(w.z);
        outputs.v[i] = vec4(w, pdf);
    } else if (TEST_MODE == TEST_MODE_LIGHT_SAMPLE) {
        // push.normal: the shading point's normal, for the light tree (0: none).
        LightSample ls = sampleLight(push.point, push.normal, rng1(rng, 2u), rng2(rng, 3u));
        outputs.v[i] = vec4(ls.wi, ls.pdf);
    } else if (TEST_MODE == TEST_MODE_LIGHT_PDF) {
        // pdf of direction inputs[i] as the integrator computes it when a BSDF ray hits a light.
        Ray ray;
        ray.origin = push.point;
        ray.direction = normalize(Vec4Ref(push.inputs).v[i].xyz);
        Hit hit;
        float pdf = 0.0;
        if (traceClosest(ray, FLOAT_MAX, hit)) {
            SurfaceInteraction si = makeInteraction(ray, hit);
            if (si.lightIndex != NO_LIGHT)
                pdf = lightPdf(si.lightIndex, ray.origin, push.normal, si.p, si.ng, hit.t, ray.direction);
        } else {
            pdf = environmentPdf(ray.direction);
        }
        outputs.v[i] = vec4(pdf);
    } else if (TEST_MODE == TEST_MODE_LIGHT_CHOICE) {
        LightChoice c = chooseLight(push.point, push.normal, rng1(rng, 2u));
        outputs.v[i] = vec4(uintBitsToFloat(c.index), c.pmf, 0.0, 0.0);
    } else if (TEST_MODE == TEST_MODE_LIGHT_SELECTION_PMF) {
        outputs.v[i] = vec4(lightSelectionPmf(i, sceneLights.v[i], push.point, push.normal), 0.0, 0.0, 0.0);
    } else if (TEST_MODE == TEST_MODE_BSDF_SAMPLE) {
        // The local frame is the canonical one: wo = push.normal, z = shading normal.
        GpuMaterial m = sceneMaterials.v[push.materialIndex];
        Frame frame = makeFrame(vec3(0.0, 0.0, 1.0));
        orientMaterialFrame(frame, m); // the coat's normal: the shading normal, as at a hit
        BsdfSample bs = surfaceSample(m, frame, normalize(push.normal), rng1(rng, 2u), u);
        outputs.v[i] = vec4(bs.wi, bs.valid ? bs.pdf : 0.0);
        outputs.v[push.count + i] = vec4(bs.weight, bs.valid ? 1.0 : 0.0);
    } else if (TEST_MODE == TEST_MODE_SOBOL_POINTS) {
        // One pixel's stream, sample index i: the points a render adds to that pixel in order.
        Rng pixelStream = rngCreate(uvec2(0u), i, push.seed);
        uvec2 a = sobolOwen2(i, sobolSeeds(pixelStream, 0u));
        uvec2 b = sobolOwen2(i, sobolSeeds(pixelStream, 3u));
        outputs.v[i] = vec4(uintToUnitFloat(a.x), uintToUnitFloat(a.y), uintToUnitFloat(b.x), uintToUnitFloat(b.y));
    } else if (TEST_MODE == TEST_MODE_SOBOL_BOUNCE_PAIR) {
        Rng pixelStream = rngCreate(uvec2(0u), i, push.seed);
        uvec2 a = sobolPoint2(pixelStream, bounceDimension(1u, DIM_BSDF_DIRECTION));
        uvec2 b = sobolPoint2(pixelStream, bounceDimension(2u, DIM_BSDF_DIRECTION));
        outputs.v[i] = vec4(uintToUnitFloat(a.x), uintToUnitFloat(a.y), uintToUnitFloat(b.x), uintToUnitFloat(b.y));
    } else if (TEST_MODE == TEST_MODE_TEXTURE) {
        // Texture push.materialIndex at uv = inputs[i].xy (images) or point inputs[i].xyz.
        vec4 at = Vec4Ref(push.inputs).v[i];
        outputs.v[i] = evalTexture(push.materialIndex, at.xy, at.xyz);
    } else if (TEST_MODE == TEST_MODE_BSDF_PDF) {
        GpuMaterial m = sceneMaterials.v[push.materialIndex];
        Frame frame = makeFrame(vec3(0.0, 0.0, 1.0));
        orientMaterialFrame(frame, m);
        vec3 wo = normalize(push.normal);
        vec3 wi = normalize(Vec4Ref(push.inputs).v[i].xyz);
        // What light sampling uses (the fused routine) in x and w; the separate routines in y, z.
        float pdf;
        vec3 f = surfaceEvalPdf(m, wo, wi, pdf);
        outputs.v[i] = vec4(f.x, surfaceEval(m, wo, wi).x, surfacePdf(m, wo, wi), pdf);
    } else if (TEST_MODE == TEST_MODE_TRACE_BVH || TEST_MODE == TEST_MODE_TRACE_BRUTE_FORCE) {
        GpuTestRay tr = TestRayRef(push.inputs).v[i];
        Ray ray;
        ray.origin = tr.origin;
        ray.direction = tr.direction;
        Hit hit;
        bool found = false;
        if (TEST_MODE == TEST_MODE_TRACE_BVH) {
            found = traceClosest(ray, tr.tMax, hit);
            // The any-hit query must agree with the closest-hit one about whether anything is there.
            bool any = traceAny(ray, tr.tMax);
            if (any != found) found = false, hit.t = -2.0;
        } else {
            WatertightRay wray = makeWatertightRay(ray);
            hit.t = tr.tMax;
            hit.primitive = 0u;
            hit.bary = vec2(0.0);
            hit.instance = NO_INSTANCE;
            // The world triangles, then each instance's in its object space (the same
            // transformed ray the traversal makes), so any difference is the trees' fault.
            uint worldTriangles =
                scene.numInstances > 0u ? InstanceRef(scene.instances).v[0].firstTriangle : scene.numTriangles;
            for (uint j = 0u; j < scene.numInstances; ++j)
                worldTriangles = min(worldTriangles, InstanceRef(scene.instances).v[j].firstTriangle);
            for (uint k = 0u; k < worldTriangles; ++k) {
                GpuTriangle tri = loadTriangle(k);
                float t;
                vec2 bary;
                if (intersectTriangle(wray, tri.p0, tri.p1, tri.p2, hit.t, t, bary)) {
                    hit.t = t;
                    hit.primitive = k;
                    hit.bary = bary;
                    found = true;
                }
            }
            for (uint j = 0u; j < scene.numInstances; ++j) {
                GpuInstance instance = InstanceRef(scene.instances).v[j];
                WatertightRay local = makeWatertightRay(toInstanceSpace(instance, ray));
                for (uint k = instance.firstTriangle; k < instance.firstTriangle + instance.triangleCount; ++k) {
                    GpuTriangle tri = loadTriangle(k);
                    float t;
                    vec2 bary;
                    if (intersectTriangle(local, tri.p0, tri.p1, tri.p2, hit.t, t, bary)) {
                        hit.t = t;
                        hit.primitive = k;
                        hit.bary = bary;
                        hit.instance = j;
                        found = true;
                    }
                }
            }
            for (uint k = 0u; k < scene.numSpheres; ++k) {
                float t;
                if (intersectSphere(SphereRef(scene.spheres).v[k], ray, hit.t, t)) {
                    hit.t = t;
                    hit.primitive = k | SPHERE_BIT;
                    hit.bary = vec2(0.0);
                    found = true;
                }
            }
        }
        // A hit in an instance: its index in place of the second barycentric, and
        // TEST_HIT_INSTANCE_BIT on the primitive.
        bool inInstance = found && hit.instance != NO_INSTANCE;
        vec4 instanced = vec4(
            hit.t, uintBitsToFloat(hit.primitive | TEST_HIT_INSTANCE_BIT), hit.bary.x, uintBitsToFloat(hit.instance));
        outputs.v[i] = inInstance ? instanced
                       : found    ? vec4(hit.t, uintBitsToFloat(hit.primitive), hit.bary)
                                  : vec4(hit.t == -2.0 ? -2.0 : -1.0, 0.0, 0.0, 0.0);
    }
}
