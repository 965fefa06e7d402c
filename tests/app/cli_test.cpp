// The pt binary as a user runs it: exit statuses, one-line error messages, outputs written (or
// not), on the malformed glTF corpus, bad command lines, bad paths and a few small renders.
//
// Every test runs pt in its own temporary directory (its working directory too, so a default
// output path could not litter the source tree), with stdout and stderr captured to files.
#include "support/malformed_corpus.h"
#include "support/pt_process.h"
#include "support/test_directory.h"
#include "image/image_io.h"
#include "film/metrics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kTests = PT_TEST_DATA_DIR;
const fs::path kDiffuseScene = kTests / "references" / "cbox-diffuse" / "scene.gltf";
const fs::path kDiffuseReference = kTests / "references" / "cbox-diffuse" / "reference.exr";

using pt::test::PtRun;
using pt::test::readFile;

using pt::test::lower;
using pt::test::removeAll;

class CliTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = pt::test::freshTestDirectory("cli");
        captureDir_ = dir_ / ".capture";
        fs::create_directories(captureDir_);
    }
    void TearDown() override {
        std::error_code ignored;
        if (!HasFailure()) fs::remove_all(dir_, ignored); // keep the evidence of a failure
    }

    // Runs `pt args...` in dir_ with `env` added to (and PT_VALIDATION and PT_FAULT removed from,
    // unless given) the environment, stdout and stderr captured; kills it after `timeoutSeconds`.
    PtRun run(const std::vector<std::string>& args, const std::map<std::string, std::string>& env = {},
        double timeoutSeconds = 30) {
        std::vector<std::string> argv = {PT_BINARY};
        argv.insert(argv.end(), args.begin(), args.end());
        pt::test::RunOptions options;
        options.dir = dir_;
        options.env = env;
        options.stdoutFile = captureDir_ / "stdout";
        options.stderrFile = captureDir_ / "stderr";
        options.timeoutSeconds = timeoutSeconds;
        const PtRun r = pt::test::runProcess(argv, options);
        if (!r.launchError.empty()) ADD_FAILURE() << r.launchError;
        return r;
    }

    // The files pt left in dir_ (relative names, the capture directory excluded).
    std::vector<std::string> outputs() const {
        std::vector<std::string> names;
        for (const auto& e : fs::recursive_directory_iterator(dir_)) {
            const fs::path rel = fs::relative(e.path(), dir_);
            if (*rel.begin() == ".capture") continue;
            names.push_back(rel.string());
        }
        std::sort(names.begin(), names.end());
        return names;
    }

    fs::path dir_, captureDir_;
};

// Exited (not killed by a signal, not timed out) with status `expected`.
#define EXPECT_EXIT_STATUS(r, expected)                                                                                \
    do {                                                                                                               \
        EXPECT_FALSE((r).signaled) << (r);                                                                             \
        EXPECT_FALSE((r).timedOut) << (r);                                                                             \
        EXPECT_EQ((r).status, (expected)) << (r);                                                                      \
    } while (0)

// ---------------------------------------------------------------------------------------------
// The malformed corpora: tests/data/malformed_{gltf,xml,ply}/README.md list each file with the
// lowercase substring its error must contain once the file's own path is removed.

using pt::test::trim;
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

using pt::test::corpusParamName;

INSTANTIATE_TEST_SUITE_P(Corpus, MalformedCorpus, ::testing::ValuesIn(corpusFiles()), corpusParamName);
INSTANTIATE_TEST_SUITE_P(XmlCorpus, MalformedXmlCorpus,
    ::testing::ValuesIn(pt::test::malformedCorpusFiles("malformed_xml")), corpusParamName);
INSTANTIATE_TEST_SUITE_P(PlyCorpus, MalformedPlyCorpus,
    ::testing::ValuesIn(pt::test::malformedCorpusFiles("malformed_ply")), corpusParamName);

// ---------------------------------------------------------------------------------------------
// Successful renders

TEST_F(CliTest, DefaultSceneWritesExrWithMetadataAndPng) {
    const fs::path exr = dir_ / "cbox.exr", png = dir_ / "cbox.png";
    const PtRun r = run({"render", "-o", exr.string(), "--spp", "2", "--width", "32", "--height", "32"});
    EXPECT_EXIT_STATUS(r, 0);
    EXPECT_TRUE(r.errorLines().empty()) << r;
    ASSERT_TRUE(fs::exists(exr)) << r;

    pt::ImageMetadata meta;
    const pt::Image image = pt::readExr(exr, &meta);
    EXPECT_EQ(image.width, 32);
    EXPECT_EQ(image.height, 32);
    EXPECT_EQ(meta["spp"], "2");
    EXPECT_EQ(meta["seed"], "0");
    EXPECT_FALSE(meta["device"].empty());
    EXPECT_FALSE(meta["integrator"].empty());
    EXPECT_EQ(meta["dropped_samples"], "0");
    EXPECT_EQ(meta["scene"], "built-in Cornell box");
    // The Cornell box is lit: some light must have arrived, and nothing non-finite.
    double sum = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            for (int c = 0; c < 3; ++c) {
                ASSERT_TRUE(std::isfinite(image.at(x, y)[c])) << x << "," << y;
                sum += image.at(x, y)[c];
            }
    EXPECT_GT(sum, 0.0);

    ASSERT_TRUE(fs::exists(png));
    EXPECT_GT(fs::file_size(png), 0u);
    const std::string header = readFile(png).substr(0, 8);
    EXPECT_EQ(header, std::string("\x89PNG\r\n\x1a\n", 8));
    EXPECT_EQ(outputs(), (std::vector<std::string>{"cbox.exr", "cbox.png"})) << "temporary files left behind";
}

TEST_F(CliTest, SeedAndSppReachTheMetadata) {
    const fs::path exr = dir_ / "sub" / "dir" / "seeded.exr";
    const PtRun r =
        run({"render", "-o", exr.string(), "--spp", "3", "--seed", "7", "--width", "8", "--height", "4", "--quiet"});
    EXPECT_EXIT_STATUS(r, 0);
    ASSERT_TRUE(fs::exists(exr)) << r; // parent directories are created
    pt::ImageMetadata meta;
    const pt::Image image = pt::readExr(exr, &meta);
    EXPECT_EQ(image.width, 8);
    EXPECT_EQ(image.height, 4);
    EXPECT_EQ(meta["spp"], "3");
    EXPECT_EQ(meta["seed"], "7");
    EXPECT_TRUE(fs::exists(dir_ / "sub" / "dir" / "seeded.png"));
}

TEST_F(CliTest, ValidationLayerStaysSilent) {
    const fs::path exr = dir_ / "v.exr";
    const PtRun r =
        run({"render", "--spp", "1", "--width", "16", "--height", "16", "-o", exr.string()}, {{"PT_VALIDATION", "1"}});
    EXPECT_EXIT_STATUS(r, 0);
    EXPECT_TRUE(r.errorLines().empty()) << r;
    // Nothing about validation (this test's own directory name aside).
    EXPECT_EQ(lower(removeAll(r.err, dir_.string())).find("validation"), std::string::npos) << r;
    EXPECT_TRUE(fs::exists(exr));
}

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

TEST_F(CliTest, ErrorLogRecordsEveryPass) {
    const fs::path log = dir_ / "errors.csv", exr = dir_ / "diffuse.exr";
    const PtRun r = run({"render", kDiffuseScene.string(), "--reference", kDiffuseReference.string(), "--error-log",
        log.string(), "--spp", "4", "--pass-spp", "1", "-o", exr.string(), "--quiet"});
    EXPECT_EXIT_STATUS(r, 0);
    ASSERT_TRUE(fs::exists(log)) << r;
    std::istringstream s(readFile(log));
    std::string line;
    ASSERT_TRUE(std::getline(s, line));
    EXPECT_EQ(line, "spp,seconds,relmse");
    std::vector<long> spp;
    std::vector<double> seconds, relmse;
    while (std::getline(s, line)) {
        if (line.empty()) continue;
        long n;
        double t, e;
        char c1, c2;
        std::istringstream row(line);
        ASSERT_TRUE(row >> n >> c1 >> t >> c2 >> e && c1 == ',' && c2 == ',') << "bad row: " << line;
        spp.push_back(n), seconds.push_back(t), relmse.push_back(e);
    }
    ASSERT_EQ(spp.size(), 4u) << readFile(log); // --pass-spp 1: one row per sample
    for (size_t i = 0; i < spp.size(); ++i) {
        EXPECT_EQ(spp[i], static_cast<long>(i + 1));
        if (i > 0) EXPECT_GE(seconds[i], seconds[i - 1]);
        EXPECT_TRUE(std::isfinite(relmse[i]) && relmse[i] > 0) << relmse[i];
    }
    // Four times the samples: well below the one-sample error (about a quarter of it).
    EXPECT_LT(relmse.back(), 0.6 * relmse.front());
    pt::ImageMetadata meta;
    const pt::Image image = pt::readExr(exr, &meta);
    EXPECT_EQ(image.width, 256); // the scene's own size hint
    EXPECT_EQ(image.height, 256);
    EXPECT_EQ(meta["spp"], "4");
}

// ---------------------------------------------------------------------------------------------
// Bad inputs

TEST_F(CliTest, MissingSceneFile) {
    const std::string scene = (dir_ / "nothere.gltf").string();
    const PtRun r = run({"render", scene, "--spp", "1", "-o", (dir_ / "x.exr").string()});
    EXPECT_EXIT_STATUS(r, 1);
    const std::string line = r.errorLine();
    EXPECT_NE(line.find(scene), std::string::npos) << line;
    EXPECT_NE(lower(removeAll(line, scene)).find("not found"), std::string::npos) << line;
    EXPECT_TRUE(outputs().empty());
}

TEST_F(CliTest, DirectoryAsScene) {
    for (const std::string name : {"scenes", "folder.gltf"}) {
        SCOPED_TRACE(name);
        const std::string scene = (dir_ / name).string();
        fs::create_directories(scene);
        const PtRun r = run({"render", scene, "--spp", "1", "-o", (dir_ / "x.exr").string()});
        EXPECT_EXIT_STATUS(r, 1);
        const std::string line = r.errorLine();
        EXPECT_NE(line.find(scene), std::string::npos) << line;
        EXPECT_FALSE(fs::exists(dir_ / "x.exr"));
    }
}

TEST_F(CliTest, UnknownSceneExtension) {
    const std::string scene = (dir_ / "model.obj").string();
    std::ofstream(scene) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    const PtRun r = run({"render", scene, "--spp", "1", "-o", (dir_ / "x.exr").string()});
    EXPECT_EXIT_STATUS(r, 1);
    const std::string line = r.errorLine();
    EXPECT_NE(line.find(scene), std::string::npos) << line;
    EXPECT_NE(removeAll(line, scene).find(".obj"), std::string::npos) << "should say which extension: " << line;
    EXPECT_FALSE(fs::exists(dir_ / "x.exr"));
}

TEST_F(CliTest, AbsurdResolutionFailsFastWithoutAllocating) {
    const PtRun r = run(
        {"render", "--spp", "1", "--width", "100000", "--height", "100000", "-o", (dir_ / "x.exr").string()}, {}, 10);
    EXPECT_EXIT_STATUS(r, 1);
    EXPECT_LT(r.seconds, 2.0) << r;
    const std::string line = r.errorLine();
    EXPECT_NE(line.find("100000"), std::string::npos) << "should mention the size: " << line;
    EXPECT_NE(lower(line).find("size"), std::string::npos) << line;
    EXPECT_TRUE(outputs().empty());
}

TEST_F(CliTest, ReferenceOfTheWrongSize) {
    const std::string ref = kDiffuseReference.string(); // 256x256
    const PtRun r = run({"render", "--reference", ref, "--spp", "1", "--width", "32", "--height", "32", "-o",
        (dir_ / "x.exr").string()});
    EXPECT_EXIT_STATUS(r, 1);
    const std::string line = r.errorLine();
    EXPECT_NE(line.find(ref), std::string::npos) << line;
    EXPECT_NE(line.find("256"), std::string::npos) << "should give the reference's size: " << line;
    EXPECT_TRUE(outputs().empty());
}

TEST_F(CliTest, MissingReference) {
    const std::string ref = (dir_ / "nothere.exr").string();
    const PtRun r = run(
        {"render", "--reference", ref, "--spp", "1", "--width", "8", "--height", "8", "-o", (dir_ / "x.exr").string()});
    EXPECT_EXIT_STATUS(r, 1);
    const std::string line = r.errorLine();
    EXPECT_NE(line.find(ref), std::string::npos) << line;
    EXPECT_TRUE(outputs().empty());
}

TEST_F(CliTest, ReferenceThatIsNotAnExr) {
    const std::string ref = kDiffuseScene.string();
    const PtRun r = run(
        {"render", "--reference", ref, "--spp", "1", "--width", "8", "--height", "8", "-o", (dir_ / "x.exr").string()});
    EXPECT_EXIT_STATUS(r, 1);
    EXPECT_NE(r.errorLine().find(ref), std::string::npos);
    EXPECT_TRUE(outputs().empty());
}

TEST_F(CliTest, OutputUnderProc) {
    const std::string out = "/proc/pt-cli-test-does-not-exist/y.exr";
    const PtRun r = run({"render", "--spp", "1", "--width", "8", "--height", "8", "-o", out});
    EXPECT_EXIT_STATUS(r, 1);
    const std::string line = r.errorLine();
    // Naming the output, or the directory that could not be made for it.
    EXPECT_NE(line.find(fs::path(out).parent_path().string()), std::string::npos) << line;
}

TEST_F(CliTest, OutputWhoseParentIsARegularFile) {
    const fs::path file = dir_ / "file.txt";
    std::ofstream(file) << "not a directory\n";
    const std::string out = (file / "y.exr").string();
    const PtRun r = run({"render", "--spp", "1", "--width", "8", "--height", "8", "-o", out});
    EXPECT_EXIT_STATUS(r, 1);
    const std::string line = r.errorLine();
    EXPECT_NE(line.find(file.string()), std::string::npos) << line;
    EXPECT_EQ(readFile(file), "not a directory\n");
    EXPECT_EQ(outputs(), std::vector<std::string>{"file.txt"});
}

TEST_F(CliTest, OutputThatIsADirectory) {
    const fs::path out = dir_ / "taken.exr";
    fs::create_directories(out);
    const PtRun r = run({"render", "--spp", "1", "--width", "8", "--height", "8", "-o", out.string(), "--quiet"});
    EXPECT_EXIT_STATUS(r, 1);
    EXPECT_NE(r.errorLine().find(out.string()), std::string::npos);
    EXPECT_TRUE(fs::is_directory(out));
    EXPECT_FALSE(fs::exists(dir_ / "taken.png"));
}

TEST_F(CliTest, OutputMustBeExr) {
    const std::string out = (dir_ / "image.png").string();
    const PtRun r = run({"render", "--spp", "1", "--width", "8", "--height", "8", "-o", out});
    EXPECT_EXIT_STATUS(r, 1);
    EXPECT_NE(r.errorLine().find(out), std::string::npos);
    EXPECT_TRUE(outputs().empty());
}

TEST_F(CliTest, CameraOutOfRange) {
    const PtRun r = run(
        {"render", "--camera", "5", "--spp", "1", "--width", "8", "--height", "8", "-o", (dir_ / "x.exr").string()});
    EXPECT_EXIT_STATUS(r, 1);
    const std::string line = r.errorLine();
    EXPECT_NE(lower(line).find("camera"), std::string::npos) << line;
    EXPECT_NE(line.find('5'), std::string::npos) << line;
    EXPECT_TRUE(outputs().empty());
}

// ---------------------------------------------------------------------------------------------
// Usage errors: exit status 2, nothing rendered.

TEST_F(CliTest, SppAndTimeTogetherIsAUsageError) {
    const PtRun r = run({"render", "--spp", "4", "--time", "1", "-o", (dir_ / "x.exr").string()});
    EXPECT_EXIT_STATUS(r, 2);
    EXPECT_NE(r.err.find("--time"), std::string::npos) << r;
    EXPECT_TRUE(outputs().empty());
}

TEST_F(CliTest, BadSwitchValueIsAUsageError) {
    const PtRun r = run({"render", "--nee", "maybe", "-o", (dir_ / "x.exr").string()});
    EXPECT_EXIT_STATUS(r, 2);
    EXPECT_NE(r.err.find("maybe"), std::string::npos) << r;
    EXPECT_TRUE(outputs().empty());
}

TEST_F(CliTest, UnknownOptionIsAUsageError) {
    const PtRun r = run({"render", "--no-such-option", "-o", (dir_ / "x.exr").string()});
    EXPECT_EXIT_STATUS(r, 2);
    EXPECT_TRUE(outputs().empty());
}

TEST_F(CliTest, MissingSubcommandIsAUsageError) {
    const PtRun r = run({});
    EXPECT_EXIT_STATUS(r, 2);
}

TEST_F(CliTest, ErrorLogWithoutReferenceIsAUsageError) {
    const PtRun r = run({"render", "--error-log", (dir_ / "e.csv").string(), "-o", (dir_ / "x.exr").string()});
    EXPECT_EXIT_STATUS(r, 2);
    EXPECT_NE(r.err.find("--reference"), std::string::npos) << r;
    EXPECT_TRUE(outputs().empty());
}

TEST_F(CliTest, HelpExitsZero) {
    const PtRun r = run({"render", "--help"});
    EXPECT_EXIT_STATUS(r, 0);
    EXPECT_NE(r.out.find("--spp"), std::string::npos) << r;
}

} // namespace

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

// Features the renderer does not model yet are named in exactly one warning, and a scene with
// nothing emitting says so instead of silently writing a black image.
TEST_F(CliTest, UnsupportedFeaturesAreListedInOneWarning) {
    const std::string scene = (kTests / "data" / "cli" / "unsupported_features.gltf").string();
    const PtRun r =
        run({"render", scene, "--spp", "1", "--width", "8", "--height", "8", "-o", (dir_ / "x.exr").string()});
    EXPECT_EXIT_STATUS(r, 0);
    std::vector<std::string> notSupported, noLight;
    std::istringstream lines(r.err);
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind("pt: warning: ", 0) != 0) continue;
        if (line.find("not supported yet") != std::string::npos) notSupported.push_back(line);
        if (line.find("nothing emits light") != std::string::npos) noLight.push_back(line);
    }
    ASSERT_EQ(notSupported.size(), 1u) << r;
    for (const char* what : {"KHR_materials_clearcoat", "KHR_materials_sheen", "orthographic cameras"})
        EXPECT_NE(notSupported[0].find(what), std::string::npos) << what << " missing from: " << notSupported[0];
    EXPECT_EQ(noLight.size(), 1u) << r;
}

// A course scene renders one image per camera, named by its ImageName, into the -o folder;
// --camera picks one camera by its id.
TEST_F(CliTest, CourseSceneRendersEveryCameraToItsImageName) {
    const std::string scene = (kTests / "data" / "ceng795" / "cornellbox_jaroslav_path_glass.xml").string();
    // Eight cameras with different switches: eight pipelines of about 2 s each on lavapipe, more
    // with another test beside it.
    const PtRun all =
        run({"render", scene, "--spp", "1", "--width", "16", "--height", "16", "-o", (dir_ / "all").string()}, {}, 120);
    EXPECT_EXIT_STATUS(all, 0);
    for (const char* name : {"glass", "glass_next", "glass_next_importance_russian", "glass_russian"}) {
        EXPECT_TRUE(fs::exists(dir_ / "all" / (std::string(name) + ".exr"))) << name << "\n" << all;
        EXPECT_TRUE(fs::exists(dir_ / "all" / (std::string(name) + ".png"))) << name;
    }
    size_t images = 0;
    for (const auto& e : fs::directory_iterator(dir_ / "all")) images += e.path().extension() == ".exr";
    EXPECT_EQ(images, 8u);

    const PtRun one = run({"render", scene, "--camera", "4", "--spp", "1", "--width", "16", "--height", "16", "-o",
        (dir_ / "one.exr").string()});
    EXPECT_EXIT_STATUS(one, 0);
    pt::ImageMetadata meta;
    pt::readExr(dir_ / "one.exr", &meta);
    EXPECT_EQ(meta["camera"], "camera 4");
    // Camera 4 asks for NEE, importance sampling and Russian roulette, with no depth cap.
    EXPECT_NE(meta["integrator"].find("nee=on"), std::string::npos) << meta["integrator"];
    EXPECT_NE(meta["integrator"].find("rr=on"), std::string::npos) << meta["integrator"];
    EXPECT_NE(meta["integrator"].find("sampling=cosine"), std::string::npos) << meta["integrator"];

    const PtRun missing = run({"render", scene, "--camera", "42", "--spp", "1", "-o", (dir_ / "x.exr").string()});
    EXPECT_EXIT_STATUS(missing, 1);
    EXPECT_NE(missing.errorLine().find("42"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// pt bench: speed against error at equal time

namespace {

// The rows of a CSV as column -> value maps.
std::vector<std::map<std::string, std::string>> readCsv(const fs::path& path) {
    std::ifstream in(path);
    std::vector<std::string> header;
    std::vector<std::map<std::string, std::string>> rows;
    for (std::string line; std::getline(in, line);) {
        std::vector<std::string> fields;
        std::istringstream s(line);
        for (std::string f; std::getline(s, f, ',');) fields.push_back(f);
        if (header.empty()) {
            header = fields;
            continue;
        }
        EXPECT_EQ(fields.size(), header.size()) << line;
        std::map<std::string, std::string> row;
        for (size_t i = 0; i < std::min(fields.size(), header.size()); ++i) row[header[i]] = fields[i];
        rows.push_back(row);
    }
    return rows;
}

} // namespace

TEST_F(CliTest, BenchWritesCsvPlotAndContactSheets) {
    const PtRun r = run({"bench", "--width", "32", "--height", "32", "--budgets", "0.8,0.2", "--configs",
                            "nee+is+rr,none,nee+is+rr+sobol", "--reference-spp", "256", "-o", "bench"},
        {}, 120);
    EXPECT_EXIT_STATUS(r, 0);
    const fs::path dir = dir_ / "bench";
    const auto rows = readCsv(dir / "bench.csv");
    ASSERT_EQ(rows.size(), 6u) << r; // 3 configurations x 2 budgets
    std::map<std::string, std::map<double, std::map<std::string, std::string>>> byConfig;
    for (const auto& row : rows) {
        for (const char* column : {"budget_s", "spp", "seconds", "mpaths_per_s", "mrays_per_s", "mrays_camera_per_s",
                 "mrays_shadow_per_s", "mrays_continuation_per_s", "relmse", "mse", "efficiency", "estimated_relmse"}) {
            const double v = std::stod(row.at(column));
            EXPECT_TRUE(std::isfinite(v) && v >= 0) << column << " = " << row.at(column);
        }
        EXPECT_GT(std::stod(row.at("relmse")), 0.0);
        EXPECT_EQ(row.at("dropped_samples"), "0");
        EXPECT_TRUE(fs::exists(dir / row.at("image"))) << row.at("image");
        byConfig[row.at("config")][std::stod(row.at("budget_s"))] = row;
    }
    ASSERT_EQ(byConfig.size(), 3u);
    for (const auto& [config, budgets] : byConfig) {
        ASSERT_EQ(budgets.size(), 2u) << config;
        const auto& shortRun = budgets.at(0.2);
        const auto& longRun = budgets.at(0.8);
        // Budgets are in ascending order of samples, each about within its time.
        EXPECT_LE(std::stoul(shortRun.at("spp")), std::stoul(longRun.at("spp"))) << config;
        EXPECT_LE(std::stod(longRun.at("seconds")), 0.8 * 3) << config; // loose: a busy machine slows passes
        EXPECT_GT(std::stoul(longRun.at("spp")), 1u) << config;
        // Ray counts: one camera ray per path; NEE traces shadow rays, "none" traces none.
        EXPECT_NEAR(std::stod(longRun.at("mrays_camera_per_s")), std::stod(longRun.at("mpaths_per_s")), 1e-9) << config;
        EXPECT_EQ(std::stod(longRun.at("mrays_shadow_per_s")) > 0, config != "none") << config;
        EXPECT_GT(std::stod(longRun.at("mrays_continuation_per_s")), 0.0) << config;
    }
    // The seed's finding holds at equal time in the Cornell box: NEE lowers the error by far.
    EXPECT_LT(std::stod(byConfig["nee+is+rr"][0.8].at("relmse")) * 4, std::stod(byConfig["none"][0.8].at("relmse")));

    for (const char* png : {"relmse_vs_time.png", "contact_0.2s.png", "contact_0.8s.png"}) {
        ASSERT_TRUE(fs::exists(dir / png)) << png << "\n" << r;
        EXPECT_EQ(readFile(dir / png).substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << png;
        EXPECT_GT(fs::file_size(dir / png), 5000u) << png; // a real plot, not an empty canvas
    }
    EXPECT_TRUE(fs::exists(dir / "reference.exr")); // made here, as no --reference was given
    EXPECT_NE(readFile(dir / "bench_info.txt").find("made here"), std::string::npos);
}

TEST_F(CliTest, BenchRejectsUnknownConfigurationWord) {
    const PtRun r = run({"bench", "--width", "8", "--height", "8", "--configs", "nee+fast", "--no-plot"});
    EXPECT_EXIT_STATUS(r, 1);
    EXPECT_NE(r.errorLine().find("unknown word 'fast'"), std::string::npos) << r;
}

TEST_F(CliTest, BenchRejectsBadBudget) {
    const PtRun r = run({"bench", "--width", "8", "--height", "8", "--budgets", "1,x", "--no-plot"});
    EXPECT_EXIT_STATUS(r, 1);
    EXPECT_NE(r.errorLine().find("'x' is not a number of seconds"), std::string::npos) << r;
}

TEST_F(CliTest, TargetErrorStopsNearTheTrueError) {
    // The estimate needs no reference; the reference here only checks it.
    const PtRun r = run({"render", kDiffuseScene.string(), "--target-error", "0.02", "--reference",
                            kDiffuseReference.string(), "-o", "t.exr", "--quiet"},
        {}, 120);
    EXPECT_EXIT_STATUS(r, 0);
    EXPECT_NE(r.err.find("(target 0.02 reached)"), std::string::npos) << r;
    pt::ImageMetadata meta;
    const pt::Image image = pt::readExr(dir_ / "t.exr", &meta);
    const double trueError = pt::relMse(image, pt::readExr(kDiffuseReference));
    EXPECT_LE(std::stod(meta.at("estimated_relmse")), 0.02);
    EXPECT_GT(trueError, 0.02 / 1.5) << meta.at("spp") << " spp";
    EXPECT_LT(trueError, 0.02 * 1.5) << meta.at("spp") << " spp";
    EXPECT_EQ(meta.at("target_error"), "0.02");
}

TEST_F(CliTest, VarianceChannelsMatchTheSpreadOfSeeds) {
    // Two renders with different seeds differ per pixel by d with E[d^2] = varA + varB. Path
    // tracing's tails make sums of d^2 erratic, so compare medians: for near-Gaussian pixel
    // means, d^2 / (varA + varB) is chi-square with one degree of freedom, median 0.455.
    const std::vector<std::string> names{"variance.R", "variance.G", "variance.B"};
    std::vector<pt::ExrChannels> variances;
    std::vector<pt::Image> means;
    for (const char* seed : {"1", "2"}) {
        const std::string file = std::string("v") + seed + ".exr";
        const PtRun r = run({"render", "--width", "32", "--height", "32", "--spp", "64", "--seed", seed, "--variance",
            "-o", file, "--quiet"});
        ASSERT_EQ(r.status, 0) << r;
        variances.push_back(pt::readExrChannels(dir_ / file, names));
        means.push_back(pt::readExr(dir_ / file));
    }
    std::vector<double> ratios;
    for (int c = 0; c < 3; ++c)
        for (size_t i = 0; i < variances[0].channels[c].values.size(); ++i) {
            const double va = variances[0].channels[c].values[i], vb = variances[1].channels[c].values[i];
            ASSERT_TRUE(std::isfinite(va) && va >= 0 && std::isfinite(vb) && vb >= 0);
            if (va + vb <= 0) continue; // black pixels: nothing to compare
            const double d = means[0].rgba[4 * i + c] - means[1].rgba[4 * i + c];
            ratios.push_back(d * d / (va + vb));
        }
    ASSERT_GT(ratios.size(), 1000u);
    std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
    const double median = ratios[ratios.size() / 2];
    EXPECT_GT(median, 0.3);  // a variance twice too large gives 0.23
    EXPECT_LT(median, 0.65); // half as large, 0.9
}
