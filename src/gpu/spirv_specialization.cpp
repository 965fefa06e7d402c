#include "gpu/spirv_specialization.h"

#include <spirv-tools/optimizer.hpp>

#include <stdexcept>
#include <string>
#include <unordered_map>

namespace pt {
namespace {

// The few opcodes and words of the SPIR-V binary form this file reads (SPIR-V 1.x, section 2.3).
constexpr uint32_t kMagic = 0x07230203;
constexpr uint32_t kHeaderWords = 5;
constexpr uint32_t kOpDecorate = 71;
constexpr uint32_t kDecorationSpecId = 1;
constexpr uint32_t kOpSpecConstantTrue = 48;
constexpr uint32_t kOpSpecConstantFalse = 49;
constexpr uint32_t kOpSpecConstant = 50;

[[noreturn]] void fail(const char* name, const std::string& problem) {
    throw std::runtime_error(std::string("specializing the '") + name + "' shader: " + problem);
}

// Calls visit(offset, opcode, wordCount) for every instruction after the header.
template <typename Visit>
void forEachInstruction(std::span<const uint32_t> words, const char* name, Visit visit) {
    if (words.size() < kHeaderWords || words[0] != kMagic) fail(name, "not a SPIR-V module");
    for (size_t at = kHeaderWords; at < words.size();) {
        const uint32_t opcode = words[at] & 0xffffu, count = words[at] >> 16;
        if (count == 0 || at + count > words.size()) fail(name, "truncated instruction");
        visit(at, opcode, count);
        at += count;
    }
}

// OpDecorate <target> SpecId <id>: the target is a specialization constant.
bool isSpecIdDecoration(std::span<const uint32_t> words, size_t at, uint32_t opcode, uint32_t count) {
    return opcode == kOpDecorate && count == 4 && words[at + 2] == kDecorationSpecId;
}

// Writes each listed value into its constant's declaration, so that freezing the constants
// afterwards gives them the values a VkSpecializationInfo would have given.
void setDefaults(std::vector<uint32_t>& words, std::span<const SpecializationConstant> constants, const char* name) {
    std::unordered_map<uint32_t, uint32_t> specIdOfResult;
    forEachInstruction(words, name, [&](size_t at, uint32_t opcode, uint32_t count) {
        if (isSpecIdDecoration(words, at, opcode, count)) specIdOfResult[words[at + 1]] = words[at + 3];
    });
    std::unordered_map<uint32_t, uint32_t> valueOfSpecId;
    for (const SpecializationConstant& c : constants) valueOfSpecId[c.id] = c.value;
    forEachInstruction(words, name, [&](size_t at, uint32_t opcode, uint32_t count) {
        if (opcode != kOpSpecConstantTrue && opcode != kOpSpecConstantFalse && opcode != kOpSpecConstant) return;
        const auto specId = specIdOfResult.find(words[at + 2]);
        if (specId == specIdOfResult.end()) return;
        const auto value = valueOfSpecId.find(specId->second);
        if (value == valueOfSpecId.end()) return;
        if (opcode == kOpSpecConstant) {
            if (count != 4)
                fail(name, "specialization constant " + std::to_string(specId->second) + " is not 32 bits wide");
            words[at + 3] = value->second;
        } else {
            words[at] = (count << 16) | (value->second ? kOpSpecConstantTrue : kOpSpecConstantFalse);
        }
    });
}

} // namespace

std::vector<uint32_t> specializeSpirv(
    std::span<const uint32_t> spirv, std::span<const SpecializationConstant> constants, const char* name) {
    std::vector<uint32_t> words(spirv.begin(), spirv.end());
    setDefaults(words, constants, name);

    spvtools::Optimizer optimizer(SPV_ENV_VULKAN_1_2);
    std::string firstError;
    optimizer.SetMessageConsumer([&](spv_message_level_t level, const char*, const spv_position_t&, const char* m) {
        if (level <= SPV_MSG_ERROR && firstError.empty()) firstError = m;
    });
    // Only passes that delete what the constants switch off: no inlining, unrolling or
    // rewriting of live code, which the driver optimises better itself (spirv-opt -O made
    // lavapipe slower to compile, not faster).
    optimizer.RegisterPass(spvtools::CreateFreezeSpecConstantValuePass())
        .RegisterPass(spvtools::CreateFoldSpecConstantOpAndCompositePass())
        .RegisterPass(spvtools::CreateCCPPass())
        .RegisterPass(spvtools::CreateDeadBranchElimPass())
        .RegisterPass(spvtools::CreateEliminateDeadFunctionsPass());
    spvtools::OptimizerOptions options;
    options.set_run_validator(false); // the build's SPIR-V is validated by the tests, not per run
    std::vector<uint32_t> out;
    if (!optimizer.Run(words.data(), words.size(), &out, options))
        fail(name, firstError.empty() ? "the optimizer failed" : firstError);
    return out;
}

size_t countSpecializationConstants(std::span<const uint32_t> spirv) {
    size_t n = 0;
    forEachInstruction(spirv, "module", [&](size_t at, uint32_t opcode, uint32_t count) {
        if (isSpecIdDecoration(spirv, at, opcode, count)) ++n;
    });
    return n;
}

} // namespace pt
