#pragma once
#include <cstdint>
#include <string>

namespace pt {

enum class DirectionSampling { Uniform, Cosine };

// What fills the random dimensions of a sample (`--sampler`): independent hashes, or
// Owen-scrambled Sobol' points shuffled per pixel (shaders/common/sobol.glsl).
enum class SamplerKind { Independent, Sobol };

// How light transport is estimated (`--integrator`): path tracing, bidirectional path tracing,
// bidirectional path tracing with vertex merging (VCM), or the one the scene calls for
// (src/flatten/feature_set.cpp, bdptChosen and mergingChosen).
enum class Estimator { Auto, Path, Bidirectional, VertexMerging };

// How light sampling chooses a light among the bounded ones (`--light-tree`): by the light tree,
// by power alone, or the one the scene calls for (src/flatten/feature_set.cpp, lightTreeChosen).
enum class LightSelection { Auto, Tree, Power };

// The integrator switches (the course's RendererParams) and limits.
struct IntegratorSettings {
    bool nee = true; // next event estimation (light sampling)
    bool mis = true; // multiple importance sampling between light and BSDF samples (needs NEE)
    bool rr = true;  // Russian roulette
    DirectionSampling sampling = DirectionSampling::Cosine;
    // Sobol' is the default: at equal time it had lower or equal error on every scene measured
    // (0.53x relMSE on the diffuse box, 0.63x on a 1 M-triangle mesh, 0.89x with rough
    // materials, 0.96x on the glass box; bench/RESULTS.md, "The defaults").
    SamplerKind sampler = SamplerKind::Sobol;
    uint32_t maxDepth = 16; // ray segments including the camera ray (Mitsuba 3's max_depth)
    // Russian roulette only after this many segments. 3 (Mitsuba 3 uses 5) had equal or lower
    // relMSE at equal time on all four scenes of bench/bench_defaults.sh (0.92-1.00x; RESULTS).
    uint32_t rrStartDepth = 3;
    // Paths whose throughput is at least this always continue; below it they survive with
    // probability throughput / rrThreshold. pbrt and Mitsuba use 1; 0.5 gave 10% lower relMSE at
    // equal time in the glass Cornell box and the same in the diffuse one (bench/RESULTS.md).
    float rrThreshold = 0.5f;
    uint32_t seed = 0;
    // The CENG795 course's classic ray tracer instead of path tracing: ambient + direct light
    // with its Blinn-Phong shading at the first non-specular surface, specular chains followed.
    bool classic = false;
    // Caustics seen directly (camera -> diffuse -> specular chain -> area light) by light
    // tracing, splatted, instead of by BSDF sampling; used where the scene has such paths
    // (computeFeatures). The image is the same in expectation, with far less noise there.
    bool lightTracing = true;
    Estimator estimator = Estimator::Auto;
    // Vertex merging: the first round's merge radius in pixel footprints at the median distance
    // of the surfaces the camera sees (FlatScene::cameraHitDistance; the scene's radius where
    // unmeasured), and the rate it shrinks at (r_i = r_1 i^((alpha - 1) / 2)).
    // 8 had 0.6x the relMSE of 5 at 30 s on Veach Ajar and was level on scenes/ajar; 12 and 3 were
    // worse (bench/RESULTS.md, "Vertex merging"). Alpha 0.65 had 0.82x the relMSE of 0.75 at 60 s
    // on scenes/ajar (whose error there is mostly the merges' bias), level at 10 s and on Veach Ajar.
    float mergeRadius = 8.0f;
    float mergeAlpha = 0.65f;
    LightSelection lightSelection = LightSelection::Auto;
    // The triangle tree for every scene (`--bvh always`, the default). `--bvh auto` (false) traces
    // a tiny scene (at most UNIFORM_TRIANGLES_MAX triangles, no instances) without it, every
    // triangle from a uniform buffer (src/flatten/feature_set.cpp, uniformTriangleCount): faster on
    // lavapipe when it came (2026-12-05), slower since the tree's least-cost collapse and its texel
    // loads (the diffuse box: 0.80x the relMSE at equal time through the tree; bench/RESULTS.md,
    // "Geometry read through texel buffers"). The same image either way.
    bool alwaysTree = true;
    // `--shared-samples on`: the path tracer's pixels of one SIMD vector (8, spread over an 8x8
    // block) take the same random numbers, so their paths stay coherent. Each pixel's expected
    // error is unchanged and paths are 1.23-1.28x faster on lavapipe (relMSE 0.74-0.83x at equal
    // time), but the group's noise is correlated: the error of the image averaged over 8x8 blocks
    // is 1.8-4x higher (bench/RESULTS.md, "Shared samples"). Off by default for that reason.
    bool sharedSamples = false;
    // false (`--texel-loads off`, or `auto` where this machine was measured faster so,
    // render/texel_load_choice.h): the trees' nodes and the triangles read through buffer
    // addresses even where texel buffers could be used (TEXEL_LOADS, shared/features.h). The
    // same image either way.
    bool texelLoads = true;

    std::string describe() const;
};

} // namespace pt
