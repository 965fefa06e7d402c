// --texel-loads auto: on a CPU device the faster of texel and address loads is measured once and
// remembered in the pipeline cache's folder; a damaged answer is measured again; without the folder
// nothing is chosen (texel loads stay on).
#include "gpu/shader_cache_directory.h"
#include "render/texel_load_choice.h"
#include "scene/scene_loader.h"
#include "support/gpu_test_support.h"
#include "support/test_directory.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>

namespace pt::test {
namespace {

namespace fs = std::filesystem;

ContextOptions optionsWithCache(const fs::path& folder) {
    ContextOptions o;
    o.validation = true;
    o.pipelineCacheDirectory = folder;
    return o;
}

TEST(TexelLoadChoice, MeasuredOnceThenRememberedAndMeasuredAgainWhenDamaged) {
    const fs::path folder = freshTestDirectory("texel_choice");
    VulkanContext context(optionsWithCache(folder));
    ASSERT_EQ(context.properties().deviceType, VK_PHYSICAL_DEVICE_TYPE_CPU) << "the suite runs on lavapipe";

    const std::optional<TexelLoadChoice> first = chooseTexelLoads(context);
    ASSERT_TRUE(first.has_value());
    EXPECT_TRUE(first->measuredNow);
    EXPECT_GT(first->texelSeconds, 0.0);
    EXPECT_GT(first->addressSeconds, 0.0);
    EXPECT_EQ(first->texelLoads, first->texelSeconds <= first->addressSeconds) << "the faster one is chosen";

    const std::optional<TexelLoadChoice> second = chooseTexelLoads(context);
    ASSERT_TRUE(second.has_value());
    EXPECT_FALSE(second->measuredNow) << "the answer is read back, not measured again";
    EXPECT_EQ(second->texelLoads, first->texelLoads);
    EXPECT_DOUBLE_EQ(second->texelSeconds, first->texelSeconds);
    EXPECT_DOUBLE_EQ(second->addressSeconds, first->addressSeconds);
    EXPECT_NE(describeTexelLoadChoice(*second).find("measured earlier"), std::string::npos);

    // A damaged file reads as absent: measured again.
    const fs::path file = ShaderCacheDirectory(folder).fileOf("texel-loads");
    ASSERT_TRUE(fs::exists(file));
    std::ofstream(file, std::ios::binary | std::ios::trunc) << "not an answer";
    const std::optional<TexelLoadChoice> third = chooseTexelLoads(context);
    ASSERT_TRUE(third.has_value());
    EXPECT_TRUE(third->measuredNow);
    EXPECT_EQ(context.validationMessageCount(), 0u) << context.firstValidationMessage();
    std::error_code ec;
    fs::remove_all(folder, ec);
}

TEST(TexelLoadChoice, NothingChosenWithoutACacheFolder) {
    VulkanContext context(optionsWithCache({}));
    EXPECT_FALSE(chooseTexelLoads(context).has_value());
}

// The suite's own choice (suiteTexelLoads): made by the first test process that renders (the fixture
// GpuSuite.GeometryLoadsChosen runs this test before the others) and read back by every later one
// from the tests' pipeline-cache folder.
TEST(TexelLoadChoice, TheSuitesChoiceIsMadeOnceForAllItsProcesses) {
    const bool texel = suiteTexelLoads();
    const std::optional<TexelLoadChoice> again = chooseTexelLoads(sharedContext());
    ASSERT_TRUE(again.has_value()) << "lavapipe with the tests' pipeline-cache folder has a choice to make";
    EXPECT_FALSE(again->measuredNow) << "remembered for the suite's other processes";
    EXPECT_EQ(again->texelLoads, texel);
    EXPECT_EQ(suiteFeatures(flattenScene(loadScene("")), IntegratorSettings{}).texelLoads, texel);
}

} // namespace
} // namespace pt::test
