#pragma once
// The Vulkan context every command makes from its options: validation, device choice and where
// pipelines are cached between processes.
#include "app/options.h"
#include "gpu/vulkan_context.h"

namespace pt {

inline ContextOptions contextOptionsFor(const RenderOptions& o) {
    ContextOptions c;
    c.validation = o.validation;
    c.deviceSubstring = o.device;
    if (!o.noPipelineCache) c.pipelineCacheDirectory = ShaderCacheDirectory::defaultPath();
    return c;
}

} // namespace pt
