// The Ray driver (tools/pt_ray) on a local Ray cluster started by the driver (ray.init with two
// local worker CPUs): a 4-chunk render equals the single render, a re-run skips the parts
// already there, and killing a Ray worker mid-chunk still gives the full image (Ray resubmits
// the lost task). Skipped when the venv of scripts/setup.sh (PT_RAY_PYTHON) is missing.
#include "image/image_io.h"
#include "support/pt_process.h"
#include "support/test_directory.h"

#include <gtest/gtest.h>

#include <signal.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

namespace fs = std::filesystem;

namespace pt::test {
namespace {

const std::string kPtArgs = "--width 32 --height 24 --max-depth 4 --seed 3 --pass-spp 1";

// The command line of process `pid`, arguments separated by spaces ("" if it is gone).
std::string commandLine(pid_t pid) {
    std::string text = readFile("/proc/" + std::to_string(pid) + "/cmdline");
    std::replace(text.begin(), text.end(), '\0', ' ');
    return text;
}

pid_t parentOf(pid_t pid) {
    std::istringstream stat(readFile("/proc/" + std::to_string(pid) + "/stat"));
    std::string field;
    for (int i = 0; i < 4 && stat >> field; ++i)
        if (i == 3) return static_cast<pid_t>(std::stol(field));
    return -1;
}

// A Ray worker process running a chunk: the parent of a `pt render --samples` process.
pid_t findChunkWorker() {
    for (const auto& entry : fs::directory_iterator("/proc")) {
        const std::string name = entry.path().filename().string();
        if (name.find_first_not_of("0123456789") != std::string::npos) continue;
        const pid_t pid = static_cast<pid_t>(std::stol(name));
        const std::string cmd = commandLine(pid);
        if (cmd.rfind(std::string(PT_BINARY) + " render", 0) != 0 || cmd.find("--samples") == std::string::npos)
            continue;
        const pid_t parent = parentOf(pid);
        if (parent > 1 && commandLine(parent).rfind("ray::", 0) == 0) return parent;
    }
    return -1;
}

class RayDriver : public ::testing::Test {
protected:
    void SetUp() override {
        if (!fs::exists(PT_RAY_PYTHON)) GTEST_SKIP() << PT_RAY_PYTHON << " missing: run scripts/setup.sh";
        dir_ = freshTestDirectory("ray");
        const PtRun r =
            runPt(dir_, {"render", "--spp", "16", "--width", "32", "--height", "24", "--max-depth", "4", "--seed", "3",
                            "--adaptive", "off", "-o", "single.exr", "-q"}); // parts are uniform
        ASSERT_EQ(r.status, 0) << r.describe();
    }
    void TearDown() override {
        if (!dir_.empty() && !HasFailure()) fs::remove_all(dir_);
    }
    PtRun driver(const std::string& output, const std::function<void(pid_t, double)>& whileRunning = {}) {
        return runProgram(dir_,
            {PT_RAY_PYTHON, "-m", "pt_ray", "render", "--spp", "16", "--chunks", "4", "--num-cpus", "2", "--pt",
                PT_BINARY, "--pt-args", kPtArgs, "-o", output},
            {{"PYTHONPATH", PT_RAY_PACKAGE_DIR}, {"RAY_USAGE_STATS_ENABLED", "0"}}, whileRunning, 240);
    }
    // The merged image equals the single render up to the last rounding (in practice exactly).
    void expectEqualsSingleRender(const std::string& output) {
        ImageMetadata meta;
        const Image merged = readExr(dir_ / output, &meta);
        const Image single = readExr(dir_ / "single.exr");
        EXPECT_EQ(meta["spp"], "16");
        EXPECT_EQ(meta["merged_parts"], "4");
        ASSERT_EQ(merged.rgba.size(), single.rgba.size());
        size_t identical = 0;
        for (size_t i = 0; i < merged.rgba.size(); ++i) {
            identical += merged.rgba[i] == single.rgba[i];
            ASSERT_LE(std::abs(merged.rgba[i] - single.rgba[i]), std::abs(single.rgba[i]) * 1.2e-7f) << "value " << i;
        }
        std::printf("%s: %zu of %zu values bit-identical to the single render\n", output.c_str(), identical,
            merged.rgba.size());
    }
    fs::path dir_;
};

TEST_F(RayDriver, FourChunksEqualTheSingleRenderAndAReRunSkipsThem) {
    const PtRun r = driver("four.exr");
    ASSERT_EQ(r.status, 0) << r.describe();
    expectEqualsSingleRender("four.exr");
    const PtRun again = driver("four.exr");
    ASSERT_EQ(again.status, 0) << again.describe();
    EXPECT_NE(again.err.find("4 already rendered"), std::string::npos) << again.err;
    expectEqualsSingleRender("four.exr");
}

TEST_F(RayDriver, KillingAWorkerMidChunkStillGivesTheFullImage) {
    bool killed = false;
    const PtRun r = driver("killed.exr", [&](pid_t, double) {
        if (killed) return;
        if (const pid_t worker = findChunkWorker(); worker > 0) killed = ::kill(worker, SIGKILL) == 0;
    });
    ASSERT_TRUE(killed) << "no Ray worker running a chunk was found\n" << r.describe();
    ASSERT_EQ(r.status, 0) << r.describe();
    expectEqualsSingleRender("killed.exr");
}

} // namespace
} // namespace pt::test
