#pragma once
// A kernel the driver has compiled: its pipeline with the set and pipeline layouts it was made
// with, shared by every ComputePipeline of the same specialised SPIR-V and push-constant size in a
// process. lavapipe compiles a kernel anew for each vkCreateComputePipelines (0.6 s for the
// path tracer, 2.6-3.6 s for BDPT's; its VkPipelineCache keeps nothing), so a process that
// renders the same kind of scene again (another camera of a scene, a viewer toggling a switch back,
// a test's replicate) would otherwise pay that each time. The descriptor sets stay each
// ComputePipeline's own, as they point at its scene's buffers.
#include <cstdint>
#include <list>
#include <memory>
#include <utility>
#include <vulkan/vulkan.h>

namespace pt {

struct CompiledKernel {
    explicit CompiledKernel(VkDevice d) : device(d) {}
    ~CompiledKernel(); // destroys whatever was made (null handles are skipped)
    CompiledKernel(const CompiledKernel&) = delete;
    CompiledKernel& operator=(const CompiledKernel&) = delete;

    VkDevice device;
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VkPipeline pipeline = VK_NULL_HANDLE;
};

// The kernels compiled most recently, kept alive after their pipelines are gone so that the next
// pipeline of one of them skips the driver's compile. At most `capacity` are kept beyond the ones
// in use (a lavapipe kernel holds about a megabyte of code and its driver state).
class RecentKernels {
public:
    explicit RecentKernels(size_t capacity) : capacity_(capacity) {}

    // The kernel made under `key`, now the most recent; null if none is kept.
    std::shared_ptr<const CompiledKernel> find(uint64_t key);
    // Keeps `kernel` as the most recent, forgetting the least recent beyond the capacity.
    void keep(uint64_t key, std::shared_ptr<const CompiledKernel> kernel);
    size_t size() const { return kept_.size(); }

private:
    size_t capacity_;
    std::list<std::pair<uint64_t, std::shared_ptr<const CompiledKernel>>> kept_; // the most recent first
};

} // namespace pt
