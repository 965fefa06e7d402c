// The kernel's features: one row each. Included by GLSL (shared/features.glsl declares the
// specialization constants from it) and by C++ (src/flatten/feature_set.h derives FeatureSet,
// FeatureSet::all, the constants handed to the pipeline and the log line from it). Adding a
// feature is one row here plus the code that reads its constant.
//
// PT_FEATURE(field, kind, CONSTANT, id, unspecialised, all, decide, log, description)
//   field         FeatureSet's member (C++)
//   kind          flag: a bool constant; choice: a uint constant; module: a bool that selects a
//                 SPIR-V module of its own (CMakeLists.txt: PT_LIGHT_TRACING), a constant only in it
//   CONSTANT      the GLSL name of the constant
//   id            its constant_id (0 and 1 are the workgroup size, SPEC_LOCAL_SIZE_X/Y)
//   unspecialised its value in the SPIR-V as compiled, and FeatureSet's default
//   all           its value in FeatureSet::all(s): every scene feature compiled in, the switches
//                 of IntegratorSettings `s` as given
//   decide        its value for a scene: an expression over the FlatScene `scene`, the
//                 IntegratorSettings `s` and the rows above it (FeatureSet `f`), with the
//                 predicates of src/flatten/feature_set.cpp
//   log           the word the log line and the EXR's "features" show for value `v`, or nullptr
//   description   what the feature is, for people
// Rows are in the order of the log line; a row's decision may read only the rows above it.
#ifndef PT_SHADERS_SHARED_FEATURES_H
#define PT_SHADERS_SHARED_FEATURES_H

#define PT_FEATURES(PT_FEATURE)                                                                                        \
    PT_FEATURE(classic, flag, CLASSIC, 26, false, s.classic, s.classic, v ? "classic" : nullptr,                       \
        "the CENG795 course's classic (Whitted / direct lighting) ray tracer instead of path tracing")                 \
    PT_FEATURE(triangles, flag, HAS_TRIANGLES, 13, true, true, !scene.triangles.empty(), v ? "triangles" : nullptr,    \
        "triangle meshes")                                                                                             \
    PT_FEATURE(instances, flag, HAS_INSTANCES, 39, true, true, !scene.instances.empty(), v ? "instances" : nullptr,    \
        "meshes placed several times, kept as instances under a tree of their own (two-level BVH)")                    \
    PT_FEATURE(spheres, flag, HAS_SPHERES, 12, true, true, !scene.spheres.empty(), v ? "spheres" : nullptr,            \
        "analytic spheres and ellipsoids")                                                                             \
    PT_FEATURE(diffuse, flag, HAS_DIFFUSE, 2, true, true, usesMaterialType(scene, MATERIAL_DIFFUSE),                   \
        v ? "diffuse" : nullptr, "Lambertian surfaces")                                                                \
    PT_FEATURE(mirror, flag, HAS_MIRROR, 3, true, true, usesMaterialType(scene, MATERIAL_MIRROR),                      \
        v ? "mirror" : nullptr, "smooth mirrors")                                                                      \
    PT_FEATURE(dielectric, flag, HAS_DIELECTRIC, 4, true, true, usesMaterialType(scene, MATERIAL_DIELECTRIC),          \
        v ? "dielectric" : nullptr, "glass and other dielectrics (smooth or GGX-rough)")                               \
    PT_FEATURE(conductor, flag, HAS_CONDUCTOR, 14, true, true, usesMaterialType(scene, MATERIAL_CONDUCTOR),            \
        v ? "conductor" : nullptr, "metals with a complex index of refraction (smooth or GGX-rough)")                  \
    PT_FEATURE(glossy, flag, HAS_GLOSSY, 16, true, true, usesMaterialType(scene, MATERIAL_GLOSSY),                     \
        v ? "glossy" : nullptr, "the course's BRDFs: Lambert plus one Phong, Blinn-Phong or Torrance-Sparrow lobe")    \
    PT_FEATURE(pbr, flag, HAS_PBR, 24, true, true, usesMaterialType(scene, MATERIAL_PBR), v ? "pbr" : nullptr,         \
        "glTF metallic-roughness materials")                                                                           \
    PT_FEATURE(diffuseTransmission, flag, HAS_DIFFUSE_TRANSMISSION, 33, true, true,                                    \
        f.pbr&& usesDiffuseTransmission(scene), v ? "diffuse-transmission" : nullptr,                                  \
        "glTF KHR_materials_diffuse_transmission (Lambertian transmission)")                                           \
    PT_FEATURE(clearcoat, flag, HAS_CLEARCOAT, 34, true, true, f.pbr&& usesClearcoat(scene),                           \
        v ? "clearcoat" : nullptr, "glTF KHR_materials_clearcoat (a GGX coat over the material)")                      \
    PT_FEATURE(sheen, flag, HAS_SHEEN, 35, true, true, f.pbr&& usesSheen(scene), v ? "sheen" : nullptr,                \
        "glTF KHR_materials_sheen (Charlie sheen under the coat, over the base)")                                      \
    PT_FEATURE(iridescence, flag, HAS_IRIDESCENCE, 36, true, true, f.pbr&& usesIridescence(scene),                     \
        v ? "iridescence" : nullptr, "glTF KHR_materials_iridescence (thin-film interference in the Fresnel term)")    \
    PT_FEATURE(anisotropy, flag, HAS_ANISOTROPY, 37, true, true, f.pbr&& usesAnisotropy(scene),                        \
        v ? "anisotropy" : nullptr, "glTF KHR_materials_anisotropy (anisotropic GGX along a tangent direction)")       \
    PT_FEATURE(dispersion, flag, HAS_DISPERSION, 38, true, true, usesDispersion(scene), v ? "dispersion" : nullptr,    \
        "glTF KHR_materials_dispersion (a wavelength per path through dispersive glass)")                              \
    PT_FEATURE(microfacet, flag, HAS_MICROFACET, 23, true, true, usesRoughConductorOrDielectric(scene),                \
        v ? "microfacet" : nullptr, "GGX-rough conductors or dielectrics")                                             \
    PT_FEATURE(absorption, flag, HAS_ABSORPTION, 5, true, true, usesMaterialFlag(scene, MATERIAL_FLAG_ABSORBING),      \
        v ? "absorption" : nullptr, "Beer-Lambert absorption inside dielectrics and PBR volumes")                      \
    PT_FEATURE(shadingNormals, flag, HAS_SHADING_NORMALS, 6, true, true,                                               \
        usesTriangleFlag(scene, TRIANGLE_FLAG_SHADING_NORMALS), v ? "shading-normals" : nullptr,                       \
        "interpolated vertex normals")                                                                                 \
    PT_FEATURE(emitters, flag, HAS_EMITTERS, 7, true, true, usesEmission(scene), v ? "emitters" : nullptr,             \
        "surfaces that emit: emissive materials, emissive textures, the course's replace_all")                         \
    PT_FEATURE(sphericalLights, flag, SPHERICAL_TRIANGLE_LIGHTS, 40, true, true,                                       \
        f.emitters&& usesSphericalTriangleSampling(scene), v ? "solid-angle-lights" : nullptr,                         \
        "triangle emitters that some surface sees under more than 0.5 sr, sampled by solid angle there")               \
    PT_FEATURE(punctualLights, flag, HAS_PUNCTUAL_LIGHTS, 15, true, true, hasPunctualLights(scene),                    \
        v ? "punctual-lights" : nullptr, "point, spot, directional and the course's square lights")                    \
    PT_FEATURE(environment, flag, HAS_ENVIRONMENT, 17, true, true, scene.environment.width > 0,                        \
        v ? "environment" : nullptr, "an environment map")                                                             \
    PT_FEATURE(textures, flag, HAS_TEXTURES, 18, true, true, usesTextureKind(scene, true), v ? "textures" : nullptr,   \
        "image textures on any material slot or the background")                                                       \
    PT_FEATURE(procedural, flag, HAS_PROCEDURAL, 21, true, true, usesTextureKind(scene, false),                        \
        v ? "procedural-textures" : nullptr, "the course's checkerboard or Perlin textures")                           \
    PT_FEATURE(normalMaps, flag, HAS_NORMAL_MAPS, 19, true, true, usesNormalMaps(scene), v ? "normal-maps" : nullptr,  \
        "normal or bump maps")                                                                                         \
    PT_FEATURE(alpha, flag, HAS_ALPHA, 20, true, true, usesTriangleFlag(scene, TRIANGLE_FLAG_ALPHA_TESTED),            \
        v ? "alpha" : nullptr, "alpha-tested (cut-out) triangles")                                                     \
    PT_FEATURE(unlit, flag, HAS_UNLIT, 22, true, true, usesMaterialFlag(scene, MATERIAL_FLAG_UNLIT),                   \
        v ? "unlit" : nullptr, "the course's replace_all surfaces, shown unshaded")                                    \
    PT_FEATURE(motion, flag, HAS_MOTION, 27, true, true, !scene.motions.empty(), v ? "motion-blur" : nullptr,          \
        "moving objects (motion blur)")                                                                                \
    /* Light sampling needs something to sample and a non-delta surface that can use it (the   \
       environment is in the light table too). The classic ray tracer always samples lights, on \
       every surface: its Blinn-Phong terms apply to mirrors and glass too. */                       \
    PT_FEATURE(nee, flag, USE_NEE, 8, true, s.nee, neeUseful(scene, s, f), v ? "nee" : nullptr,                        \
        "next event estimation (light sampling)")                                                                      \
    /* The classic ray tracer never continues diffuse paths: no MIS, no roulette. */                                   \
    PT_FEATURE(mis, flag, USE_MIS, 9, true, s.nee&& s.mis, f.nee&& s.mis && !f.classic, v ? "mis" : nullptr,           \
        "multiple importance sampling of light and BSDF samples")                                                      \
    PT_FEATURE(rr, flag, USE_RR, 10, true, s.rr, s.rr && !f.classic, v ? "rr" : nullptr, "Russian roulette")           \
    /* Estimators the scene decides, not compiled-in features: off in all(). */                                        \
    PT_FEATURE(bdpt, module, BDPT, 41, false, false, bdptChosen(scene, s, f), v ? "bdpt" : nullptr,                    \
        "bidirectional path tracing: light and camera subpaths joined by every strategy, weighted by MIS")             \
    PT_FEATURE(merging, flag, MERGING, 44, false, false, mergingChosen(scene, s, f), v ? "merging" : nullptr,          \
        "vertex merging: BDPT's camera vertices also gather every light subpath's vertices near them (VCM)")           \
    PT_FEATURE(bdptStrategy, choice, BDPT_STRATEGY, 42, BDPT_ALL_STRATEGIES, BDPT_ALL_STRATEGIES, BDPT_ALL_STRATEGIES, \
        v == BDPT_ALL_STRATEGIES ? nullptr : "bdpt-one-strategy",                                                      \
        "BDPT_ONE_STRATEGY: tests only, one bidirectional strategy alone, unweighted")                                 \
    PT_FEATURE(lightTracing, module, LIGHT_TRACING, 31, false, false, lightTracingPays(scene, s, f),                   \
        v ? "light-tracing" : nullptr,                                                                                 \
        "caustics seen directly (camera, diffuse, specular chain, area light) by light tracing, splatted")             \
    PT_FEATURE(lightTree, flag, LIGHT_TREE, 43, true,                                                                  \
        s.nee && !s.classic && s.lightSelection != LightSelection::Power, lightTreeChosen(scene, s, f),                \
        v ? "light-tree" : nullptr,                                                                                    \
        "light sampling chooses among the bounded lights by a tree of their bounds, power and orientation")            \
    PT_FEATURE(cosineSampling, flag, COSINE_SAMPLING, 11, true, s.sampling == DirectionSampling::Cosine,               \
        s.sampling == DirectionSampling::Cosine, v ? "cosine-sampling" : "uniform-sampling",                           \
        "cosine-weighted rather than uniform hemisphere sampling of diffuse lobes")                                    \
    PT_FEATURE(sampler, choice, SAMPLER, 29, SAMPLER_INDEPENDENT, samplerOf(s), samplerOf(s),                          \
        v == SAMPLER_SOBOL ? "sobol" : nullptr, "SAMPLER_*: how the sample dimensions are filled")                     \
    /* The path tracer only: a light subpath shared by 8 pixels would splat 8 times to one place. */                   \
    PT_FEATURE(sharedSamples, flag, SHARED_SAMPLES, 46, false, s.sharedSamples,                                        \
        s.sharedSamples && !f.classic && !f.bdpt, v ? "shared-samples" : nullptr,                                      \
        "the 8 pixels of a SIMD vector (spread over an 8x8 block) share their camera paths' random numbers")           \
    PT_FEATURE(uniformTriangles, choice, UNIFORM_TRIANGLE_COUNT, 45, 0, 0, uniformTriangleCount(scene, s, f),          \
        v ? "all-triangles" : nullptr,                                                                                 \
        "a tiny scene's triangle count: each ray tests them all from a uniform buffer, no tree (0: the tree)")         \
    /* Where a scene's pipeline is not specialised (FeatureSet::all, the test kernels), the      \
       kernel reads the format from the scene. */                     \
    PT_FEATURE(nodeFormat, choice, NODE_FORMAT, 32, BVH_NODES_FROM_SCENE, BVH_NODES_FROM_SCENE, nodeFormatOf(scene),   \
        v == BVH_NODES_QUANTIZED ? "quantized-bvh" : nullptr,                                                          \
        "BVH_NODES_*: how the triangle tree's nodes are stored (float, or quantised for big trees)")                   \
    /* Where a tree is traversed: measured faster on lavapipe (the 1 M-triangle mesh 1.16x, a box \
       through its tree 1.09x, course scenes with spheres 1.05-1.14x) and level where a tiny scene \
       skips its triangle tree; left off on GPUs (src/render/renderer.cpp, supportedFeatures). The \
       image is the same either way. */                    \
    PT_FEATURE(texelLoads, flag, TEXEL_LOADS, 47, false, false,                                                        \
        s.texelLoads && ((hasTriangleTree(scene) && f.uniformTriangles == 0) || hasSphereTree(scene)),                 \
        v ? "texel-loads" : nullptr,                                                                                   \
        "the trees' nodes, the triangles and the spheres read through texel buffers, not buffer addresses")            \
    PT_FEATURE(countRays, flag, COUNT_RAYS, 28, false, false, false, v ? "ray-counts" : nullptr,                       \
        "count traced rays per pixel (pt bench; GpuRenderPush::rayCounts)")                                            \
    PT_FEATURE(forcedRandom, choice, FORCED_RANDOM, 30, FORCED_RANDOM_OFF, FORCED_RANDOM_OFF, FORCED_RANDOM_OFF,       \
        v == FORCED_RANDOM_OFF    ? nullptr                                                                            \
        : v == FORCED_RANDOM_ZERO ? "forced-random-0"                                                                  \
                                  : "forced-random-1",                                                                 \
        "FORCED_RANDOM_*: tests only, every random number pinned to an end of [0, 1)")                                 \
    PT_FEATURE(debugView, choice, DEBUG_VIEW, 25, DEBUG_VIEW_NONE, DEBUG_VIEW_NONE, DEBUG_VIEW_NONE, nullptr,          \
        "DEBUG_VIEW_*: the viewer's diagnostic images instead of radiance")

#endif
