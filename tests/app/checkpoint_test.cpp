// Long renders that survive interruption: SIGTERM/SIGINT mid-render save the checkpoint and a
// partial image and exit 143/130; --resume continues to an image bit-identical to an
// uninterrupted render; a lost device or exhausted device memory (PT_FAULT test hook) gives
// one error line and a non-zero exit after saving the progress so far.
#include "image/image_io.h"
#include "support/pt_process.h"
#include "support/test_directory.h"

#include <gtest/gtest.h>

#include <signal.h>

#include <algorithm>

namespace fs = std::filesystem;

namespace pt::test {
namespace {

// Many one-sample passes, a checkpoint after each: slow enough to be interrupted mid-way.
const std::vector<std::string> kRender = {
    "render", "--width", "32", "--height", "24", "--max-depth", "4", "--pass-spp", "1", "-q"};

// The render every test resumes to: seed 9, 300 spp, unless `more` says otherwise.
std::vector<std::string> with(const std::vector<std::string>& more) {
    std::vector<std::string> args = kRender;
    auto has = [&](const char* option) { return std::find(more.begin(), more.end(), option) != more.end(); };
    if (!has("--seed")) args.insert(args.end(), {"--seed", "9"});
    if (!has("--spp")) args.insert(args.end(), {"--spp", "300"});
    args.insert(args.end(), more.begin(), more.end());
    return args;
}

std::string errorLines(const std::string& err) {
    std::string lines;
    size_t count = 0, start = 0;
    while ((start = err.find("pt: error: ", start)) != std::string::npos)
        ++count, lines += err.substr(start, err.find('\n', start) - start), ++start;
    return std::to_string(count) + ": " + lines;
}

// ctest runs every test in its own process: the uninterrupted render is made by the tests that
// compare with it.
class Checkpoint : public ::testing::Test {
protected:
    void SetUp() override { dir_ = freshTestDirectory("checkpoint"); }
    void TearDown() override {
        if (!HasFailure()) fs::remove_all(dir_);
    }
    void renderUninterrupted() {
        const PtRun r = runPt(dir_, with({"-o", "uninterrupted.exr"}));
        ASSERT_EQ(r.status, 0) << r.describe();
        uninterrupted_ = readExr(dir_ / "uninterrupted.exr");
    }

    // Sends `signal` once the checkpoint file exists, then resumes; returns the final image.
    void interruptAndResume(int signal, int expectedStatus, const std::string& name) {
        const fs::path checkpoint = dir_ / (name + ".ckpt.exr");
        bool sent = false;
        const PtRun first =
            runPt(dir_, with({"-o", name + ".exr", "--checkpoint", checkpoint.string(), "--checkpoint-every", "0"}), {},
                [&](pid_t pid, double) {
                    if (!sent && fs::exists(checkpoint)) sent = ::kill(pid, signal) == 0;
                });
        ASSERT_TRUE(sent) << "the render finished before a checkpoint appeared\n" << first.describe();
        ASSERT_EQ(first.status, expectedStatus) << first.describe();
        EXPECT_FALSE(first.signaled);
        ImageMetadata partial, saved;
        readExr(dir_ / (name + ".exr"), &partial);
        readExr(checkpoint, &saved);
        EXPECT_EQ(partial["spp"], saved["spp"]);
        EXPECT_LT(std::stoi(saved["spp"]), 300) << "not interrupted mid-way";
        const PtRun resumed = runPt(dir_, with({"-o", name + ".exr", "--resume", checkpoint.string()}));
        ASSERT_EQ(resumed.status, 0) << resumed.describe();
        ImageMetadata meta;
        const Image image = readExr(dir_ / (name + ".exr"), &meta);
        EXPECT_EQ(meta["spp"], "300");
        EXPECT_EQ(image.rgba, uninterrupted_.rgba) << "resumed render differs from the uninterrupted one";
    }

    fs::path dir_;
    Image uninterrupted_;
};

TEST_F(Checkpoint, SigtermAndSigintSaveAndResumeIsBitIdentical) {
    renderUninterrupted();
    interruptAndResume(SIGTERM, 143, "term");
    interruptAndResume(SIGINT, 130, "int");
}

TEST_F(Checkpoint, ResumeRefusesACheckpointOfAnotherRender) {
    const fs::path checkpoint = dir_ / "other.ckpt.exr";
    ASSERT_EQ(runPt(dir_, with({"--spp", "2", "-o", "other.exr", "--checkpoint", checkpoint.string()})).status, 0);
    const PtRun r = runPt(dir_, with({"--seed", "10", "-o", "other2.exr", "--resume", checkpoint.string()}));
    EXPECT_EQ(r.status, 1) << r.describe();
    EXPECT_EQ(errorLines(r.err).substr(0, 2), "1:") << r.err;
    EXPECT_NE(r.err.find("another render"), std::string::npos) << r.err;
}

TEST_F(Checkpoint, DeviceLostSavesProgressThenResumesBitIdentically) {
    renderUninterrupted();
    const fs::path checkpoint = dir_ / "lost.ckpt.exr";
    // The 40th submission and every later one report VK_ERROR_DEVICE_LOST.
    const PtRun lost =
        runPt(dir_, with({"-o", "lost.exr", "--checkpoint", checkpoint.string(), "--checkpoint-every", "0"}),
            {{"PT_FAULT", "device-lost@40"}});
    EXPECT_EQ(lost.status, 1) << lost.describe();
    EXPECT_EQ(errorLines(lost.err).substr(0, 2), "1:") << lost.err;
    EXPECT_NE(lost.err.find("device lost"), std::string::npos) << lost.err;
    EXPECT_NE(lost.err.find("saved"), std::string::npos) << lost.err;
    ImageMetadata partial;
    readExr(dir_ / "lost.exr", &partial);
    EXPECT_GT(std::stoi(partial["spp"]), 0);
    EXPECT_LT(std::stoi(partial["spp"]), 300);
    const PtRun resumed = runPt(dir_, with({"-o", "lost.exr", "--resume", checkpoint.string()}));
    ASSERT_EQ(resumed.status, 0) << resumed.describe();
    EXPECT_EQ(readExr(dir_ / "lost.exr").rgba, uninterrupted_.rgba);
}

TEST_F(Checkpoint, OutOfDeviceMemoryIsOneLineAndLeavesTheCheckpointIntact) {
    const fs::path checkpoint = dir_ / "oom.ckpt.exr";
    ASSERT_EQ(runPt(dir_, with({"--spp", "3", "-o", "oom.exr", "--checkpoint", checkpoint.string()})).status, 0);
    const auto before = fs::last_write_time(checkpoint);
    for (const char* fault : {"out-of-memory@1", "out-of-memory@3"}) {
        const PtRun r = runPt(dir_, with({"-o", "oom2.exr", "--resume", checkpoint.string()}), {{"PT_FAULT", fault}});
        EXPECT_EQ(r.status, 1) << fault << r.describe();
        EXPECT_FALSE(r.signaled);
        EXPECT_EQ(errorLines(r.err).substr(0, 2), "1:") << r.err;
        EXPECT_NE(r.err.find("out of device memory"), std::string::npos) << r.err;
    }
    EXPECT_EQ(fs::last_write_time(checkpoint), before);
    ImageMetadata meta;
    readExr(checkpoint, &meta);
    EXPECT_EQ(meta["spp"], "3");
}

} // namespace
} // namespace pt::test
