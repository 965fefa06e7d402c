// The glTF loader on the malformed corpus (tests/data/malformed_gltf/README.md): every file throws
// one-line pt::SceneError "<file>: <problem>" with the README's substring in <problem>.
#include "support/malformed_corpus.h"
#include "scene/gltf/gltf_loader.h"
#include "scene/scene_error.h"
#include "scene/scene_loader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>
#include <typeinfo>
#include <vector>

namespace fs = std::filesystem;

namespace pt::test {
namespace {

const fs::path kTests = PT_TEST_DATA_DIR;
const fs::path kCorpus = kTests / "data" / "malformed_gltf";

std::map<std::string, std::string> expectedSubstrings() { return pt::test::malformedCorpusExpectations(); }
std::vector<std::string> corpusFiles() { return pt::test::malformedCorpusFiles(); }

TEST(GltfLoaderCorpus, ReadmeTableCoversEveryCorpusFile) {
    const auto expected = expectedSubstrings();
    const auto files = corpusFiles();
    EXPECT_GE(files.size(), 21u);
    for (const auto& f : files) EXPECT_EQ(expected.count(f), 1u) << f << " has no row in README.md";
    for (const auto& [f, sub] : expected) EXPECT_TRUE(fs::exists(kCorpus / f)) << f << " is in README.md but missing";
}

class MalformedGltf : public ::testing::TestWithParam<std::string> {};

TEST_P(MalformedGltf, ThrowsSceneErrorNamingFileAndProblem) {
    const auto expected = expectedSubstrings();
    auto it = expected.find(GetParam());
    ASSERT_NE(it, expected.end()) << GetParam() << " has no expected substring in README.md";
    const fs::path path = kCorpus / GetParam();
    const std::string name = path.string();
    try {
        pt::loadGltfFile(path);
        FAIL() << name << " loaded without an error";
    } catch (const pt::SceneError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.rfind(name + ": ", 0), 0u) << "what() does not start with the path: " << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << "not one line: " << what;
        const std::string problem = lower(removeAll(what, name));
        EXPECT_NE(problem.find(it->second), std::string::npos)
            << "expected '" << it->second << "' in the problem: " << what;
        EXPECT_GT(trim(removeAll(problem, ":")).size(), it->second.size()) << "problem text too terse: " << what;
    } catch (const std::exception& e) {
        FAIL() << "threw a " << typeid(e).name() << " that is not a pt::SceneError: " << e.what();
    }
    // Through the extension dispatch too.
    EXPECT_THROW(pt::loadScene(path), pt::SceneError);
}

INSTANTIATE_TEST_SUITE_P(Corpus, MalformedGltf, ::testing::ValuesIn(corpusFiles()), pt::test::corpusParamName);

} // namespace
} // namespace pt::test
