#include "gpu/fault_injection.h"

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <string>

namespace pt {
namespace {

struct Fault {
    const char* kind = nullptr; // "device-lost" or "out-of-memory"
    long at = 0;                // which call fails, from 1
};

Fault configuredFault() {
    Fault fault;
    const char* text = std::getenv("PT_FAULT");
    if (!text) return fault;
    const std::string spec = text;
    const auto at = spec.find('@');
    if (at == std::string::npos) return fault;
    const std::string kind = spec.substr(0, at);
    fault.at = std::strtol(spec.c_str() + at + 1, nullptr, 10);
    if (kind == "device-lost")
        fault.kind = "device-lost";
    else if (kind == "out-of-memory")
        fault.kind = "out-of-memory";
    return fault;
}

// `sticky`: every call from the Nth on fails, as on a really lost device.
VkResult countAndMaybeFail(const char* kind, std::atomic<long>& counter, VkResult failure, bool sticky) {
    static const Fault fault = configuredFault();
    if (!fault.kind || std::strcmp(fault.kind, kind) != 0) return VK_SUCCESS;
    const long n = ++counter;
    return (sticky ? n >= fault.at : n == fault.at) ? failure : VK_SUCCESS;
}

} // namespace

VkResult injectedSubmitFault() {
    static std::atomic<long> submits{0};
    return countAndMaybeFail("device-lost", submits, VK_ERROR_DEVICE_LOST, true);
}

VkResult injectedAllocationFault() {
    static std::atomic<long> allocations{0};
    return countAndMaybeFail("out-of-memory", allocations, VK_ERROR_OUT_OF_DEVICE_MEMORY, false);
}

} // namespace pt
