#include "flatten/feature_set.h"

#include "shared/layout.h"

#include <cmath>
#include <initializer_list>
#include <numbers>
#include <sstream>

namespace pt {

std::string IntegratorSettings::describe() const {
    std::ostringstream s;
    if (classic)
        s << "integrator=classic ";
    else
        s << "integrator="
          << (estimator == Estimator::Path               ? "path"
                 : estimator == Estimator::Bidirectional ? "bdpt"
                 : estimator == Estimator::VertexMerging ? "vcm"
                                                         : "auto")
          << ' ';
    s << "nee=" << (nee ? "on" : "off") << " mis=" << (mis ? "on" : "off") << " rr=" << (rr ? "on" : "off")
      << " sampling=" << (sampling == DirectionSampling::Cosine ? "cosine" : "uniform")
      << " sampler=" << (sampler == SamplerKind::Sobol ? "sobol" : "independent") << " max-depth=" << maxDepth
      << " rr-start=" << rrStartDepth << " rr-threshold=" << rrThreshold
      << " light-tracing=" << (lightTracing ? "on" : "off") << " light-tree="
      << (lightSelection == LightSelection::Tree       ? "on"
             : lightSelection == LightSelection::Power ? "off"
                                                       : "auto")
      << " seed=" << seed;
    if (!alwaysTree) s << " bvh=auto";
    if (sharedSamples) s << " shared-samples=on";
    // Where vertex merging may render it: its radius and how fast it shrinks change the image.
    if (!classic && (estimator == Estimator::Auto || estimator == Estimator::VertexMerging))
        s << " merge-radius=" << mergeRadius << " merge-alpha=" << mergeAlpha;
    return s.str();
}

namespace {

// ---- The predicates the table's `decide` column uses ----

// The materials some object uses (FlatScene::materialUsed; every one where it was not recorded).
struct UsedMaterials {
    const FlatScene& scene;
    struct Iterator {
        const FlatScene& scene;
        size_t i;
        void skipUnused() {
            while (i < scene.materials.size() && !scene.materialUsed.empty() && !scene.materialUsed[i]) ++i;
        }
        const gpu::GpuMaterial& operator*() const { return scene.materials[i]; }
        Iterator& operator++() {
            ++i;
            skipUnused();
            return *this;
        }
        bool operator!=(const Iterator& other) const { return i != other.i; }
    };
    Iterator begin() const {
        Iterator it{scene, 0};
        it.skipUnused();
        return it;
    }
    Iterator end() const { return Iterator{scene, scene.materials.size()}; }
};

UsedMaterials usedMaterials(const FlatScene& scene) { return UsedMaterials{scene}; }

bool usesMaterialType(const FlatScene& scene, uint32_t type) {
    for (const auto& m : usedMaterials(scene))
        if (m.type == type) return true;
    return false;
}

bool usesMaterialFlag(const FlatScene& scene, uint32_t flag) {
    for (const auto& m : usedMaterials(scene))
        if ((m.flags & flag) != 0u) return true;
    return false;
}

// Mirrors, conductors and dielectrics: smooth (delta) with alpha 0, GGX-rough above
// (shared/layout.h: MIN_ROUGH_ALPHA).
bool isMicrofacetCapable(const gpu::GpuMaterial& m) {
    return m.type == MATERIAL_MIRROR || m.type == MATERIAL_CONDUCTOR || m.type == MATERIAL_DIELECTRIC;
}

bool usesRoughConductorOrDielectric(const FlatScene& scene) {
    for (const auto& m : usedMaterials(scene))
        if (isMicrofacetCapable(m) && m.alpha > 0.0f) return true;
    return false;
}

// The specular chain's vertices (shaders/integrator/caustic_partition.glsl): every lobe a delta.
bool usesDeltaMaterial(const FlatScene& scene) {
    for (const auto& m : usedMaterials(scene))
        if (isMicrofacetCapable(m) && m.alpha <= 0.0f) return true;
    return false;
}

// Where a light path meets the camera (caustic_partition.glsl's isCausticReceiver).
bool usesCausticReceiver(const FlatScene& scene) {
    for (const auto& m : usedMaterials(scene)) {
        if ((m.flags & MATERIAL_FLAG_UNLIT) != 0u) continue;
        if (m.type == MATERIAL_DIFFUSE || m.type == MATERIAL_GLOSSY) return true;
        if ((m.type == MATERIAL_MIRROR || m.type == MATERIAL_CONDUCTOR) && m.alpha > 0.0f) return true;
    }
    return false;
}

bool usesDiffuseTransmission(const FlatScene& scene) {
    for (const auto& m : usedMaterials(scene))
        if (m.type == MATERIAL_PBR && (m.diffuseTransmission > 0.0f || m.diffuseTransmissionTexture != NO_TEXTURE))
            return true;
    return false;
}

bool usesClearcoat(const FlatScene& scene) {
    for (const auto& m : usedMaterials(scene))
        if (m.type == MATERIAL_PBR && m.clearcoat > 0.0f) return true;
    return false;
}

bool usesSheen(const FlatScene& scene) {
    for (const auto& m : usedMaterials(scene))
        if (hasSheen(m)) return true;
    return false;
}

bool usesIridescence(const FlatScene& scene) {
    for (const auto& m : usedMaterials(scene))
        if (m.type == MATERIAL_PBR && m.iridescence > 0.0f) return true;
    return false;
}

bool usesAnisotropy(const FlatScene& scene) {
    for (const auto& m : usedMaterials(scene))
        if (m.type == MATERIAL_PBR && m.anisotropy > 0.0f) return true;
    return false;
}

bool usesDispersion(const FlatScene& scene) {
    for (const auto& m : usedMaterials(scene))
        if ((m.type == MATERIAL_DIELECTRIC || m.type == MATERIAL_PBR) && m.dispersion > 0.0f) return true;
    return false;
}

bool usesEmission(const FlatScene& scene) {
    for (const auto& m : usedMaterials(scene)) {
        if (m.emissiveTexture != NO_TEXTURE || (m.flags & MATERIAL_FLAG_UNLIT) != 0u) return true;
        if (m.emission.x > 0 || m.emission.y > 0 || m.emission.z > 0) return true;
    }
    return false;
}

// Any material slot (or the course's background texture) reading an image texture
// (image = true) or a procedural one (image = false).
// Some receiver sees a triangle emitter under a solid angle worth sampling directly
// (lights/light_table.h); instanced triangles, in object space, are not receivers here.
bool usesSphericalTriangleSampling(const FlatScene& scene) {
    size_t world = scene.triangles.size();
    for (const gpu::GpuInstance& i : scene.instances) world = std::min<size_t>(world, i.firstTriangle);
    return someReceiverSeesALargeTriangleLight(scene.triangles, world);
}

bool usesTextureKind(const FlatScene& scene, bool image) {
    auto matches = [&](uint32_t slot) {
        return slot != NO_TEXTURE && (scene.textures[slot].type == TEXTURE_IMAGE) == image;
    };
    for (const auto& m : usedMaterials(scene))
        for (uint32_t slot : materialTextureSlots(m))
            if (matches(slot)) return true;
    return matches(scene.backgroundTexture);
}

bool usesNormalMaps(const FlatScene& scene) {
    for (const auto& m : usedMaterials(scene))
        if (m.normalTexture != NO_TEXTURE) return true;
    return false;
}

bool usesTriangleFlag(const FlatScene& scene, uint32_t flag) {
    for (const auto& t : scene.triangles)
        if ((t.flags & flag) != 0u) return true;
    return false;
}

bool hasLightOfType(const FlatScene& scene, std::initializer_list<uint32_t> types) {
    for (const auto& l : scene.lights.lights)
        for (uint32_t type : types)
            if (l.type == type) return true;
    return false;
}

bool hasPunctualLights(const FlatScene& scene) {
    return hasLightOfType(scene, {LIGHT_POINT, LIGHT_DIRECTIONAL, LIGHT_SPOT, LIGHT_SQUARE});
}

bool neeUseful(const FlatScene& scene, const IntegratorSettings& s, const FeatureSet& f) {
    const bool lights = !scene.lights.lights.empty();
    if (f.classic) return lights;
    return s.nee && lights && (f.diffuse || f.glossy || f.pbr || f.microfacet);
}

// Bidirectional path tracing can render the scene: not for the classic ray tracer, nor through
// dispersive glass (the two subpaths would need one wavelength), nor paths longer than the light
// vertices a sample keeps (BDPT_MAX_LIGHT_VERTICES, plus the camera segment and a connection).
bool bdptPossible(const FlatScene& scene, const IntegratorSettings& s, const FeatureSet& f) {
    return !f.classic && !f.dispersion && !scene.lights.lights.empty() && s.maxDepth <= BDPT_MAX_LIGHT_VERTICES + 2;
}

// Under `auto`, where light sampling at the surfaces the camera sees finds its light less often
// than kBdptBelowLightVisibility (measured on the device, FlatScene::lightVisibility): light that
// arrives through a gap, a shade or glass, which unidirectional paths find by chance and light
// subpaths carry to them.
bool lightMostlyHidden(const FlatScene& scene) {
    return scene.lightVisibility && *scene.lightVisibility < kBdptBelowLightVisibility;
}

// `--integrator bdpt` where possible; under `auto`, where the light is mostly hidden or where
// glossy caustics are common (FlatScene::glossyCausticBounces: light that a rough gold or glass
// block focuses onto diffuse surfaces, which a light subpath's connection to the camera carries).
bool bdptChosen(const FlatScene& scene, const IntegratorSettings& s, const FeatureSet& f) {
    if (s.estimator == Estimator::Path || !bdptPossible(scene, s, f)) return false;
    if (s.estimator == Estimator::Bidirectional || s.estimator == Estimator::VertexMerging) return true;
    return lightMostlyHidden(scene) ||
           (scene.glossyCausticBounces && *scene.glossyCausticBounces >= kBdptFromGlossyCausticBounces);
}

// Vertex merging over BDPT (integrator/vcm.glsl): for `--integrator vcm`, and under auto where
// the light is mostly hidden (on both such scenes, Veach Ajar and the two rooms of scenes/ajar,
// merging had 2-5x lower error than BDPT at equal time; bench/RESULTS.md). Not where BDPT was
// chosen for glossy caustics alone: connections carry those, and on four of five such boxes
// merging's cost outweighed what it added (bench/RESULTS.md, "Glossy caustics choose BDPT"). Not
// with moving objects (a round's light subpaths would be merged across shutter times), nor deeper
// than the light vertices a pixel keeps.
bool mergingChosen(const FlatScene& scene, const IntegratorSettings& s, const FeatureSet& f) {
    if (!f.bdpt || f.motion || s.maxDepth > BDPT_MAX_LIGHT_VERTICES + 1) return false;
    return s.estimator == Estimator::VertexMerging || (s.estimator == Estimator::Auto && lightMostlyHidden(scene));
}

// Light tracing pays only where caustics can be seen directly: a smooth (delta) mirror, conductor or
// dielectric (a rough one ends the specular chain, and the path tracer has those paths), a receiver
// and an area emitter. Left to the path tracer: absorbing interiors, cut-outs, moving objects and
// dispersive glass (the light path does not model them).
bool lightTracingPays(const FlatScene& scene, const IntegratorSettings& s, const FeatureSet& f) {
    return s.lightTracing && !f.classic && !f.bdpt && hasLightOfType(scene, {LIGHT_TRIANGLE, LIGHT_SPHERE}) &&
           usesDeltaMaterial(scene) && usesCausticReceiver(scene) && !f.absorption && !f.alpha && !f.motion &&
           !f.dispersion;
}

// The light tree pays where which light matters depends on where the shading point is: lights
// spread over more than kLightTreeSpread of the scene's diagonal, or facing more ways than a cone
// of kLightTreeConeDegrees. On the Cornell box (one quad light, two triangles side by side) it
// cost 8% of the paths per second and gained nothing; in a hall of 184 lamps it had 2.8x lower
// relMSE per sample (bench/RESULTS.md, "The light tree").
constexpr float kLightTreeSpread = 0.25f;
constexpr double kLightTreeConeDegrees = 30.0;

bool lightTreePays(const FlatScene& scene) {
    const gpu::GpuLightTreeNode& root = scene.lights.tree.nodes.at(0);
    if (root.cosThetaO < std::cos(kLightTreeConeDegrees * std::numbers::pi / 180.0)) return true;
    const Aabb box = sceneBounds(scene);
    return !box.empty() &&
           glm::length(root.boundsMax - root.boundsMin) > kLightTreeSpread * glm::length(box.hi - box.lo);
}

// The light tree chooses among the bounded lights where the scene has one (two or more of them,
// FlatScene::lights.tree), light sampling is on and (under auto) it pays. In BDPT it chooses for
// light sampling at camera vertices; light subpaths start from lights chosen by power.
bool lightTreeChosen(const FlatScene& scene, const IntegratorSettings& s, const FeatureSet& f) {
    if (s.lightSelection == LightSelection::Power || !f.nee || f.classic) return false;
    if (scene.lights.tree.nodes.empty()) return false;
    return s.lightSelection == LightSelection::Tree || lightTreePays(scene);
}

bool hasTriangleTree(const FlatScene& scene) { return !scene.nodes.empty() || !scene.quantizedNodes.empty(); }
bool hasSphereTree(const FlatScene& scene) { return !scene.sphereNodes.empty(); }

uint32_t nodeFormatOf(const FlatScene& scene) {
    return scene.quantizedNodes.empty() ? BVH_NODES_FLOAT : BVH_NODES_QUANTIZED;
}

// With `--bvh auto` a tiny scene's triangles are all tested against each ray, from a uniform
// buffer, without the tree: on lavapipe 1.10-1.13x the paths per second of the four-wide tree at
// 32 triangles (the diffuse box), 0.73x at 82 (bench/RESULTS.md, "Tiny scenes without a tree"),
// hence UNIFORM_TRIANGLES_MAX = 48. Since the tree's least-cost collapse and texel loads the tree
// is faster there too, so it is no longer the default ("Geometry read through texel buffers").
// Instanced meshes keep their trees (the ray changes space per instance).
uint32_t uniformTriangleCount(const FlatScene& scene, const IntegratorSettings& s, const FeatureSet& f) {
    if (s.alwaysTree || scene.triangles.empty() || scene.triangles.size() > UNIFORM_TRIANGLES_MAX) return 0;
    // Not in the bidirectional kernels: with a dozen trace calls, each inlined with every triangle
    // unrolled, lavapipe took 3x as long to compile them (8 -> 24 s for the rough box).
    if (f.bdpt) return 0;
    if (!scene.instances.empty()) return 0;
    return static_cast<uint32_t>(scene.triangles.size());
}

uint32_t samplerOf(const IntegratorSettings& s) {
    return s.sampler == SamplerKind::Sobol ? SAMPLER_SOBOL : SAMPLER_INDEPENDENT;
}

constexpr FeatureInfo kFeatureTable[] = {
#define PT_FEATURE_INFO(field, kind, NAME, id, unspecialised, all, decide, log, description)                           \
    {#field, #NAME, id, description},
    PT_FEATURES(PT_FEATURE_INFO)
#undef PT_FEATURE_INFO
};

} // namespace

std::span<const FeatureInfo> featureTable() { return kFeatureTable; }

FeatureSet FeatureSet::all(const IntegratorSettings& s) {
    FeatureSet f;
#define PT_FEATURE_ALL(field, kind, NAME, id, unspecialised, all, decide, log, description) f.field = all;
    PT_FEATURES(PT_FEATURE_ALL)
#undef PT_FEATURE_ALL
    return f;
}

FeatureSet computeFeatures(const FlatScene& scene, const IntegratorSettings& s) {
    FeatureSet f;
#define PT_FEATURE_DECIDE(field, kind, NAME, id, unspecialised, all, decide, log, description) f.field = decide;
    PT_FEATURES(PT_FEATURE_DECIDE)
#undef PT_FEATURE_DECIDE
    return f;
}

std::vector<SpecializationConstant> FeatureSet::constants(uint32_t localSizeX, uint32_t localSizeY) const {
    std::vector<SpecializationConstant> c{{SPEC_LOCAL_SIZE_X, localSizeX}, {SPEC_LOCAL_SIZE_Y, localSizeY}};
#define PT_FEATURE_CONSTANT(field, kind, NAME, id, unspecialised, all, decide, log, description)                       \
    c.push_back({id, static_cast<uint32_t>(field)});
    PT_FEATURES(PT_FEATURE_CONSTANT)
#undef PT_FEATURE_CONSTANT
    return c;
}

std::string FeatureSet::describe() const {
    std::string s;
    auto add = [&](const char* word) {
        if (word == nullptr) return;
        if (!s.empty()) s += ' ';
        s += word;
    };
#define PT_FEATURE_LOG(field, kind, NAME, id, unspecialised, all, decide, log, description)                            \
    {                                                                                                                  \
        [[maybe_unused]] const auto v = field;                                                                         \
        add(log);                                                                                                      \
    }
    PT_FEATURES(PT_FEATURE_LOG)
#undef PT_FEATURE_LOG
    return s;
}

} // namespace pt
