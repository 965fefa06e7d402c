#include "gpu/vulkan_error.h"

namespace pt {

std::string describeVkResult(VkResult result) {
    switch (result) {
    case VK_SUCCESS: return "success";
    case VK_NOT_READY: return "not ready";
    case VK_TIMEOUT: return "timed out";
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "out of host memory";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "out of device memory (try a smaller scene or resolution)";
    case VK_ERROR_INITIALIZATION_FAILED: return "initialization failed";
    case VK_ERROR_DEVICE_LOST: return "device lost (the GPU reset or the driver crashed)";
    case VK_ERROR_MEMORY_MAP_FAILED: return "memory map failed";
    case VK_ERROR_LAYER_NOT_PRESENT: return "layer not present (install vulkan-validationlayers)";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "extension not present";
    case VK_ERROR_FEATURE_NOT_PRESENT: return "feature not present";
    case VK_ERROR_INCOMPATIBLE_DRIVER: return "no compatible Vulkan driver (install mesa-vulkan-drivers)";
    case VK_ERROR_TOO_MANY_OBJECTS: return "too many objects";
    case VK_ERROR_FORMAT_NOT_SUPPORTED: return "format not supported";
    case VK_ERROR_OUT_OF_POOL_MEMORY: return "out of pool memory";
    case VK_ERROR_INVALID_SHADER_NV: return "invalid shader";
    default: return "VkResult " + std::to_string(static_cast<int>(result));
    }
}

VulkanError::VulkanError(VkResult result, const std::string& what)
    : std::runtime_error(what + ": " + describeVkResult(result)), result_(result) {}

void vkCheck(VkResult result, const char* what) {
    if (result != VK_SUCCESS) throw VulkanError(result, what);
}

} // namespace pt
