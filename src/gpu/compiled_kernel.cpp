#include "gpu/compiled_kernel.h"

namespace pt {

CompiledKernel::~CompiledKernel() {
    if (pipeline) vkDestroyPipeline(device, pipeline, nullptr);
    if (layout) vkDestroyPipelineLayout(device, layout, nullptr);
    if (setLayout) vkDestroyDescriptorSetLayout(device, setLayout, nullptr);
}

std::shared_ptr<const CompiledKernel> RecentKernels::find(uint64_t key) {
    for (auto it = kept_.begin(); it != kept_.end(); ++it)
        if (it->first == key) {
            kept_.splice(kept_.begin(), kept_, it);
            return kept_.front().second;
        }
    return nullptr;
}

void RecentKernels::keep(uint64_t key, std::shared_ptr<const CompiledKernel> kernel) {
    for (auto it = kept_.begin(); it != kept_.end(); ++it)
        if (it->first == key) {
            kept_.erase(it);
            break;
        }
    kept_.emplace_front(key, std::move(kernel));
    while (kept_.size() > capacity_) kept_.pop_back();
}

} // namespace pt
