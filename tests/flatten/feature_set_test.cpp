// The kernel feature table (shaders/shared/features.h) and what FeatureSet derives from it.
#include "flatten/feature_set.h"
#include "flatten/flat_scene.h"
#include "scene/default_scene.h"
#include "shared/layout.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace {

using namespace pt;

TEST(FeatureTable, ConstantIdsAreUniqueAndClearOfTheWorkgroupSize) {
    std::set<uint32_t> ids{SPEC_LOCAL_SIZE_X, SPEC_LOCAL_SIZE_Y};
    std::set<std::string> names;
    for (const FeatureInfo& row : featureTable()) {
        EXPECT_TRUE(ids.insert(row.id).second) << row.field << " reuses constant_id " << row.id;
        EXPECT_TRUE(names.insert(row.constant).second) << row.constant;
        EXPECT_GT(std::string(row.description).size(), 10u) << row.field << " needs a description";
    }
    // One constant per row, plus the workgroup size, all distinct.
    const std::vector<SpecializationConstant> constants = FeatureSet{}.constants(8, 8);
    ASSERT_EQ(constants.size(), featureTable().size() + 2);
    std::set<uint32_t> constantIds;
    for (const SpecializationConstant& c : constants) EXPECT_TRUE(constantIds.insert(c.id).second) << c.id;
}

// (Through its tree, whose nodes and triangles are read as texels: texel-loads; with --bvh auto
// its 32 triangles are few enough to be tested without a tree: all-triangles.)
TEST(FeatureTable, TheCornellBoxNeedsTrianglesDiffuseAndEmitters) {
    const FlatScene box = flattenScene(loadDefaultScene());
    EXPECT_EQ(computeFeatures(box, IntegratorSettings{}).describe(),
        "triangles diffuse emitters nee mis rr cosine-sampling sobol texel-loads");
    IntegratorSettings classic;
    classic.classic = true; // the course's ray tracer samples lights everywhere, no MIS or roulette
    EXPECT_EQ(computeFeatures(box, classic).describe(),
        "classic triangles diffuse emitters nee cosine-sampling sobol texel-loads");
    IntegratorSettings plain;
    plain.nee = false; // MIS needs NEE
    plain.sampling = DirectionSampling::Uniform;
    plain.sampler = SamplerKind::Independent;
    EXPECT_EQ(computeFeatures(box, plain).describe(), "triangles diffuse emitters rr uniform-sampling texel-loads");
    plain.alwaysTree = false; // --bvh auto: no tree for a tiny scene, and no texels to read
    EXPECT_EQ(computeFeatures(box, plain).describe(), "triangles diffuse emitters rr uniform-sampling all-triangles");
    plain.alwaysTree = true;
    plain.texelLoads = false; // --texel-loads off: the same image through buffer addresses
    EXPECT_EQ(computeFeatures(box, plain).describe(), "triangles diffuse emitters rr uniform-sampling");
}

// A material no object uses costs nothing: the Cornell box with an unused glass, an unused
// emitter and an unused textured material compiles as the box alone; given to a triangle, each
// brings its feature in.
TEST(FeatureTable, MaterialsNoObjectUsesAreLeftOut) {
    Scene scene = loadDefaultScene();
    const std::string alone = computeFeatures(flattenScene(scene), IntegratorSettings{}).describe();
    Material glass;
    glass.type = MaterialType::Dielectric;
    Material lamp;
    lamp.emission = glm::vec3(5.0f);
    scene.materials.push_back(glass);
    scene.materials.push_back(lamp);
    // The box's own lamp made black, so that "emitters" comes from the unused lamp alone.
    for (Material& m : scene.materials)
        if (&m != &scene.materials.back()) m.emission = glm::vec3(0.0f);
    scene.punctualLights.push_back(PunctualLight{}); // the box still needs a light
    const FlatScene unused = flattenScene(scene);
    const std::string described = computeFeatures(unused, IntegratorSettings{}).describe();
    EXPECT_EQ(described.find("dielectric"), std::string::npos) << described;
    EXPECT_EQ(described.find("emitters"), std::string::npos) << described;
    ASSERT_FALSE(scene.meshes.empty());
    scene.meshes[0].material = static_cast<uint32_t>(scene.materials.size() - 2); // the glass
    scene.meshes[1].material = static_cast<uint32_t>(scene.materials.size() - 1); // the lamp
    const std::string used = computeFeatures(flattenScene(scene), IntegratorSettings{}).describe();
    EXPECT_NE(used.find("dielectric"), std::string::npos) << used;
    EXPECT_NE(used.find("emitters"), std::string::npos) << used;
    EXPECT_NE(alone.find("emitters"), std::string::npos) << alone;
}

// The light tree under `--light-tree auto`: not for the box's one quad light (two triangles side by
// side, facing one way: the power CDF does as well for less), but once a second light sits far
// from it; `on` and `off` decide it, and BDPT's light sampling takes it as the path tracer's does.
TEST(FeatureTable, LightTreeWhereLightsSpreadOverTheScene) {
    Scene scene = loadDefaultScene();
    auto hasTree = [](const Scene& sc, const IntegratorSettings& s) {
        return computeFeatures(flattenScene(sc), s).describe().find("light-tree") != std::string::npos;
    };
    IntegratorSettings automatic, on, off, bdpt;
    on.lightSelection = LightSelection::Tree;
    off.lightSelection = LightSelection::Power;
    bdpt.estimator = Estimator::Bidirectional;
    EXPECT_FALSE(hasTree(scene, automatic));
    EXPECT_TRUE(hasTree(scene, on));
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const Mesh& m : scene.meshes)
        for (const glm::vec3& p : m.positions) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
    PunctualLight corner;
    corner.position = lo + 0.05f * (hi - lo);
    corner.intensity = glm::vec3(1.0f);
    scene.punctualLights.push_back(corner);
    EXPECT_TRUE(hasTree(scene, automatic));
    EXPECT_FALSE(hasTree(scene, off));
    EXPECT_TRUE(hasTree(scene, bdpt));
    bdpt.lightSelection = LightSelection::Power;
    EXPECT_FALSE(hasTree(scene, bdpt));
}

// Light tracing renders only caustics through delta surfaces: a box whose one specular surface is
// rough has none, and the light paths would be traced for nothing.
TEST(FeatureTable, LightTracingNeedsASmoothSpecularSurfaceAndAReceiver) {
    FlatScene box = flattenScene(loadDefaultScene());
    ASSERT_GE(box.materials.size(), 2u);
    EXPECT_FALSE(computeFeatures(box, IntegratorSettings{}).lightTracing); // diffuse only: no caustics
    for (uint32_t type : {MATERIAL_MIRROR, MATERIAL_CONDUCTOR, MATERIAL_DIELECTRIC}) {
        box.materials[0].type = type;
        box.materials[0].alpha = 0.0f;
        EXPECT_TRUE(computeFeatures(box, IntegratorSettings{}).lightTracing) << "smooth type " << type;
        box.materials[0].alpha = 0.1f;
        EXPECT_FALSE(computeFeatures(box, IntegratorSettings{}).lightTracing) << "rough type " << type;
    }
    // Smooth glass with nothing but glass and rough glass around it: no receiver.
    for (auto& m : box.materials) {
        m.type = MATERIAL_DIELECTRIC;
        m.alpha = 0.1f;
    }
    box.materials[0].alpha = 0.0f;
    EXPECT_FALSE(computeFeatures(box, IntegratorSettings{}).lightTracing);
    box.materials[1].type = MATERIAL_MIRROR; // a rough Schlick metal receives
    EXPECT_TRUE(computeFeatures(box, IntegratorSettings{}).lightTracing);
}

// The glTF layers (coat, sheen, thin film) are compiled in only where a metallic-roughness
// material has them: a zero factor or a zero sheen colour is no layer, and other material types
// ignore the fields.
TEST(FeatureTable, ClearcoatSheenAndIridescenceOnlyWhereAPbrMaterialHasThem) {
    FlatScene box = flattenScene(loadDefaultScene());
    box.materials[0].type = MATERIAL_PBR;
    auto decide = [&] { return computeFeatures(box, IntegratorSettings{}); };
    EXPECT_TRUE(decide().pbr);
    EXPECT_FALSE(decide().clearcoat || decide().sheen);
    box.materials[0].clearcoat = 0.5f;
    EXPECT_TRUE(decide().clearcoat);
    EXPECT_FALSE(decide().sheen);
    box.materials[0].sheenColor = glm::vec3(0.0f, 0.1f, 0.0f);
    EXPECT_TRUE(decide().sheen);
    EXPECT_FALSE(decide().iridescence);
    box.materials[0].iridescence = 1.0f;
    EXPECT_TRUE(decide().iridescence);
    box.materials[0].type = MATERIAL_DIFFUSE;
    EXPECT_FALSE(decide().clearcoat || decide().sheen || decide().iridescence) << "only the full model has layers";
    const FeatureSet all = FeatureSet::all(IntegratorSettings{});
    EXPECT_TRUE(all.clearcoat && all.sheen && all.iridescence);
}

// Dispersion is compiled in where a dielectric or a glTF transmission has it, and then light
// tracing, which does not carry a wavelength, leaves the caustics to the path tracer.
TEST(FeatureTable, DispersionOnlyWhereGlassHasItAndWithoutLightTracing) {
    FlatScene box = flattenScene(loadDefaultScene());
    box.materials[0].type = MATERIAL_DIELECTRIC;
    box.materials[0].alpha = 0.0f;
    EXPECT_FALSE(computeFeatures(box, IntegratorSettings{}).dispersion);
    EXPECT_TRUE(computeFeatures(box, IntegratorSettings{}).lightTracing);
    box.materials[0].dispersion = 0.5f;
    EXPECT_TRUE(computeFeatures(box, IntegratorSettings{}).dispersion);
    EXPECT_FALSE(computeFeatures(box, IntegratorSettings{}).lightTracing);
    box.materials[0].type = MATERIAL_DIFFUSE;
    EXPECT_FALSE(computeFeatures(box, IntegratorSettings{}).dispersion);
}

TEST(FeatureTable, AllCompilesEverySceneFeatureAndKeepsTheSwitches) {
    IntegratorSettings s;
    s.mis = false;
    const FeatureSet all = FeatureSet::all(s);
    EXPECT_TRUE(all.diffuse && all.dielectric && all.textures && all.motion && all.environment);
    EXPECT_TRUE(all.nee);
    EXPECT_FALSE(all.mis);
    EXPECT_FALSE(all.lightTracing); // decided by the scene, never compiled in by all()
    EXPECT_FALSE(all.texelLoads);   // a scene's texel views are bound only by its renderer
    EXPECT_FALSE(all.classic);
    EXPECT_EQ(all.debugView, DEBUG_VIEW_NONE);
    // The constants carry each field's value.
    for (const SpecializationConstant& c : all.constants(8, 4)) {
        if (c.id == SPEC_LOCAL_SIZE_Y) EXPECT_EQ(c.value, 4u);
    }
}

} // namespace
