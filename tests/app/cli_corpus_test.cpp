// pt render on the malformed corpora (glTF, course XML, PLY): exit 1 within a second, one error
// line naming the file and its README's problem, nothing written.
#include "cli_fixture.h"
#include "support/malformed_corpus.h"

#include <cstring>

namespace pt::test {
namespace {

// ---------------------------------------------------------------------------------------------
// The malformed corpora: tests/data/malformed_{gltf,xml,ply}/README.md list each file with the
// lowercase substring its error must contain once the file's own path is removed.

std::map<std::string, std::string> expectedSubstrings() { return pt::test::malformedCorpusExpectations(); }
std::vector<std::string> corpusFiles() { return pt::test::malformedCorpusFiles(); }

TEST(CliCorpus, ReadmeTableCoversEveryCorpusFile) {
    const auto expected = expectedSubstrings();
    const auto files = corpusFiles();
    EXPECT_GE(files.size(), 32u);
    for (const auto& f : files) EXPECT_EQ(expected.count(f), 1u) << f << " has no row in README.md";
}

class MalformedCorpus : public CliTest, public ::testing::WithParamInterface<std::string> {
protected:
    // `pt render` on one corpus file: exit 1 (not a signal) within one second of wall time, one
    // error line naming the file and containing the README's substring, and no output written.
    // No --width/--height: a size the file asks for (absurd or not) must be judged before rendering.
    void checkCorpusFile(const std::string& corpus, const std::string& name) {
        const auto expected = pt::test::malformedCorpusExpectations(corpus);
        const auto it = expected.find(name);
        ASSERT_NE(it, expected.end()) << name << " has no expected substring in README.md";
        const std::string file = (kTests / "data" / corpus / name).string();

        const PtRun r = run({"render", file, "--spp", "1", "-o", (dir_ / "x.exr").string()}, {}, 10);
        EXPECT_EXIT_STATUS(r, 1);
        EXPECT_LT(r.seconds, 1.0) << r;
        const std::string line = r.errorLine();
        EXPECT_NE(line.find(file), std::string::npos) << "the error does not name " << file << ": " << line;
        const std::string problem = lower(removeAll(line.substr(std::strlen("pt: error: ")), file));
        EXPECT_NE(problem.find(it->second), std::string::npos) << "expected '" << it->second << "' in: " << line;
        EXPECT_FALSE(fs::exists(dir_ / "x.exr"));
        EXPECT_FALSE(fs::exists(dir_ / "x.png"));
        EXPECT_TRUE(outputs().empty()) << "left " << outputs().front();
    }
};

TEST_P(MalformedCorpus, FailsWithOneLineNamingFileAndProblem) { checkCorpusFile("malformed_gltf", GetParam()); }

class MalformedXmlCorpus : public MalformedCorpus {};
TEST_P(MalformedXmlCorpus, FailsWithOneLineNamingFileAndProblem) { checkCorpusFile("malformed_xml", GetParam()); }

class MalformedPlyCorpus : public MalformedCorpus {};
TEST_P(MalformedPlyCorpus, FailsWithOneLineNamingFileAndProblem) { checkCorpusFile("malformed_ply", GetParam()); }

TEST(CliCorpus, XmlReadmeTableCoversEveryCorpusFile) {
    const auto expected = pt::test::malformedCorpusExpectations("malformed_xml");
    const auto files = pt::test::malformedCorpusFiles("malformed_xml");
    EXPECT_GE(files.size(), 26u);
    for (const auto& f : files) EXPECT_EQ(expected.count(f), 1u) << f << " has no row in README.md";
}

TEST(CliCorpus, PlyReadmeTableCoversEveryCorpusFile) {
    const auto expected = pt::test::malformedCorpusExpectations("malformed_ply");
    const auto files = pt::test::malformedCorpusFiles("malformed_ply");
    EXPECT_GE(files.size(), 14u);
    for (const auto& f : files) EXPECT_EQ(expected.count(f), 1u) << f << " has no row in README.md";
}

// Issue 7 asks for at least 40 kinds of malformed input across the three formats.
TEST(CliCorpus, AtLeastFortyKindsAcrossTheFormats) {
    size_t kinds = 0;
    for (const char* corpus : {"malformed_gltf", "malformed_xml", "malformed_ply"})
        kinds += pt::test::malformedCorpusFiles(corpus).size();
    EXPECT_GE(kinds, 40u);
}

INSTANTIATE_TEST_SUITE_P(Corpus, MalformedCorpus, ::testing::ValuesIn(corpusFiles()), corpusParamName);
INSTANTIATE_TEST_SUITE_P(XmlCorpus, MalformedXmlCorpus,
    ::testing::ValuesIn(pt::test::malformedCorpusFiles("malformed_xml")), corpusParamName);
INSTANTIATE_TEST_SUITE_P(PlyCorpus, MalformedPlyCorpus,
    ::testing::ValuesIn(pt::test::malformedCorpusFiles("malformed_ply")), corpusParamName);

} // namespace
} // namespace pt::test
