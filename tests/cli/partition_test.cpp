// pt render --samples A:B and pt merge: the merge of a partition of 0:N is the single --spp N
// render up to the last float rounding (measured here: at most one ulp, most values identical),
// and merge refuses parts that cannot belong together.
#include "render/image_io.h"
#include "support/pt_process.h"

#include <gtest/gtest.h>

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

class Partition : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        dir_ = freshTestDirectory("partition");
        auto run = [](const std::vector<std::string>& more) {
            const PtRun r = runPt(dir_, with(kRender, more));
            ASSERT_EQ(r.status, 0) << r.describe();
        };
        run({"--spp", "12", "--seed", "5", "-o", "single.exr"});
        run({"--samples", "0:5", "--seed", "5", "-o", "a.exr"});
        run({"--samples", "5:9", "--seed", "5", "-o", "b.exr"});
        run({"--samples", "9:12", "--seed", "5", "-o", "c.exr"});
        run({"--samples", "4:9", "--seed", "5", "-o", "overlapping.exr"});
        run({"--samples", "9:12", "--seed", "6", "-o", "other-seed.exr"});
    }
    static void TearDownTestSuite() { fs::remove_all(dir_); }
    static PtRun merge(const std::vector<std::string>& args) { return runPt(dir_, with({"merge"}, args)); }
    static fs::path dir_;
};
fs::path Partition::dir_;

TEST_F(Partition, MergeOfAPartitionEqualsTheSingleRenderUpToOneUlp) {
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
}

TEST_F(Partition, MergeRefusesOverlappingRanges) {
    const PtRun r = merge({"a.exr", "overlapping.exr", "c.exr", "-o", "bad.exr"});
    EXPECT_EQ(r.status, 1) << r.describe();
    EXPECT_NE(r.err.find("overlap"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "bad.exr"));
}

TEST_F(Partition, MergeReportsGapsAndMergesThemOnlyWhenAllowed) {
    const PtRun refused = merge({"a.exr", "c.exr", "-o", "gap.exr"});
    EXPECT_EQ(refused.status, 1) << refused.describe();
    EXPECT_NE(refused.err.find("5:9"), std::string::npos) << refused.err;
    const PtRun allowed = merge({"a.exr", "c.exr", "--allow-gaps", "-o", "gap.exr"});
    ASSERT_EQ(allowed.status, 0) << allowed.describe();
    ImageMetadata meta;
    readExr(dir_ / "gap.exr", &meta);
    EXPECT_EQ(meta["spp"], "8");
}

TEST_F(Partition, MergeRefusesPartsOfAnotherRender) {
    const PtRun r = merge({"a.exr", "b.exr", "other-seed.exr", "-o", "mixed.exr"});
    EXPECT_EQ(r.status, 1) << r.describe();
    EXPECT_NE(r.err.find("seed"), std::string::npos) << r.err;
    const PtRun plain = merge({"a.exr", "single.exr", "-o", "mixed.exr"}); // a normal render has no state
    EXPECT_EQ(plain.status, 1) << plain.describe();
    EXPECT_NE(plain.err.find("single.exr"), std::string::npos) << plain.err;
}

TEST_F(Partition, MergedPartsMergeAgain) {
    ASSERT_EQ(merge({"a.exr", "b.exr", "-o", "ab.exr"}).status, 0);
    const PtRun r = merge({"ab.exr", "c.exr", "-o", "abc.exr"});
    ASSERT_EQ(r.status, 0) << r.describe();
    ImageMetadata meta;
    readExr(dir_ / "abc.exr", &meta);
    EXPECT_EQ(meta["spp"], "12");
}

} // namespace
} // namespace pt::test
