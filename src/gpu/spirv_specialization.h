#pragma once
// Bakes specialization constants into a SPIR-V module and removes the code they disable, before
// the driver sees it. Drivers that inline every function before folding constants (lavapipe:
// spirv_to_nir, then nir_inline_functions, then constant folding) otherwise spend most of
// pipeline creation on code a scene never runs: for the Cornell box, 2.4 s of lavapipe's 2.5 s
// goes to branches the constants switch off. The result computes exactly what the driver would
// have computed with the same constants (images are bit-identical); bench/RESULTS.md has the
// measurements.
#include <cstdint>
#include <span>
#include <vector>

namespace pt {

struct SpecializationConstant {
    uint32_t id;
    uint32_t value; // booleans are 0 or 1, as VkBool32
    bool operator==(const SpecializationConstant&) const = default;
};

// Bumped whenever specializeSpirv's output may change for the same input, so that cached results
// of an older version are not reused.
inline constexpr uint32_t kSpirvSpecializationVersion = 2;

// Sets every listed constant (by SpecId) as the module's value, freezes all specialization
// constants (unlisted ones keep their defaults, as Vulkan would), folds the expressions built on
// them and deletes the branches and functions that became dead. Throws std::runtime_error naming
// `name` if the module is malformed or a listed constant is not a 32-bit scalar or boolean.
std::vector<uint32_t> specializeSpirv(
    std::span<const uint32_t> spirv, std::span<const SpecializationConstant> constants, const char* name);

// Specialization constants (OpDecorate ... SpecId) left in a module: 0 after specializeSpirv.
size_t countSpecializationConstants(std::span<const uint32_t> spirv);

} // namespace pt
