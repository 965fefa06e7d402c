// specializeSpirv on the host: constants land where a VkSpecializationInfo would put them, code
// they disable is gone, and the production kernels stay valid SPIR-V for every kind of scene.
#include "flatten/feature_set.h"
#include "gpu/spirv_specialization.h"
#include "pt_render_light_tracing_spv.h"
#include "pt_render_spv.h"

#include <gtest/gtest.h>
#include <spirv-tools/libspirv.hpp>

#include <string>

namespace pt::test {
namespace {

// A compute shader with one constant of each kind; main stores a value chosen by them.
const char* kModule = R"(
               OpCapability Shader
               OpMemoryModel Logical GLSL450
               OpEntryPoint GLCompute %main "main"
               OpExecutionMode %main LocalSize 1 1 1
               OpName %out "out"
               OpDecorate %flagOn SpecId 3
               OpDecorate %flagOff SpecId 4
               OpDecorate %count SpecId 7
               OpDecorate %untouched SpecId 9
       %void = OpTypeVoid
       %bool = OpTypeBool
       %uint = OpTypeInt 32 0
     %fnvoid = OpTypeFunction %void
     %flagOn = OpSpecConstantTrue %bool
    %flagOff = OpSpecConstantFalse %bool
      %count = OpSpecConstant %uint 5
  %untouched = OpSpecConstant %uint 11
     %uint_1 = OpConstant %uint 1
    %uint_2 = OpConstant %uint 2
%ptr_private = OpTypePointer Private %uint
        %out = OpVariable %ptr_private Private
       %sum = OpSpecConstantOp %uint IAdd %count %untouched
       %main = OpFunction %void None %fnvoid
      %entry = OpLabel
               OpSelectionMerge %merge None
               OpBranchConditional %flagOn %taken %other
      %taken = OpLabel
               OpStore %out %sum
               OpBranch %merge
      %other = OpLabel
               OpStore %out %uint_2
               OpBranch %merge
      %merge = OpLabel
               OpSelectionMerge %merge2 None
               OpBranchConditional %flagOff %set %done
        %set = OpLabel
               OpStore %out %uint_1
               OpBranch %merge2
       %done = OpLabel
               OpBranch %merge2
     %merge2 = OpLabel
               OpReturn
               OpFunctionEnd
)";

std::vector<uint32_t> assemble(const char* text) {
    spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_2);
    std::vector<uint32_t> words;
    EXPECT_TRUE(tools.Assemble(text, &words));
    return words;
}

std::string disassemble(const std::vector<uint32_t>& words) {
    spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_2);
    std::string text;
    EXPECT_TRUE(tools.Disassemble(
        words, &text, SPV_BINARY_TO_TEXT_OPTION_NO_HEADER | SPV_BINARY_TO_TEXT_OPTION_FRIENDLY_NAMES));
    return text;
}

bool valid(const std::vector<uint32_t>& words, std::string* why) {
    spvtools::SpirvTools tools(SPV_ENV_VULKAN_1_2);
    tools.SetMessageConsumer([&](spv_message_level_t, const char*, const spv_position_t&, const char* m) {
        if (why->empty()) *why = m;
    });
    spvtools::ValidatorOptions options;
    options.SetScalarBlockLayout(true); // the kernels' buffers use scalar layout (layout.h)
    return tools.Validate(words.data(), words.size(), options);
}

TEST(SpirvSpecialization, SetsEachKindOfConstantAndRemovesTheBranchesTheyDisable) {
    const std::vector<uint32_t> module = assemble(kModule);
    ASSERT_FALSE(module.empty());
    EXPECT_EQ(countSpecializationConstants(module), 4u);

    // flagOn -> false, flagOff -> true, count -> 20; untouched keeps its default 11.
    const SpecializationConstant constants[] = {{3, 0}, {4, 1}, {7, 20}};
    const std::vector<uint32_t> out = specializeSpirv(module, constants, "test");
    EXPECT_EQ(countSpecializationConstants(out), 0u);
    const std::string text = disassemble(out);
    // The first branch now takes %other (stores 2), the second always stores 1: no
    // conditional branch is left, and the 20 + 11 store is gone with its block.
    EXPECT_EQ(text.find("OpBranchConditional"), std::string::npos) << text;
    EXPECT_EQ(text.find("OpSpecConstant"), std::string::npos) << text;
    EXPECT_NE(text.find("OpStore %out %uint_2"), std::string::npos) << text;
    EXPECT_NE(text.find("OpStore %out %uint_1"), std::string::npos) << text;

    // The defaults, as Vulkan would use them without a VkSpecializationInfo: flagOn true keeps
    // the store of count + untouched, folded to the constant 16.
    const std::string defaults = disassemble(specializeSpirv(module, {}, "test"));
    EXPECT_NE(defaults.find("OpConstant %uint 16"), std::string::npos) << defaults;
    EXPECT_EQ(defaults.find("OpStore %out %uint_2"), std::string::npos) << defaults;
}

TEST(SpirvSpecialization, RejectsWhatIsNotSpirv) {
    const std::vector<uint32_t> junk = {1, 2, 3, 4, 5, 6};
    EXPECT_THROW(specializeSpirv(junk, {}, "junk"), std::runtime_error);
    std::vector<uint32_t> truncated = assemble(kModule);
    truncated.resize(truncated.size() - 3);
    EXPECT_THROW(specializeSpirv(truncated, {}, "truncated"), std::runtime_error);
}

// The production kernels for a spread of scenes: the Cornell box's features, every feature, the
// course's classic integrator, each sampler and debug view. Valid SPIR-V, no constant left, and
// smaller than the module the driver would otherwise inline whole.
TEST(SpirvSpecialization, ProductionKernelsStayValidForEveryKindOfScene) {
    FeatureSet box; // unspecialised: every flag on; keep what the Cornell box uses
    box.spheres = box.mirror = box.dielectric = box.conductor = box.glossy = box.pbr = box.microfacet = false;
    box.absorption = box.shadingNormals = box.punctualLights = box.environment = box.textures = false;
    box.procedural = box.normalMaps = box.alpha = box.unlit = box.motion = false;
    const FeatureSet all = FeatureSet::all(IntegratorSettings{});
    FeatureSet classic = box;
    classic.classic = true;
    FeatureSet sobol = all;
    sobol.sampler = SAMPLER_SOBOL;
    FeatureSet debug = box;
    debug.debugView = DEBUG_VIEW_BVH_COST;
    const struct {
        const char* name;
        FeatureSet features;
    } cases[] = {
        {"cornell box", box}, {"all features", all}, {"classic", classic}, {"sobol", sobol}, {"debug view", debug}};
    const std::span<const uint32_t> kernels[] = {pt_render_spv, pt_render_light_tracing_spv};
    for (const auto& c : cases) {
        for (const auto kernel : kernels) {
            const std::vector<uint32_t> out = specializeSpirv(kernel, c.features.constants(8, 8), c.name);
            std::string why;
            EXPECT_TRUE(valid(out, &why)) << c.name << ": " << why;
            EXPECT_EQ(countSpecializationConstants(out), 0u) << c.name;
            EXPECT_LT(out.size(), kernel.size()) << c.name;
        }
    }
}

} // namespace
} // namespace pt::test
