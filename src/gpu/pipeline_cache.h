#pragma once
// What makes the second pipeline of a kernel cheap to create, in this process and the next:
//  - SPIR-V with its specialization constants baked in and dead code removed (specializeSpirv),
//    kept on disk by the hash of the input module and the constants, so later processes skip
//    the specialisation too;
//  - the driver's VkPipelineCache, loaded from disk at start and written back when it grew
//    (GPU drivers keep compiled code there; lavapipe's is empty, which the disk copy shows);
//  - the kernels compiled most recently in this process (gpu/compiled_kernel.h), which lavapipe
//    would otherwise compile again for each pipeline.
// With no directory everything works the same but nothing persists (--no-pipeline-cache).
#include "gpu/compiled_kernel.h"
#include "gpu/shader_cache_directory.h"
#include "gpu/spirv_specialization.h"

#include <filesystem>
#include <memory>
#include <span>
#include <unordered_map>
#include <vector>
#include <vulkan/vulkan.h>

namespace pt {

struct SpecializedKernel {
    std::vector<uint32_t> spirv;
    bool fromCache = false; // made earlier (in this process or, through the disk, another)
    uint64_t key = 0;       // of the module and the constants it was made from
};

class PipelineCache {
public:
    // `directory` empty: nothing is read from or written to disk.
    PipelineCache(
        VkDevice device, const VkPhysicalDeviceProperties& properties, const std::filesystem::path& directory);
    ~PipelineCache();
    PipelineCache(const PipelineCache&) = delete;
    PipelineCache& operator=(const PipelineCache&) = delete;

    VkPipelineCache handle() const { return cache_; }
    // The folder in use, or empty.
    std::filesystem::path directory() const;

    SpecializedKernel specialize(
        std::span<const uint32_t> spirv, std::span<const SpecializationConstant> constants, const char* name);

    // The kernels compiled lately, by the key of their SpecializedKernel and push-constant size.
    RecentKernels& recentKernels() { return recent_; }

    // Writes the driver's cache to disk if it holds more than what was loaded, merged with what
    // other processes wrote meanwhile. Called after each pipeline is created.
    void save();

private:
    std::vector<uint8_t> driverData() const;

    VkDevice device_;
    VkPipelineCache cache_ = VK_NULL_HANDLE;
    std::unique_ptr<ShaderCacheDirectory> disk_;
    std::string driverEntry_; // file name of this device and driver's VkPipelineCache
    uint64_t driverKey_ = 0;
    std::unordered_map<uint64_t, std::vector<uint32_t>> specializedInProcess_;
    size_t savedDriverBytes_ = 0;
    // Eight: the most kernels a scene's work switches between (a path tracer and BDPT kernel of
    // each kind a test renders, the viewer's switches and back).
    RecentKernels recent_{8};
};

} // namespace pt
