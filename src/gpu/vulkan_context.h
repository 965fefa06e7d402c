#pragma once
// Vulkan instance, device selection and the one compute queue everything runs on.
#include "gpu/pipeline_cache.h"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>
#include <vulkan/vulkan.h>

namespace pt {

struct DeviceInfo {
    uint32_t index = 0;
    std::string name;
    std::string type;   // "discrete GPU", "integrated GPU", "CPU", ...
    std::string driver; // driver name and version, e.g. "llvmpipe Mesa 25.0.7"
    uint32_t apiVersion = 0;
    bool usable = false;
    std::string whyNotUsable;  // empty when usable
    bool int64Atomics = false; // shaderBufferInt64Atomics: light tracing's splats need it
};

struct ContextOptions {
    bool validation = false;     // enable VK_LAYER_KHRONOS_validation and count its messages
    std::string deviceSubstring; // pick the first usable device whose name contains this

    // Presentation (pt view); the headless path leaves both empty. `instanceExtensions` are
    // enabled on the instance (glfwGetRequiredInstanceExtensions). `createSurface`, called once
    // the instance exists, returns the window's surface; the context then owns it, enables
    // VK_KHR_swapchain and picks a device whose compute queue family can present to it.
    std::vector<std::string> instanceExtensions;
    std::function<VkSurfaceKHR(VkInstance)> createSurface;

    // Where pipelines are cached between processes (ShaderCacheDirectory::defaultPath() for pt's
    // commands); empty: nothing persists (--no-pipeline-cache).
    std::filesystem::path pipelineCacheDirectory;
};

class VulkanContext {
public:
    explicit VulkanContext(const ContextOptions& options);
    ~VulkanContext();
    VulkanContext(const VulkanContext&) = delete;
    VulkanContext& operator=(const VulkanContext&) = delete;

    // Every device the loader reports, with whether pt can use it and why not.
    static std::vector<DeviceInfo> listDevices();

    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queueFamily() const { return queueFamily_; }
    // The window surface given through ContextOptions::createSurface, or VK_NULL_HANDLE.
    VkSurfaceKHR surface() const { return surface_; }
    const DeviceInfo& info() const { return info_; }
    const VkPhysicalDeviceProperties& properties() const { return properties_; }
    const VkPhysicalDeviceMemoryProperties& memoryProperties() const { return memoryProperties_; }
    // True for lavapipe older than Mesa 24, which runs our kernel about 3.5x slower.
    bool isSlowLavapipe() const { return slowLavapipe_; }
    // The lavapipe settings pt chose in this process, as the environment variables it set where
    // the user had not (e.g. "LP_NUM_THREADS=4 GALLIUM_OVERRIDE_CPU_CAPS=avx"); empty if none.
    static std::string lavapipeSettingsChosen();

    // Validation messages (warnings and errors) seen so far; 0 when validation is off.
    uint32_t validationMessageCount() const { return validationMessages_; }
    const std::string& firstValidationMessage() const { return firstValidationMessage_; }

    // Specialised kernels and the driver's pipeline cache, shared by every pipeline.
    PipelineCache& pipelineCache() { return *pipelineCache_; }

    // Records commands into a one-shot command buffer, submits it and waits for completion.
    void submitAndWait(const std::function<void(VkCommandBuffer)>& record);

private:
    static VKAPI_ATTR VkBool32 VKAPI_CALL debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
        VkDebugUtilsMessageTypeFlagsEXT types, const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkSurfaceKHR surface_ = VK_NULL_HANDLE;
    VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    uint32_t queueFamily_ = 0;
    VkCommandPool commandPool_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
    std::unique_ptr<PipelineCache> pipelineCache_;
    DeviceInfo info_;
    VkPhysicalDeviceProperties properties_{};
    VkPhysicalDeviceMemoryProperties memoryProperties_{};
    bool slowLavapipe_ = false;
    uint32_t validationMessages_ = 0;
    std::string firstValidationMessage_;
};

} // namespace pt
