// pt render --samples A:B and pt merge: the merge of a partition of 0:N is the single --spp N
// render up to the last float rounding (measured here: at most one ulp, most values identical),
// and merge refuses parts that cannot belong together.
#include "image/image_io.h"
#include "support/pt_process.h"
#include "support/test_directory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace fs = std::filesystem;

namespace pt::test {
namespace {

// A small, quick render of the built-in Cornell box; every part and the single render share it.
const std::vector<std::string> kRender = {"render", "--width", "32", "--height", "24", "--max-depth", "4", "-q"};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
    args.insert(args.end(), more.begin(), more.end());
    return args;
}

// Distance in units in the last place between two finite floats of the same sign.
int64_t ulpDistance(float a, float b) {
    int32_t ia, ib;
    std::memcpy(&ia, &a, 4);
    std::memcpy(&ib, &b, 4);
    return std::abs(int64_t(ia) - int64_t(ib));
}

// ctest runs every test in its own process, so each test renders only the parts it needs.
class Partition : public ::testing::Test {
protected:
    void SetUp() override { dir_ = freshTestDirectory("partition"); }
    void TearDown() override {
        if (!HasFailure()) fs::remove_all(dir_); // keep the evidence of a failure
    }
    void render(const std::vector<std::string>& more) {
        const PtRun r = runPt(dir_, with(kRender, more));
        ASSERT_EQ(r.status, 0) << r.describe();
    }
    PtRun merge(const std::vector<std::string>& args) { return runPt(dir_, with({"merge"}, args)); }
    fs::path dir_;
};

TEST_F(Partition, MergeOfAPartitionEqualsTheSingleRenderUpToOneUlp) {
    // Parts are uniform (every pixel the same samples); so is the single render they equal.
    render({"--spp", "12", "--seed", "5", "--adaptive", "off", "-o", "single.exr"});
    render({"--samples", "0:5", "--seed", "5", "-o", "a.exr"});
    render({"--samples", "5:9", "--seed", "5", "-o", "b.exr"});
    render({"--samples", "9:12", "--seed", "5", "-o", "c.exr"});
    const PtRun r = merge({"c.exr", "a.exr", "b.exr", "-o", "merged.exr"}); // any order
    ASSERT_EQ(r.status, 0) << r.describe();
    ImageMetadata meta;
    const Image merged = readExr(dir_ / "merged.exr", &meta);
    const Image single = readExr(dir_ / "single.exr");
    EXPECT_EQ(meta["spp"], "12");
    EXPECT_EQ(meta["samples"], "0:12");
    EXPECT_TRUE(fs::exists(dir_ / "merged.png"));
    ASSERT_EQ(merged.rgba.size(), single.rgba.size());
    size_t identical = 0;
    int64_t worst = 0;
    for (size_t i = 0; i < merged.rgba.size(); ++i) {
        identical += merged.rgba[i] == single.rgba[i];
        worst = std::max(worst, ulpDistance(merged.rgba[i], single.rgba[i]));
    }
    std::printf("merge vs single render: %zu of %zu values bit-identical, worst %lld ulp\n", identical,
        merged.rgba.size(), static_cast<long long>(worst));
    EXPECT_LE(worst, 1);
    EXPECT_GT(identical, merged.rgba.size() * 9 / 10);

    // Merged files are parts again: (a + b) + c is the same image.
    ASSERT_EQ(merge({"a.exr", "b.exr", "-o", "ab.exr"}).status, 0);
    ASSERT_EQ(merge({"ab.exr", "c.exr", "-o", "abc.exr"}).status, 0);
    ImageMetadata nested;
    const Image abc = readExr(dir_ / "abc.exr", &nested);
    EXPECT_EQ(nested["spp"], "12");
    for (size_t i = 0; i < abc.rgba.size(); ++i) ASSERT_LE(ulpDistance(abc.rgba[i], merged.rgba[i]), 1) << i;

    // A gap is an error unless allowed; allowed, the image has the samples present.
    const PtRun refused = merge({"a.exr", "c.exr", "-o", "gap.exr"});
    EXPECT_EQ(refused.status, 1) << refused.describe();
    EXPECT_NE(refused.err.find("5:9"), std::string::npos) << refused.err;
    EXPECT_FALSE(fs::exists(dir_ / "gap.exr"));
    const PtRun allowed = merge({"a.exr", "c.exr", "--allow-gaps", "-o", "gap.exr"});
    ASSERT_EQ(allowed.status, 0) << allowed.describe();
    ImageMetadata gapMeta;
    readExr(dir_ / "gap.exr", &gapMeta);
    EXPECT_EQ(gapMeta["spp"], "8");
}

// Light tracing's splat sums are integers: parts of a light-traced render (the glass box, whose
// caustics are light traced) merge to the single render, and resuming needs the same setting.
TEST_F(Partition, LightTracedPartsMergeToTheSingleRender) {
    const std::string glass = std::string(PT_TEST_DATA_DIR) + "/references/cbox-glass-mirror/scene.gltf";
    const std::vector<std::string> scene = {
        "render", glass, "--width", "24", "--height", "24", "--max-depth", "8", "-q"};
    auto renderGlass = [&](const std::vector<std::string>& more) {
        const PtRun r = runPt(dir_, with(scene, more));
        ASSERT_EQ(r.status, 0) << r.describe();
    };
    renderGlass({"--spp", "6", "-o", "single.exr"});
    renderGlass({"--samples", "0:4", "-o", "a.exr"});
    renderGlass({"--samples", "4:6", "-o", "b.exr"});
    renderGlass({"--samples", "4:6", "--light-tracing", "off", "-o", "b-off.exr"});
    ASSERT_EQ(merge({"b.exr", "a.exr", "-o", "merged.exr"}).status, 0);
    ImageMetadata meta;
    const Image merged = readExr(dir_ / "merged.exr", &meta);
    const Image single = readExr(dir_ / "single.exr");
    EXPECT_EQ(meta["spp"], "6");
    ASSERT_EQ(merged.rgba.size(), single.rgba.size());
    for (size_t i = 0; i < merged.rgba.size(); ++i) ASSERT_LE(ulpDistance(merged.rgba[i], single.rgba[i]), 1) << i;
    const PtRun mixed = merge({"a.exr", "b-off.exr", "-o", "bad.exr"});
    EXPECT_EQ(mixed.status, 1) << mixed.describe();
    EXPECT_NE(mixed.err.find("light-tracing"), std::string::npos) << mixed.err;
    EXPECT_FALSE(fs::exists(dir_ / "bad.exr"));
    // A part carries the splat sums too: resuming it (last: it checkpoints into a.exr) is
    // bit-identical.
    renderGlass({"--spp", "6", "--resume", (dir_ / "a.exr").string(), "-o", "resumed.exr"});
    EXPECT_EQ(readExr(dir_ / "resumed.exr").rgba, single.rgba);
}

// BDPT splats its light subpaths' camera connections into the same integer sums: its parts merge
// to the single render, a resumed part is bit-identical, and a part by the path tracer is refused.
TEST_F(Partition, BidirectionalPartsMergeToTheSingleRender) {
    const std::vector<std::string> scene = {"render", "--width", "24", "--height", "24", "--max-depth", "5", "-q"};
    auto renderBdpt = [&](std::vector<std::string> more) {
        if (std::find(more.begin(), more.end(), "--integrator") == more.end())
            more.insert(more.end(), {"--integrator", "bdpt"});
        const PtRun r = runPt(dir_, with(scene, more));
        ASSERT_EQ(r.status, 0) << r.describe();
    };
    renderBdpt({"--spp", "6", "-o", "single.exr"});
    renderBdpt({"--samples", "0:4", "-o", "a.exr"});
    renderBdpt({"--samples", "4:6", "-o", "b.exr"});
    renderBdpt({"--samples", "4:6", "--integrator", "path", "-o", "b-path.exr"});
    ASSERT_EQ(merge({"b.exr", "a.exr", "-o", "merged.exr"}).status, 0);
    ImageMetadata meta;
    const Image merged = readExr(dir_ / "merged.exr", &meta);
    const Image single = readExr(dir_ / "single.exr");
    EXPECT_NE(meta["features"].find("bdpt"), std::string::npos) << meta["features"];
    ASSERT_EQ(merged.rgba.size(), single.rgba.size());
    for (size_t i = 0; i < merged.rgba.size(); ++i) ASSERT_LE(ulpDistance(merged.rgba[i], single.rgba[i]), 1) << i;
    const PtRun mixed = merge({"a.exr", "b-path.exr", "-o", "bad.exr"});
    EXPECT_EQ(mixed.status, 1) << mixed.describe();
    EXPECT_NE(mixed.err.find("integrator=path"), std::string::npos) << mixed.err;
    EXPECT_FALSE(fs::exists(dir_ / "bad.exr"));
    renderBdpt({"--spp", "6", "--resume", (dir_ / "a.exr").string(), "-o", "resumed.exr"});
    EXPECT_EQ(readExr(dir_ / "resumed.exr").rgba, single.rgba);
}

// Vertex merging renders a part's rounds as the whole render does (each round's light subpaths,
// the pilot and the radius of each round by its sample index): its parts merge to the single
// render, and a resumed part is bit-identical.
TEST_F(Partition, VertexMergingPartsMergeToTheSingleRender) {
    const std::vector<std::string> scene = {
        "render", "--width", "24", "--height", "24", "--max-depth", "5", "--integrator", "vcm", "-q"};
    auto renderVcm = [&](const std::vector<std::string>& more) {
        const PtRun r = runPt(dir_, with(scene, more));
        ASSERT_EQ(r.status, 0) << r.describe();
    };
    renderVcm({"--spp", "6", "-o", "single.exr"});
    renderVcm({"--samples", "0:4", "-o", "a.exr"});
    renderVcm({"--samples", "4:6", "-o", "b.exr"});
    ASSERT_EQ(merge({"b.exr", "a.exr", "-o", "merged.exr"}).status, 0);
    ImageMetadata meta;
    const Image merged = readExr(dir_ / "merged.exr", &meta);
    const Image single = readExr(dir_ / "single.exr");
    EXPECT_NE(meta["features"].find("merging"), std::string::npos) << meta["features"];
    ASSERT_EQ(merged.rgba.size(), single.rgba.size());
    for (size_t i = 0; i < merged.rgba.size(); ++i) ASSERT_LE(ulpDistance(merged.rgba[i], single.rgba[i]), 1) << i;
    renderVcm({"--spp", "6", "--resume", (dir_ / "a.exr").string(), "-o", "resumed.exr"});
    EXPECT_EQ(readExr(dir_ / "resumed.exr").rgba, single.rgba);
}

TEST_F(Partition, MergeRefusesOverlapsOtherRendersAndPlainImages) {
    render({"--samples", "0:5", "--seed", "5", "-o", "a.exr"});
    render({"--samples", "4:9", "--seed", "5", "-o", "overlapping.exr"});
    render({"--samples", "9:12", "--seed", "6", "-o", "other-seed.exr"});
    const PtRun overlap = merge({"a.exr", "overlapping.exr", "-o", "bad.exr"});
    EXPECT_EQ(overlap.status, 1) << overlap.describe();
    EXPECT_NE(overlap.err.find("overlap"), std::string::npos) << overlap.err;
    const PtRun seed = merge({"a.exr", "other-seed.exr", "-o", "bad.exr"});
    EXPECT_EQ(seed.status, 1) << seed.describe();
    EXPECT_NE(seed.err.find("seed"), std::string::npos) << seed.err;
    Image plain; // a normal render's output has no state channels
    plain.width = 32;
    plain.height = 24;
    plain.rgba.assign(32 * 24 * 4, 0.5f);
    writeExr(dir_ / "plain.exr", plain, {});
    const PtRun notAPart = merge({"a.exr", "plain.exr", "-o", "bad.exr"});
    EXPECT_EQ(notAPart.status, 1) << notAPart.describe();
    EXPECT_NE(notAPart.err.find("plain.exr"), std::string::npos) << notAPart.err;
    EXPECT_FALSE(fs::exists(dir_ / "bad.exr"));
}

} // namespace
} // namespace pt::test
