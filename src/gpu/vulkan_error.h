#pragma once
// Vulkan failures as exceptions with a message a user can act on.
#include <stdexcept>
#include <string>
#include <vulkan/vulkan.h>

namespace pt {

class VulkanError : public std::runtime_error {
public:
    VulkanError(VkResult result, const std::string& what);
    VkResult result() const { return result_; }

private:
    VkResult result_;
};

// A short human description of a VkResult ("out of device memory", "device lost", ...).
std::string describeVkResult(VkResult result);

// Throws VulkanError("<what>: <description>") unless result is VK_SUCCESS.
void vkCheck(VkResult result, const char* what);

} // namespace pt
