// pt render on bad inputs: missing or wrong scenes, references and outputs, an absurd size, a camera
// out of range; each exits 1 with one error line naming the culprit, nothing written.
#include "cli_fixture.h"
#include "support/malformed_corpus.h"

#include <fstream>

namespace pt::test {
namespace {

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
    const PtRun r = run({"render", "--reference", ref, "--spp", "1", "--width", "48", "--height", "48", "-o",
        (dir_ / "x.exr").string()});
    EXPECT_EXIT_STATUS(r, 1);
    const std::string line = r.errorLine();
    EXPECT_NE(line.find(ref), std::string::npos) << line;
    EXPECT_NE(line.find("256"), std::string::npos) << "should give the reference's size: " << line;
    EXPECT_TRUE(outputs().empty());
    // A whole fraction of the reference's size is scored against it box-filtered down.
    const PtRun quarter = run({"render", kDiffuseScene.string(), "--reference", ref, "--spp", "64", "--width", "64",
        "--height", "64", "-o", (dir_ / "x.exr").string()});
    EXPECT_EXIT_STATUS(quarter, 0);
    const size_t at = quarter.err.rfind(", relMSE ");
    ASSERT_NE(at, std::string::npos) << quarter;
    EXPECT_LT(std::stod(quarter.err.substr(at + 9)), 0.02) << "the same box, its reference filtered down: " << quarter;
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

} // namespace
} // namespace pt::test
