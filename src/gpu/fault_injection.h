#pragma once
// Test hook for Vulkan faults that cannot be provoked on demand. PT_FAULT=device-lost@N makes
// the Nth queue submission (counted from 1 in the process) and every later one report
// VK_ERROR_DEVICE_LOST instead of running; PT_FAULT=out-of-memory@N makes the Nth device memory allocation report
// VK_ERROR_OUT_OF_DEVICE_MEMORY. Unset (always, outside tests), both return VK_SUCCESS.
#include <vulkan/vulkan.h>

namespace pt {

VkResult injectedSubmitFault();
VkResult injectedAllocationFault();

} // namespace pt
