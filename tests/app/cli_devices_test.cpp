// pt and the Vulkan devices: pt devices lists one, no driver and an unmatched --device are one
// clear error line each.
#include "cli_fixture.h"
#include "support/malformed_corpus.h"

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

} // namespace
} // namespace pt::test
