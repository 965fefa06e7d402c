// glTF KHR_lights_punctual: point, spot and directional lights with their units and node
// transforms, the range noted, bad lights errors.
#include "gltf_test_documents.h"
#include "scene/scene_error.h"

#include <cmath>
#include <sstream>

namespace pt::test::gltf {
namespace {

TEST(GltfLoaderLights, PunctualLightsWithUnitsAndNodeTransforms) {
    const float h = std::sqrt(0.5f);
    std::ostringstream nodes;
    // Point at (1, 2, 3); spot at (0, 5, 0) turned by -90 degrees about x (its -z axis looks
    // down, to -y); directional rotated 90 degrees about y (its -z becomes -x); a light under a
    // translated parent inherits the parent's transform.
    nodes << R"({"translation": [1, 2, 3], "extensions": {"KHR_lights_punctual": {"light": 0}}},
      {"translation": [0, 5, 0], "rotation": [)"
          << -h << ", 0, 0, " << h << R"(], "extensions": {"KHR_lights_punctual": {"light": 1}}},
      {"rotation": [0, )"
          << h << ", 0, " << h << R"(], "extensions": {"KHR_lights_punctual": {"light": 2}}},
      {"translation": [10, 0, 0], "children": [)"
          << 5 << R"(]})";
    // (The child node 5, listed after these, is not a scene root: the helper makes every
    // top-level object of the list a root, so it is added by hand below.)
    std::string doc = materialDocument(R"([{"name": "grey"}])", 1, R"([
      {"type": "point", "color": [1, 0.5, 0.25], "intensity": 40, "range": 0},
      {"type": "spot", "intensity": 100, "spot": {"innerConeAngle": 0.3, "outerConeAngle": 0.6}},
      {"type": "directional", "color": [0.5, 0.5, 1], "intensity": 3},
      {"type": "point", "intensity": 2}
    ])",
        nodes.str());
    // Add node 5 (a point light at the parent's origin plus (0, 1, 0)) without making it a root.
    const std::string lastNode = R"("children": [5]})";
    doc.insert(doc.find(lastNode) + lastNode.size(),
        R"(, {"translation": [0, 1, 0], "extensions": {"KHR_lights_punctual": {"light": 3}}})");
    const pt::Scene s = loadText(doc);
    ASSERT_EQ(s.punctualLights.size(), 4u);
    const pt::PunctualLight& point = s.punctualLights[0];
    EXPECT_EQ(point.type, pt::PunctualLight::Type::Point);
    EXPECT_TRUE(near3(point.position, glm::vec3(1, 2, 3), 1e-6f));
    // Candela read as W/sr, times the colour.
    EXPECT_TRUE(near3(point.intensity, glm::vec3(40.0f, 20.0f, 10.0f), 1e-5f));

    const pt::PunctualLight& spot = s.punctualLights[1];
    EXPECT_EQ(spot.type, pt::PunctualLight::Type::Spot);
    EXPECT_TRUE(near3(spot.position, glm::vec3(0, 5, 0), 1e-6f));
    EXPECT_TRUE(near3(spot.direction, glm::vec3(0, -1, 0), 1e-5f));
    EXPECT_TRUE(near3(spot.intensity, glm::vec3(100.0f), 1e-4f));
    EXPECT_NEAR(spot.cosCoverage, std::cos(0.6f), 1e-6f);
    // glTF's edge exactly: t^2 between the inner and the outer cone.
    EXPECT_NEAR(spot.cosFalloff, std::cos(0.3f), 1e-6f);
    EXPECT_FLOAT_EQ(spot.falloffExponent, 2.0f);

    const pt::PunctualLight& sun = s.punctualLights[2];
    EXPECT_EQ(sun.type, pt::PunctualLight::Type::Directional);
    EXPECT_TRUE(near3(sun.direction, glm::vec3(-1, 0, 0), 1e-5f));
    // Lux read as irradiance (W/m^2), times the colour.
    EXPECT_TRUE(near3(sun.intensity, glm::vec3(1.5f, 1.5f, 3.0f), 1e-5f));

    EXPECT_TRUE(near3(s.punctualLights[3].position, glm::vec3(10, 1, 0), 1e-6f)) << "the parent's transform applies";
    EXPECT_TRUE(s.unsupported.empty()) << s.unsupported.front();
}

TEST(GltfLoaderLights, RangeIsNotedAndBadLightsAreErrors) {
    const std::string node = R"({"extensions": {"KHR_lights_punctual": {"light": 0}}})";
    const pt::Scene ranged =
        loadText(materialDocument(R"([{}])", 1, R"([{"type": "point", "intensity": 1, "range": 5}])", node));
    ASSERT_EQ(ranged.punctualLights.size(), 1u);
    ASSERT_EQ(ranged.unsupported.size(), 1u);
    EXPECT_NE(ranged.unsupported[0].find("range"), std::string::npos) << ranged.unsupported[0];

    // A colour that is not an RGB triple: white, the extension's default, and a note.
    const pt::Scene odd =
        loadText(materialDocument(R"([{}])", 1, R"([{"type": "point", "intensity": 2, "color": [1, 0]}])", node));
    ASSERT_EQ(odd.punctualLights.size(), 1u);
    EXPECT_TRUE(near3(odd.punctualLights[0].intensity, glm::vec3(2.0f), 0.0f));
    EXPECT_EQ(odd.unsupported, std::vector<std::string>{"light 0: color is not 3 numbers (1 1 1 assumed)"});

    EXPECT_THROW(
        loadText(materialDocument(R"([{}])", 1, R"([{"type": "point", "intensity": -1}])", node)), pt::SceneError);
    EXPECT_THROW(loadText(materialDocument(R"([{}])", 1,
                     R"([{"type": "spot", "spot": {"innerConeAngle": 0.8, "outerConeAngle": 0.5}}])", node)),
        pt::SceneError);
    EXPECT_THROW(loadText(materialDocument(R"([{}])", 1, R"([{"type": "point"}])",
                     R"({"extensions": {"KHR_lights_punctual": {"light": 3}}})")),
        pt::SceneError);
}
} // namespace
} // namespace pt::test::gltf
