// The pipeline cache across processes: the first render fills it, the second uses it, both make
// the same image; a damaged entry is replaced without changing the image; --no-pipeline-cache
// writes nothing; a cache folder that cannot be made costs one warning, not the render; the
// measured choice of texel loads is remembered there.
#include "cli_fixture.h"
#include "image/image_io.h"

#include <fstream>

namespace pt::test {
namespace {

std::vector<std::string> renderArgs(const fs::path& exr) {
    // path: one kernel (`auto` first measures with a kernel of its own; CliTest.AutoIntegrator...);
    // texel loads on: `auto` would first measure them with two kernels of its own (and remember the
    // answer there too; TexelLoadChoice.*, CliTest.TexelLoadsMeasuredOnceAndRemembered).
    return {"render", "-o", exr.string(), "--spp", "4", "--width", "24", "--height", "24", "--integrator", "path",
        "--texel-loads", "on"};
}

std::vector<fs::path> entries(const fs::path& dir, const std::string& prefix) {
    std::vector<fs::path> found;
    if (!fs::exists(dir)) return found;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().filename().string().starts_with(prefix)) found.push_back(e.path());
    return found;
}

void expectSamePixels(const fs::path& a, const fs::path& b) {
    const Image x = readExr(a), y = readExr(b);
    ASSERT_EQ(x.width, y.width);
    ASSERT_EQ(x.height, y.height);
    EXPECT_TRUE(x.rgba == y.rgba) << a << " and " << b << " differ";
}

TEST_F(CliTest, PipelineCacheFilledByTheFirstRenderAndUsedByTheSecond) {
    const std::map<std::string, std::string> env = {{"XDG_CACHE_HOME", (dir_ / "cache").string()}};
    const fs::path cache = dir_ / "cache" / "pt";

    const PtRun first = run(renderArgs(dir_ / "first.exr"), env);
    EXPECT_EXIT_STATUS(first, 0);
    EXPECT_NE(first.err.find("(specialised kernel)"), std::string::npos) << first;
    const auto spirv = entries(cache, "spirv-");
    ASSERT_EQ(spirv.size(), 1u) << first;
    EXPECT_EQ(entries(cache, "vulkan-").size(), 1u) << first; // the driver's cache, per device

    const PtRun second = run(renderArgs(dir_ / "second.exr"), env);
    EXPECT_EXIT_STATUS(second, 0);
    EXPECT_NE(second.err.find("(cached kernel)"), std::string::npos) << second;
    expectSamePixels(dir_ / "first.exr", dir_ / "second.exr");

    // Damage the specialised kernel: the third render notices, specialises again, same image.
    {
        std::fstream f(spirv[0], std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(200);
        f.write("garbage!", 8);
    }
    const PtRun third = run(renderArgs(dir_ / "third.exr"), env);
    EXPECT_EXIT_STATUS(third, 0);
    EXPECT_NE(third.err.find("is invalid or from another build; replacing it"), std::string::npos) << third;
    EXPECT_NE(third.err.find("(specialised kernel)"), std::string::npos) << third;
    expectSamePixels(dir_ / "first.exr", dir_ / "third.exr");
    const PtRun fourth = run(renderArgs(dir_ / "fourth.exr"), env);
    EXPECT_NE(fourth.err.find("(cached kernel)"), std::string::npos) << fourth; // repaired
}

TEST_F(CliTest, NoPipelineCacheReadsAndWritesNothing) {
    const std::map<std::string, std::string> env = {{"XDG_CACHE_HOME", (dir_ / "cache").string()}};
    auto args = renderArgs(dir_ / "a.exr");
    args.push_back("--no-pipeline-cache");
    const PtRun r = run(args, env);
    EXPECT_EXIT_STATUS(r, 0);
    EXPECT_NE(r.err.find("(specialised kernel)"), std::string::npos) << r;
    EXPECT_FALSE(fs::exists(dir_ / "cache" / "pt")) << r;
}

TEST_F(CliTest, UnwritablePipelineCacheCostsOneWarning) {
    std::ofstream(dir_ / "not-a-folder") << "x";
    const PtRun r = run(renderArgs(dir_ / "a.exr"), {{"XDG_CACHE_HOME", (dir_ / "not-a-folder").string()}});
    EXPECT_EXIT_STATUS(r, 0);
    const size_t warning = r.err.find("pt: warning: pipeline cache:");
    EXPECT_NE(warning, std::string::npos) << r;
    EXPECT_EQ(r.err.find("pt: warning: pipeline cache:", warning + 1), std::string::npos) << r;
    EXPECT_TRUE(fs::exists(dir_ / "a.exr"));
}

TEST_F(CliTest, TexelLoadsMeasuredOnceAndRemembered) {
    const std::map<std::string, std::string> env = {{"XDG_CACHE_HOME", (dir_ / "cache").string()}};
    auto args = renderArgs(dir_ / "a.exr");
    args.resize(args.size() - 2); // the default, auto
    const PtRun first = run(args, env);
    EXPECT_EXIT_STATUS(first, 0);
    EXPECT_NE(first.err.find("pt: geometry loads: "), std::string::npos) << first;
    EXPECT_NE(first.err.find("(measured now on this machine"), std::string::npos) << first;
    EXPECT_EQ(entries(dir_ / "cache" / "pt", "texel-loads").size(), 1u) << first;
    const PtRun second = run(args, env);
    EXPECT_NE(second.err.find("(measured earlier on this machine"), std::string::npos) << second;
    // Without a cache folder nothing is measured: texel loads, as before.
    args.push_back("--no-pipeline-cache");
    const PtRun third = run(args, env);
    EXPECT_EQ(third.err.find("geometry loads"), std::string::npos) << third;
    EXPECT_NE(third.err.find("texel-loads"), std::string::npos) << third; // in the kernel's features
}

} // namespace
} // namespace pt::test
