// base/memory_usage.h: what the process holds, what it may still take, and how both are printed.
#include "base/memory_usage.h"

#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <vector>

namespace {

TEST(MemoryUsage, ResidentBytesFollowWhatIsTouched) {
    const uint64_t before = pt::residentBytes();
    ASSERT_GT(before, 0u) << "/proc/self/status has VmRSS";
    std::vector<char> block(64 << 20, 1); // 64 MB, every page written
    const uint64_t during = pt::residentBytes();
    EXPECT_GE(during, before + (48 << 20)) << "64 MB written should be resident";
    EXPECT_GE(pt::peakResidentBytes(), during);
    EXPECT_EQ(block[12345], 1);
}

TEST(MemoryUsage, HeadroomIsBoundedAndNamesItsLimit) {
    const pt::MemoryHeadroom h = pt::hostMemoryHeadroom();
    ASSERT_LT(h.bytes, UINT64_MAX) << "MemAvailable is always there on Linux";
    EXPECT_GT(h.bytes, uint64_t(16) << 20);
    EXPECT_FALSE(h.limit.empty());
}

// An address-space limit (ulimit -v) below the machine's memory is what binds, and is named;
// set in a child process, so this one keeps its own limits.
TEST(MemoryUsage, AnAddressSpaceLimitBinds) {
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
        rlimit limit{};
        getrlimit(RLIMIT_AS, &limit);
        limit.rlim_cur = rlim_t(8) << 30; // 8 GiB: far above this process's size
        if (setrlimit(RLIMIT_AS, &limit) != 0) _exit(3);
        const pt::MemoryHeadroom h = pt::hostMemoryHeadroom();
        const bool named = h.limit.find("ulimit -v") != std::string::npos;
        const bool bounded = h.bytes <= (uint64_t(8) << 30);
        // MemAvailable may be lower still on a small machine; then it is the one named.
        _exit(bounded && (named || h.limit.find("MemAvailable") != std::string::npos) ? 0 : 1);
    }
    int status = 0;
    ASSERT_EQ(waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 0);
}

TEST(MemoryUsage, BytesAreWrittenInDecimalUnits) {
    EXPECT_EQ(pt::formatBytes(0), "0 kB");
    EXPECT_EQ(pt::formatBytes(4096), "4 kB");
    EXPECT_EQ(pt::formatBytes(275'000'000), "275.0 MB");
    EXPECT_EQ(pt::formatBytes(1'310'000'000), "1.31 GB");
}

} // namespace
