#pragma once
// Which parts of the megakernel a scene and its switches need. Everything else is removed by
// specialization constants when the pipeline is created. The features are the rows of
// shaders/shared/features.h; this struct, all(), constants() and describe() are derived from it.
#include "flatten/flat_scene.h"
#include "flatten/integrator_settings.h"
#include "gpu/compute_pipeline.h"
#include "shared/features.h"

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace pt {

// `--integrator auto` renders by BDPT where fewer light samples than this find their light
// (FlatScene::lightVisibility; bench/RESULTS.md, "Bidirectional path tracing").
constexpr float kBdptBelowLightVisibility = 0.1f;
// ... and where at least this fraction of the bounces from the surfaces the camera sees meet a lit
// sharp GGX lobe (FlatScene::glossyCausticBounces): glossy caustics, which light subpaths carry
// (bench/RESULTS.md, "Glossy caustics choose BDPT").
constexpr float kBdptFromGlossyCausticBounces = 0.02f;

#define PT_FEATURE_CPP_TYPE_flag bool
#define PT_FEATURE_CPP_TYPE_module bool
#define PT_FEATURE_CPP_TYPE_choice uint32_t

struct FeatureSet {
#define PT_FEATURE_MEMBER(field, kind, NAME, id, unspecialised, all, decide, log, description)                         \
    PT_FEATURE_CPP_TYPE_##kind field = unspecialised;
    PT_FEATURES(PT_FEATURE_MEMBER)
#undef PT_FEATURE_MEMBER

    // Every scene feature on, the switches as given: the unspecialised kernel, for comparison
    // (--all-features) and for tests.
    static FeatureSet all(const IntegratorSettings& settings);
    std::vector<SpecializationConstant> constants(uint32_t localSizeX, uint32_t localSizeY) const;
    std::string describe() const; // e.g. "triangles diffuse emitters nee mis rr cosine-sampling"
};

// One row of the table, for listings and checks.
struct FeatureInfo {
    const char* field;    // FeatureSet's member
    const char* constant; // the GLSL constant
    uint32_t id;          // its constant_id
    const char* description;
};
std::span<const FeatureInfo> featureTable();

FeatureSet computeFeatures(const FlatScene& scene, const IntegratorSettings& settings);

} // namespace pt
