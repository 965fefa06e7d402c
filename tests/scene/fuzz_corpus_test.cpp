// Replays every checked-in fuzz input (tests/fuzz/corpus/<target>/: the seeds and every input a
// fuzzer once crashed on) through the loaders in the ordinary build, checking the same contract
// as the fuzz targets: a consistent scene or one line naming the file. So a fixed crash stays
// fixed even where clang and libFuzzer are not installed.
#include "support/fuzz_inputs.h"
#include "support/load_contract.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace {

namespace fs = std::filesystem;
using pt::test::FuzzTarget;

const fs::path kFuzzDir = PT_FUZZ_DIR;

std::string readBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<fs::path> corpusFiles(FuzzTarget target) {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(kFuzzDir / "corpus" / pt::test::fuzzTargetName(target)))
        if (e.is_regular_file()) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

class FuzzCorpus : public ::testing::TestWithParam<FuzzTarget> {};

TEST_P(FuzzCorpus, EveryInputKeepsTheLoaderContract) {
    const auto files = corpusFiles(GetParam());
    EXPECT_GE(files.size(), 3u) << "the seed corpus should cover more than one kind of input";
    for (const fs::path& f : files)
        EXPECT_EQ(pt::test::fuzzOneInput(GetParam(), readBytes(f), kFuzzDir / "data"), "") << f;
}

INSTANTIATE_TEST_SUITE_P(Loaders, FuzzCorpus, ::testing::ValuesIn(pt::test::allFuzzTargets()),
    [](const ::testing::TestParamInfo<FuzzTarget>& info) { return std::string(pt::test::fuzzTargetName(info.param)); });

// The contract checks themselves must be able to fail, or the replay above proves nothing.
TEST(LoadContract, MessagesMustNameTheFileOnOneLine) {
    EXPECT_EQ(pt::test::messageProblem("a.ply: truncated", "a.ply"), "");
    EXPECT_NE(pt::test::messageProblem("truncated", "a.ply"), "");
    EXPECT_NE(pt::test::messageProblem("a.ply: ", "a.ply"), "");
    EXPECT_NE(pt::test::messageProblem("a.ply: two\nlines", "a.ply"), "");
    EXPECT_NE(pt::test::messageProblem("a.ply: " + std::string(5000, 'x'), "a.ply"), "");
}

TEST(LoadContract, ScenesMustBeConsistent) {
    pt::Scene s;
    EXPECT_NE(pt::test::sceneInconsistency(s), "") << "an empty scene";
    s.materials.emplace_back();
    pt::Mesh& m = s.meshes.emplace_back();
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    m.triangles = {{0, 1, 2}};
    EXPECT_EQ(pt::test::sceneInconsistency(s), "");
    m.triangles = {{0, 1, 3}};
    EXPECT_NE(pt::test::sceneInconsistency(s), "") << "index out of range";
    m.triangles = {{0, 1, 2}};
    m.material = 1;
    EXPECT_NE(pt::test::sceneInconsistency(s), "") << "material out of range";
    m.material = 0;
    m.positions[1].x = NAN;
    EXPECT_NE(pt::test::sceneInconsistency(s), "") << "NaN position";
}

} // namespace
