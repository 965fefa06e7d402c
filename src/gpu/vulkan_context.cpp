#include "gpu/vulkan_context.h"

#include "gpu/fault_injection.h"
#include "gpu/vulkan_error.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <regex>
#include <string>

#include <sched.h>

namespace pt {
namespace {

const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

const char* deviceTypeName(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
    }
}

// Preference order when no --device is given: a real GPU first, lavapipe last.
int deviceTypeRank(VkPhysicalDeviceType type) {
    switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
    }
}

// What pt set of lavapipe's environment in this process, for the log (lavapipeSettingsChosen).
std::string& chosenLavapipeSettings() {
    static std::string chosen;
    return chosen;
}

// Sets `variable` unless it is set already: the user's value wins, and a second context in this
// process finds pt's own and leaves it, so each setting is named once.
void chooseLavapipeSetting(const char* variable, const std::string& value) {
    if (std::getenv(variable) || setenv(variable, value.c_str(), 0) != 0) return;
    std::string& chosen = chosenLavapipeSettings();
    chosen += (chosen.empty() ? "" : " ") + std::string(variable) + "=" + value;
}

// Lavapipe runs a dispatch on one thread per core (LP_NUM_THREADS), each thread taking one
// contiguous run of the workgroups, fixed in advance (Mesa's lp_cs_tpool.c). In row order twice
// as many threads traced 22-25% more paths per second in the glass box with adaptive sampling on
// a 2-core machine (a core whose thread had finished its run then worked on another's;
// bench/RESULTS.md, "Lavapipe threads"). Since the workgroups visit the image in a strided order
// (render/workgroup_order.h) every run costs about the same and two threads a core are level with
// one ("Workgroups in a strided order"); kept for what unevenness is left. Only where the user
// has not chosen; other drivers ignore the variable. Before the instance, whose creation starts
// the driver.
void oversubscribeLavapipeThreads() {
    cpu_set_t set;
    CPU_ZERO(&set);
    const int cores = sched_getaffinity(0, sizeof set, &set) == 0 ? CPU_COUNT(&set) : 0;
    if (cores < 1) return;
    chooseLavapipeSetting("LP_NUM_THREADS", std::to_string(std::min(2 * cores, 32)));
}

// On an Intel CPU with AVX-512, lavapipe's kernels built for AVX2 traced 4-10% more paths per
// second than the AVX-512 ones it builds by default (the diffuse box +4%, the 1 M-triangle mesh
// +8-10%, the glass box and BDPT level; bench/RESULTS.md, "Lavapipe without AVX-512"). Why is not
// known: the AVX-512 code loads through 512-bit gathers and may run the core at a lower clock.
// Mesa reads GALLIUM_OVERRIDE_CPU_CAPS when the driver loads; "avx" clears AVX-512 and keeps AVX2
// and FMA. Images do not change. AMD's AVX-512 CPUs keep the driver's choice: there the AVX2 code
// was 1.6-2x slower (Zen 4) or level (Zen 5; "On an AMD EPYC Zen 5"); so does a user who set the
// variable.
void preferLavapipeAvx2Code() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_cpu_init();
    if (__builtin_cpu_is("intel") && __builtin_cpu_supports("avx512f"))
        chooseLavapipeSetting("GALLIUM_OVERRIDE_CPU_CAPS", "avx");
#endif
}

VkInstance createInstance(bool validation, const std::vector<std::string>& extraExtensions = {}) {
    oversubscribeLavapipeThreads();
    preferLavapipeAvx2Code();
    if (validation) {
        uint32_t count = 0;
        vkEnumerateInstanceLayerProperties(&count, nullptr);
        std::vector<VkLayerProperties> layers(count);
        vkEnumerateInstanceLayerProperties(&count, layers.data());
        bool found = std::any_of(layers.begin(), layers.end(),
            [](const VkLayerProperties& l) { return std::strcmp(l.layerName, kValidationLayer) == 0; });
        if (!found)
            throw std::runtime_error("Vulkan validation requested but VK_LAYER_KHRONOS_validation is not installed "
                                     "(apt-get install vulkan-validationlayers)");
    }
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "pt";
    app.apiVersion = VK_API_VERSION_1_2;
    std::vector<const char*> extensions;
    for (const auto& e : extraExtensions) extensions.push_back(e.c_str());
    std::vector<const char*> layers;
    if (validation) {
        extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
        layers.push_back(kValidationLayer);
    }
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    info.enabledLayerCount = static_cast<uint32_t>(layers.size());
    info.ppEnabledLayerNames = layers.data();
    VkInstance instance = VK_NULL_HANDLE;
    VkResult result = vkCreateInstance(&info, nullptr, &instance);
    if (result == VK_ERROR_INCOMPATIBLE_DRIVER || result == VK_ERROR_INITIALIZATION_FAILED)
        throw std::runtime_error("no Vulkan driver found (install mesa-vulkan-drivers for lavapipe, or a GPU driver)");
    vkCheck(result, "creating the Vulkan instance");
    return instance;
}

std::vector<VkPhysicalDevice> enumerateDevices(VkInstance instance) {
    uint32_t count = 0;
    vkCheck(vkEnumeratePhysicalDevices(instance, &count, nullptr), "listing Vulkan devices");
    std::vector<VkPhysicalDevice> devices(count);
    vkCheck(vkEnumeratePhysicalDevices(instance, &count, devices.data()), "listing Vulkan devices");
    return devices;
}

int findComputeQueueFamily(VkPhysicalDevice device) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
    for (uint32_t i = 0; i < count; ++i)
        if (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) return static_cast<int>(i);
    return -1;
}

// A compute queue family that can also present to `surface` (the viewer records compute,
// copies and presents on one queue), or -1.
int findPresentQueueFamily(VkPhysicalDevice device, VkSurfaceKHR surface) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
    for (uint32_t i = 0; i < count; ++i) {
        VkBool32 present = VK_FALSE;
        if ((families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) &&
            vkGetPhysicalDeviceSurfaceSupportKHR(device, i, surface, &present) == VK_SUCCESS && present)
            return static_cast<int>(i);
    }
    return -1;
}

bool hasDeviceExtension(VkPhysicalDevice device, const char* name) {
    uint32_t count = 0;
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
    std::vector<VkExtensionProperties> extensions(count);
    vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
    return std::any_of(extensions.begin(), extensions.end(),
        [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

DeviceInfo describeDevice(VkPhysicalDevice device, uint32_t index) {
    VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    driver.pNext = &subgroup;
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    props.pNext = &driver;
    vkGetPhysicalDeviceProperties2(device, &props);
    VkPhysicalDeviceVulkan12Features features12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features.pNext = &features12;
    if (props.properties.apiVersion >= VK_API_VERSION_1_2) vkGetPhysicalDeviceFeatures2(device, &features);

    DeviceInfo info;
    info.index = index;
    info.name = props.properties.deviceName;
    info.type = deviceTypeName(props.properties.deviceType);
    info.driver = std::string(driver.driverName) + " " + driver.driverInfo;
    info.apiVersion = props.properties.apiVersion;
    if (props.properties.apiVersion < VK_API_VERSION_1_2)
        info.whyNotUsable = "needs Vulkan 1.2";
    else if (!features12.bufferDeviceAddress)
        info.whyNotUsable = "no bufferDeviceAddress";
    else if (!features.features.shaderInt64)
        info.whyNotUsable = "no shaderInt64";
    else if (findComputeQueueFamily(device) < 0)
        info.whyNotUsable = "no compute queue";
    // The BVH traversal asks whether every lane of its SIMD group has a leaf (subgroupAll,
    // geometry/traverse.glsl): Vulkan 1.1 devices have it everywhere in practice, but it is optional.
    else if ((subgroup.supportedStages & VK_SHADER_STAGE_COMPUTE_BIT) == 0 ||
             (subgroup.supportedOperations & VK_SUBGROUP_FEATURE_VOTE_BIT) == 0)
        info.whyNotUsable = "no subgroup vote operations in compute shaders";
    info.usable = info.whyNotUsable.empty();
    info.int64Atomics = features12.shaderBufferInt64Atomics;
    return info;
}

// Mesa's lavapipe before 24 compiles our branches into much slower code (shared/LAVAPIPE.md).
bool driverIsSlowLavapipe(VkPhysicalDevice device) {
    VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
    props.pNext = &driver;
    vkGetPhysicalDeviceProperties2(device, &props);
    if (driver.driverID != VK_DRIVER_ID_MESA_LLVMPIPE) return false;
    std::smatch m;
    std::string text = driver.driverInfo;
    if (!std::regex_search(text, m, std::regex(R"(Mesa (\d+)\.)"))) return false;
    return std::stoi(m[1].str()) < 24;
}

} // namespace

std::string VulkanContext::lavapipeSettingsChosen() { return chosenLavapipeSettings(); }

std::vector<DeviceInfo> VulkanContext::listDevices() {
    VkInstance instance = createInstance(false);
    std::vector<DeviceInfo> result;
    try {
        auto devices = enumerateDevices(instance);
        for (uint32_t i = 0; i < devices.size(); ++i) result.push_back(describeDevice(devices[i], i));
    } catch (...) {
        vkDestroyInstance(instance, nullptr);
        throw;
    }
    vkDestroyInstance(instance, nullptr);
    return result;
}

VulkanContext::VulkanContext(const ContextOptions& options) {
    instance_ = createInstance(options.validation, options.instanceExtensions);
    try {
        if (options.validation) {
            auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
                vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
            VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
            info.messageSeverity =
                VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
            info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
            info.pfnUserCallback = &VulkanContext::debugCallback;
            info.pUserData = this;
            if (create) vkCheck(create(instance_, &info, nullptr, &messenger_), "creating the validation messenger");
        }
        if (options.createSurface) surface_ = options.createSurface(instance_);

        // Pick a device: the first match for --device, else the best-ranked usable one.
        auto devices = enumerateDevices(instance_);
        if (devices.empty())
            throw std::runtime_error(
                "no Vulkan device found (install mesa-vulkan-drivers for lavapipe, or a GPU driver)");
        int best = -1;
        int bestRank = -1;
        std::string rejected;
        for (uint32_t i = 0; i < devices.size(); ++i) {
            DeviceInfo info = describeDevice(devices[i], i);
            if (!options.deviceSubstring.empty() && info.name.find(options.deviceSubstring) == std::string::npos)
                continue;
            if (info.usable && surface_ && !hasDeviceExtension(devices[i], VK_KHR_SWAPCHAIN_EXTENSION_NAME))
                info.usable = false, info.whyNotUsable = "no VK_KHR_swapchain";
            else if (info.usable && surface_ && findPresentQueueFamily(devices[i], surface_) < 0)
                info.usable = false, info.whyNotUsable = "cannot present to the window from a compute queue";
            if (!info.usable) {
                rejected += (rejected.empty() ? "" : "; ") + info.name + ": " + info.whyNotUsable;
                continue;
            }
            VkPhysicalDeviceProperties p;
            vkGetPhysicalDeviceProperties(devices[i], &p);
            int rank = deviceTypeRank(p.deviceType);
            if (!options.deviceSubstring.empty()) rank = 100 - static_cast<int>(i); // first match wins
            if (rank > bestRank) {
                best = static_cast<int>(i);
                bestRank = rank;
            }
        }
        if (best < 0) {
            if (!options.deviceSubstring.empty())
                throw std::runtime_error("no usable Vulkan device matches --device '" + options.deviceSubstring + "'" +
                                         (rejected.empty() ? "" : " (" + rejected + ")") + "; see 'pt devices'");
            throw std::runtime_error("no usable Vulkan device (" + rejected + ")");
        }
        physicalDevice_ = devices[best];
        info_ = describeDevice(physicalDevice_, static_cast<uint32_t>(best));
        slowLavapipe_ = driverIsSlowLavapipe(physicalDevice_);
        vkGetPhysicalDeviceProperties(physicalDevice_, &properties_);
        vkGetPhysicalDeviceMemoryProperties(physicalDevice_, &memoryProperties_);
        queueFamily_ = static_cast<uint32_t>(
            surface_ ? findPresentQueueFamily(physicalDevice_, surface_) : findComputeQueueFamily(physicalDevice_));

        float priority = 1.0f;
        VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
        queueInfo.queueFamilyIndex = queueFamily_;
        queueInfo.queueCount = 1;
        queueInfo.pQueuePriorities = &priority;
        VkPhysicalDeviceVulkan12Features features12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
        features12.bufferDeviceAddress = VK_TRUE;
        features12.shaderBufferInt64Atomics = info_.int64Atomics ? VK_TRUE : VK_FALSE;
        VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
        features.pNext = &features12;
        features.features.shaderInt64 = VK_TRUE;
        VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
        deviceInfo.pNext = &features;
        deviceInfo.queueCreateInfoCount = 1;
        deviceInfo.pQueueCreateInfos = &queueInfo;
        const char* swapchainExtension = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
        if (surface_) {
            deviceInfo.enabledExtensionCount = 1;
            deviceInfo.ppEnabledExtensionNames = &swapchainExtension;
        }
        vkCheck(vkCreateDevice(physicalDevice_, &deviceInfo, nullptr, &device_), "creating the Vulkan device");
        vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);

        VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
        poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        poolInfo.queueFamilyIndex = queueFamily_;
        vkCheck(vkCreateCommandPool(device_, &poolInfo, nullptr, &commandPool_), "creating a command pool");
        VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
        vkCheck(vkCreateFence(device_, &fenceInfo, nullptr, &fence_), "creating a fence");
        pipelineCache_ = std::make_unique<PipelineCache>(device_, properties_, options.pipelineCacheDirectory);
    } catch (...) {
        this->~VulkanContext();
        throw;
    }
}

VulkanContext::~VulkanContext() {
    if (device_) {
        vkDeviceWaitIdle(device_);
        pipelineCache_.reset();
        if (fence_) vkDestroyFence(device_, fence_, nullptr);
        if (commandPool_) vkDestroyCommandPool(device_, commandPool_, nullptr);
        vkDestroyDevice(device_, nullptr);
        device_ = VK_NULL_HANDLE;
    }
    if (surface_) {
        vkDestroySurfaceKHR(instance_, surface_, nullptr);
        surface_ = VK_NULL_HANDLE;
    }
    if (messenger_) {
        auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
            vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
        if (destroy) destroy(instance_, messenger_, nullptr);
        messenger_ = VK_NULL_HANDLE;
    }
    if (instance_) {
        vkDestroyInstance(instance_, nullptr);
        instance_ = VK_NULL_HANDLE;
    }
}

void VulkanContext::submitAndWait(const std::function<void(VkCommandBuffer)>& record) {
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = commandPool_;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    vkCheck(vkAllocateCommandBuffers(device_, &alloc, &cmd), "allocating a command buffer");
    struct Free {
        VkDevice d;
        VkCommandPool p;
        VkCommandBuffer c;
        ~Free() { vkFreeCommandBuffers(d, p, 1, &c); }
    } guard{device_, commandPool_, cmd};
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkCheck(vkBeginCommandBuffer(cmd, &begin), "recording commands");
    record(cmd);
    vkCheck(vkEndCommandBuffer(cmd), "recording commands");
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd;
    vkCheck(vkResetFences(device_, 1, &fence_), "resetting a fence");
    vkCheck(injectedSubmitFault(), "submitting work to the GPU"); // PT_FAULT test hook
    vkCheck(vkQueueSubmit(queue_, 1, &submit, fence_), "submitting work to the GPU");
    vkCheck(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX), "waiting for the GPU");
}

VKAPI_ATTR VkBool32 VKAPI_CALL VulkanContext::debugCallback(VkDebugUtilsMessageSeverityFlagBitsEXT,
    VkDebugUtilsMessageTypeFlagsEXT, const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
    auto* self = static_cast<VulkanContext*>(user);
    if (self->validationMessages_++ == 0 && data && data->pMessage) self->firstValidationMessage_ = data->pMessage;
    return VK_FALSE;
}

} // namespace pt
