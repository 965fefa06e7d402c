#include "base/memory_usage.h"

#include <sys/resource.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace pt {
namespace {

// The value of a "Key:   123 kB" line of a /proc file, in bytes; 0 if absent.
uint64_t procField(const char* path, const std::string& key) {
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
        if (line.compare(0, key.size(), key) != 0 || line.size() <= key.size() || line[key.size()] != ':') continue;
        std::istringstream fields(line.substr(key.size() + 1));
        uint64_t value = 0;
        std::string unit;
        fields >> value >> unit;
        return unit == "kB" ? value * 1024 : value;
    }
    return 0;
}

// A file holding one number (cgroup limits and usages); nothing for "max" or unreadable.
bool readNumber(const std::string& path, uint64_t& value) {
    std::ifstream in(path);
    std::string text;
    if (!(in >> text) || text == "max") return false;
    try {
        size_t used = 0;
        value = std::stoull(text, &used);
        return used == text.size();
    } catch (const std::exception&) {
        return false;
    }
}

// The folders that may hold this process's cgroup memory files: its own cgroup's path (from
// /proc/self/cgroup: "0::/path" for v2, "N:memory:/path" for v1) under the mount, and the mount's
// root (inside a cgroup namespace the root is the process's own cgroup).
std::vector<std::string> cgroupFolders() {
    std::vector<std::string> folders;
    std::ifstream in("/proc/self/cgroup");
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("0::", 0) == 0) folders.push_back("/sys/fs/cgroup" + line.substr(3));
        const size_t memory = line.find(":memory:");
        if (memory != std::string::npos) folders.push_back("/sys/fs/cgroup/memory" + line.substr(memory + 8));
    }
    folders.push_back("/sys/fs/cgroup");
    folders.push_back("/sys/fs/cgroup/memory");
    return folders;
}

void consider(MemoryHeadroom& h, uint64_t bytes, const std::string& limit) {
    if (bytes < h.bytes) h = {bytes, limit};
}

} // namespace

uint64_t residentBytes() { return procField("/proc/self/status", "VmRSS"); }

uint64_t peakResidentBytes() {
    if (const uint64_t hwm = procField("/proc/self/status", "VmHWM")) return hwm;
    rusage usage{};
    return getrusage(RUSAGE_SELF, &usage) == 0 ? uint64_t(usage.ru_maxrss) * 1024 : 0;
}

MemoryHeadroom hostMemoryHeadroom() {
    MemoryHeadroom h;
    if (const uint64_t available = procField("/proc/meminfo", "MemAvailable"))
        consider(h, available, "the memory available (MemAvailable, " + formatBytes(available) + ")");
    // cgroup v2 (memory.max) or v1 (memory.limit_in_bytes, "unlimited" near 2^63): a
    // container's limit is below what /proc/meminfo shows.
    for (const std::string& folder : cgroupFolders()) {
        uint64_t limit = 0, usage = 0;
        const bool v2 = readNumber(folder + "/memory.max", limit) && readNumber(folder + "/memory.current", usage);
        const bool v1 = !v2 && readNumber(folder + "/memory.limit_in_bytes", limit) && limit < (uint64_t(1) << 60) &&
                        readNumber(folder + "/memory.usage_in_bytes", usage);
        if (v2 || v1) {
            consider(h, limit > usage ? limit - usage : 0,
                "the cgroup's memory limit (" + formatBytes(limit) + ", " + formatBytes(usage) + " in use)");
            break;
        }
    }
    rlimit as{};
    if (getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY) {
        const uint64_t size = procField("/proc/self/status", "VmSize");
        consider(h, as.rlim_cur > size ? as.rlim_cur - size : 0,
            "the address-space limit (ulimit -v, " + formatBytes(as.rlim_cur) + ")");
    }
    return h;
}

std::string formatBytes(uint64_t bytes) {
    char text[32];
    const double b = static_cast<double>(bytes);
    if (b >= 1e9)
        std::snprintf(text, sizeof text, "%.2f GB", b / 1e9);
    else if (b >= 1e6)
        std::snprintf(text, sizeof text, "%.1f MB", b / 1e6);
    else
        std::snprintf(text, sizeof text, "%.0f kB", b / 1e3);
    return text;
}

} // namespace pt
