// pt and the Vulkan devices: pt devices lists one, no driver and an unmatched --device are one
// clear error line each, and the lavapipe settings pt chooses are named and yield to the user's.
#include "cli_fixture.h"
#include "support/malformed_corpus.h"

#include <sched.h>

#include <algorithm>
#include <cctype>
#include <sstream>

namespace pt::test {
namespace {

TEST_F(CliTest, DevicesListsAtLeastOneDevice) {
    const PtRun r = run({"devices"});
    EXPECT_EXIT_STATUS(r, 0);
    std::istringstream s(r.out);
    int devices = 0;
    for (std::string line; std::getline(s, line);) {
        // "<index>: <name> (<type>, <driver>, Vulkan x.y)"
        if (line.empty() || !std::isdigit(static_cast<unsigned char>(line[0])) || line.find(": ") == std::string::npos)
            continue;
        if (line.find("llvmpipe") != std::string::npos || line.find("GPU") != std::string::npos) ++devices;
    }
    EXPECT_GE(devices, 1) << r;
}

// Vulkan failures are one clear line too: no driver at all, and a --device nothing matches.
TEST_F(CliTest, NoVulkanDriverIsAClearError) {
    const PtRun r = run({"render", "--spp", "1", "--width", "8", "--height", "8", "-o", (dir_ / "x.exr").string()},
        {{"VK_ICD_FILENAMES", (dir_ / "no-such-icd.json").string()},
            {"VK_DRIVER_FILES", (dir_ / "no-such-icd.json").string()}});
    EXPECT_EXIT_STATUS(r, 1);
    const std::string line = lower(r.errorLine());
    EXPECT_NE(line.find("vulkan"), std::string::npos) << line;
    EXPECT_TRUE(line.find("driver") != std::string::npos || line.find("device") != std::string::npos) << line;
    EXPECT_TRUE(outputs().empty());
}

TEST_F(CliTest, UnmatchedDeviceIsAClearError) {
    const PtRun r = run({"render", "--spp", "1", "--width", "8", "--height", "8", "--device", "NoSuchGpu9000", "-o",
        (dir_ / "x.exr").string()});
    EXPECT_EXIT_STATUS(r, 1);
    const std::string line = r.errorLine();
    EXPECT_NE(line.find("NoSuchGpu9000"), std::string::npos) << line;
    EXPECT_NE(line.find("pt devices"), std::string::npos) << line;
}

// The log's "pt: device ..." line.
std::string deviceLine(const std::string& log) {
    std::istringstream s(log);
    for (std::string line; std::getline(s, line);)
        if (line.rfind("pt: device ", 0) == 0) return line;
    return "";
}

// Where the user has not set them, pt sets two lavapipe threads a core and, on Intel CPUs with
// AVX-512, AVX2 code, and says so on the device line; variables the user set are left alone.
TEST_F(CliTest, LavapipeSettingsAreNamedAndYieldToTheUsers) {
    const std::vector<std::string> argv = {PT_BINARY, "render", kDiffuseScene.string(), "--spp", "1", "--width", "8",
        "--height", "8", "-o", (dir_ / "x.exr").string()};
    RunOptions options;
    options.dir = dir_;
    options.unset.insert({"LP_NUM_THREADS", "GALLIUM_OVERRIDE_CPU_CAPS"});
    const PtRun chosen = runProcess(argv, options);
    EXPECT_EXIT_STATUS(chosen, 0);
    const std::string line = deviceLine(chosen.err);
    if (line.find("llvmpipe") == std::string::npos) GTEST_SKIP() << "not lavapipe: " << line;
    cpu_set_t set;
    CPU_ZERO(&set);
    ASSERT_EQ(sched_getaffinity(0, sizeof set, &set), 0);
    const int threads = std::min(2 * CPU_COUNT(&set), 32);
    EXPECT_NE(line.find("LP_NUM_THREADS=" + std::to_string(threads)), std::string::npos) << line;
#if defined(__x86_64__) || defined(__i386__)
    __builtin_cpu_init();
    const bool intelAvx512 = __builtin_cpu_is("intel") && __builtin_cpu_supports("avx512f");
#else
    const bool intelAvx512 = false;
#endif
    EXPECT_EQ(line.find("GALLIUM_OVERRIDE_CPU_CAPS=avx") != std::string::npos, intelAvx512) << line;

    options.env = {{"LP_NUM_THREADS", "3"}, {"GALLIUM_OVERRIDE_CPU_CAPS", "avx"}};
    const PtRun users = runProcess(argv, options);
    EXPECT_EXIT_STATUS(users, 0);
    EXPECT_NE(deviceLine(users.err).find("llvmpipe"), std::string::npos) << users;
    EXPECT_EQ(deviceLine(users.err).find("settings pt chose"), std::string::npos) << users;
}

} // namespace
} // namespace pt::test
