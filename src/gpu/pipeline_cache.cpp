#include "gpu/pipeline_cache.h"

#include "base/hash.h"
#include "gpu/vulkan_error.h"

#include <cstring>

namespace pt {
namespace {

// Vulkan's own header at the start of pipeline cache data (VkPipelineCacheHeaderVersionOne).
bool matchesDevice(const std::vector<uint8_t>& data, const VkPhysicalDeviceProperties& p) {
    VkPipelineCacheHeaderVersionOne h{};
    if (data.size() < sizeof h) return false;
    std::memcpy(&h, data.data(), sizeof h);
    return h.headerSize >= sizeof h && h.headerVersion == VK_PIPELINE_CACHE_HEADER_VERSION_ONE &&
           h.vendorID == p.vendorID && h.deviceID == p.deviceID &&
           std::memcmp(h.pipelineCacheUUID, p.pipelineCacheUUID, VK_UUID_SIZE) == 0;
}

uint64_t spirvKey(std::span<const uint32_t> spirv, std::span<const SpecializationConstant> constants) {
    uint64_t key = fnv1a64(&kSpirvSpecializationVersion, sizeof kSpirvSpecializationVersion);
    key = fnv1a64(spirv.data(), spirv.size_bytes(), key);
    for (const SpecializationConstant& c : constants) {
        key = fnv1a64(&c.id, sizeof c.id, key);
        key = fnv1a64(&c.value, sizeof c.value, key);
    }
    return key;
}

} // namespace

PipelineCache::PipelineCache(
    VkDevice device, const VkPhysicalDeviceProperties& properties, const std::filesystem::path& directory)
    : device_(device) {
    std::vector<uint8_t> initial;
    if (!directory.empty()) {
        disk_ = std::make_unique<ShaderCacheDirectory>(directory);
        // One file per device and driver version: a driver update starts a new one and the old
        // one ages out of the folder.
        driverKey_ = fnv1a64(&properties.vendorID, sizeof properties.vendorID);
        driverKey_ = fnv1a64(&properties.deviceID, sizeof properties.deviceID, driverKey_);
        driverKey_ = fnv1a64(&properties.driverVersion, sizeof properties.driverVersion, driverKey_);
        driverKey_ = fnv1a64(properties.pipelineCacheUUID, VK_UUID_SIZE, driverKey_);
        driverEntry_ = "vulkan-" + hexDigits(driverKey_);
        if (auto data = disk_->read(driverEntry_, driverKey_); data && matchesDevice(*data, properties))
            initial = std::move(*data);
    }
    VkPipelineCacheCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
    info.initialDataSize = initial.size();
    info.pInitialData = initial.empty() ? nullptr : initial.data();
    vkCheck(vkCreatePipelineCache(device_, &info, nullptr, &cache_), "creating the pipeline cache");
    savedDriverBytes_ = initial.size();
}

PipelineCache::~PipelineCache() {
    if (cache_) vkDestroyPipelineCache(device_, cache_, nullptr);
}

std::filesystem::path PipelineCache::directory() const { return disk_ ? disk_->path() : std::filesystem::path(); }

SpecializedKernel PipelineCache::specialize(
    std::span<const uint32_t> spirv, std::span<const SpecializationConstant> constants, const char* name) {
    SpecializedKernel kernel;
    const uint64_t key = spirvKey(spirv, constants);
    kernel.key = key;
    if (auto known = specializedInProcess_.find(key); known != specializedInProcess_.end()) {
        kernel.spirv = known->second;
        kernel.fromCache = true;
        return kernel;
    }
    const std::string entry = "spirv-" + hexDigits(key);
    if (disk_) {
        if (auto bytes = disk_->read(entry, key); bytes && bytes->size() % 4 == 0 && !bytes->empty()) {
            kernel.spirv.resize(bytes->size() / 4);
            std::memcpy(kernel.spirv.data(), bytes->data(), bytes->size());
            if (kernel.spirv[0] == 0x07230203) {
                kernel.fromCache = true;
                specializedInProcess_[key] = kernel.spirv;
                return kernel;
            }
        }
    }
    kernel.spirv = specializeSpirv(spirv, constants, name);
    specializedInProcess_[key] = kernel.spirv;
    if (disk_)
        disk_->write(entry, key,
            std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(kernel.spirv.data()), kernel.spirv.size() * 4));
    return kernel;
}

std::vector<uint8_t> PipelineCache::driverData() const {
    size_t bytes = 0;
    if (vkGetPipelineCacheData(device_, cache_, &bytes, nullptr) != VK_SUCCESS) return {};
    std::vector<uint8_t> data(bytes);
    if (vkGetPipelineCacheData(device_, cache_, &bytes, data.data()) != VK_SUCCESS) return {};
    data.resize(bytes);
    return data;
}

void PipelineCache::save() {
    if (!disk_) return;
    std::vector<uint8_t> data = driverData();
    if (data.size() <= savedDriverBytes_) return; // nothing new (always so on lavapipe)
    // Keep what other processes added since this one started.
    if (auto other = disk_->read(driverEntry_, driverKey_); other && other->size() > savedDriverBytes_) {
        VkPipelineCacheCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
        info.initialDataSize = other->size();
        info.pInitialData = other->data();
        VkPipelineCache theirs = VK_NULL_HANDLE;
        if (vkCreatePipelineCache(device_, &info, nullptr, &theirs) == VK_SUCCESS) {
            vkMergePipelineCaches(device_, cache_, 1, &theirs);
            vkDestroyPipelineCache(device_, theirs, nullptr);
            data = driverData();
        }
    }
    disk_->write(driverEntry_, driverKey_, data);
    savedDriverBytes_ = data.size();
}

} // namespace pt
