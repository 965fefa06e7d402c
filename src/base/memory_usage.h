#pragma once
// What this process holds in memory and what the machine lets it have, read from Linux's /proc
// and cgroup files (no library reports cgroup limits): for the summary line's peak, the per-phase
// log, and the check that refuses a scene before it is allocated rather than after a
// std::bad_alloc or the kernel's OOM killer.
#include <cstdint>
#include <string>

namespace pt {

// Resident set size now and at its peak (VmRSS, VmHWM); 0 where /proc is unreadable.
uint64_t residentBytes();
uint64_t peakResidentBytes();

// The most this process can still allocate, and what sets it: the least of the kernel's
// estimate of available memory (MemAvailable), the cgroup's limit less its usage (v2 or v1),
// and the address-space limit (ulimit -v) less the process's size.
struct MemoryHeadroom {
    uint64_t bytes = UINT64_MAX; // UINT64_MAX: nothing readable limits it
    std::string limit;           // e.g. "available memory (MemAvailable)", "the cgroup's limit of 24.0 GB"
};
MemoryHeadroom hostMemoryHeadroom();

// "1.31 GB" (decimal units, as `free -h` and the issue tracker write them).
std::string formatBytes(uint64_t bytes);

} // namespace pt
