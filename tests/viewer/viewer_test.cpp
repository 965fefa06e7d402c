// `pt view` as a user runs it, in a virtual X server (xvfb-run): a scripted session checks the
// saved EXR, the reset of accumulation after a camera move, the window screenshot and the
// swapchain's recreation on resize, all with the validation layer on; the image of the
// untouched default camera is compared with `pt render`; without a display pt view must fail
// with one line. The Xvfb tests skip only when xvfb-run is not installed (.ci/run installs it).
#include "image/image_io.h"
#include "film/metrics.h"
#include "support/pt_process.h"
#include "support/test_directory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

namespace fs = std::filesystem;

namespace {

using pt::test::onPath;
using pt::test::PtRun;

class ViewerProcess : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = pt::test::freshTestDirectory("view");
        fs::create_directories(dir_ / "xdg");
        fs::permissions(dir_ / "xdg", fs::perms::owner_all);
    }
    void TearDown() override {
        std::error_code ignored;
        if (!HasFailure()) fs::remove_all(dir_, ignored); // keep the evidence of a failure
    }

    // Runs argv in dir_ with `unset` removed from the environment and `set` added.
    PtRun run(const std::vector<std::string>& args, const std::set<std::string>& unset = {},
        const std::map<std::string, std::string>& set = {}, double timeoutSeconds = 240) {
        pt::test::RunOptions options;
        options.dir = dir_;
        options.unset.insert(unset.begin(), unset.end());
        options.env = set;
        options.env["XDG_RUNTIME_DIR"] = (dir_ / "xdg").string(); // GLFW and Mesa want one
        options.stdoutFile = dir_ / "stdout.txt";
        options.stderrFile = dir_ / "stderr.txt";
        options.timeoutSeconds = timeoutSeconds;
        const PtRun r = pt::test::runProcess(args, options);
        if (!r.launchError.empty()) ADD_FAILURE() << r.launchError;
        if (r.timedOut) ADD_FAILURE() << "timed out after " << timeoutSeconds << " s";
        return r;
    }

    // `pt view ARGS --script SCRIPT` inside xvfb-run with a 24-bit screen.
    PtRun view(const std::string& script, std::vector<std::string> args) {
        std::ofstream(dir_ / "script.txt") << script;
        std::vector<std::string> cmd = {"xvfb-run", "-a", "-s", "-screen 0 1024x768x24", PT_BINARY, "view"};
        cmd.insert(cmd.end(), args.begin(), args.end());
        cmd.push_back("--script");
        cmd.push_back("script.txt");
        return run(cmd);
    }

    fs::path dir_;
};

#define SKIP_WITHOUT_XVFB()                                                                                            \
    if (!onPath("xvfb-run")) GTEST_SKIP() << "xvfb-run is not installed (apt-get install xvfb xauth)"

// Values of "key=value" in the report lines of stdout, in order.
std::vector<double> reported(const std::string& out, const std::string& key) {
    std::vector<double> values;
    std::istringstream lines(out);
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind("pt: view: report ", 0) != 0) continue;
        const auto at = line.find(" " + key + "=");
        if (at != std::string::npos) values.push_back(std::stod(line.substr(at + key.size() + 2)));
    }
    return values;
}

double meanValue(const pt::Image& image) {
    double sum = 0;
    for (size_t i = 0; i < image.rgba.size(); i += 4) sum += image.rgba[i] + image.rgba[i + 1] + image.rgba[i + 2];
    return sum / (3.0 * image.width * image.height);
}

struct Png {
    int width = 0, height = 0;
    double mean = 0; // of the 8-bit values
};

Png readPng(const fs::path& path) {
    Png png;
    int channels = 0;
    unsigned char* data = stbi_load(path.c_str(), &png.width, &png.height, &channels, 3);
    if (!data) return png;
    double sum = 0;
    for (int i = 0; i < png.width * png.height * 3; ++i) sum += data[i];
    png.mean = sum / (png.width * png.height * 3.0);
    stbi_image_free(data);
    return png;
}

TEST_F(ViewerProcess, ScriptedSessionSavesResetsAndResizes) {
    SKIP_WITHOUT_XVFB();
    const PtRun r = view("wait-spp 4\n"
                         "report\n"
                         "save out/still.exr\n"
                         "screenshot out/window.png\n"
                         "orbit 40 0\n"
                         "wait 1\n"
                         "report\n"
                         "resize 200 150\n"
                         "wait 2\n"
                         "report\n"
                         "screenshot out/resized.png\n"
                         "quit\n",
        {"--validation", "--width", "128", "--height", "128", "--spp", "64"});
    ASSERT_EQ(r.status, 0) << r; // 3 would mean validation messages

    // The saved image: 4 spp of the Cornell box, clearly not black, with its metadata.
    pt::ImageMetadata meta;
    const pt::Image still = pt::readExr(dir_ / "out" / "still.exr", &meta);
    EXPECT_EQ(still.width, 128);
    EXPECT_GT(meanValue(still), 0.05) << "the saved EXR is black";
    EXPECT_EQ(meta["spp"], "4");
    EXPECT_EQ(meta["seed"], "0");
    EXPECT_NE(meta["camera"].find("position"), std::string::npos);
    EXPECT_TRUE(fs::exists(dir_ / "out" / "still.png"));
    EXPECT_TRUE(fs::exists(dir_ / "out" / "still.var.exr"));

    // The window showed the picture.
    const Png window = readPng(dir_ / "out" / "window.png");
    EXPECT_EQ(window.width, 128);
    EXPECT_GT(window.mean, 20.0) << "the window screenshot is black";

    // The camera move dropped the accumulated samples.
    const std::vector<double> spp = reported(r.out, "spp");
    ASSERT_EQ(spp.size(), 3u) << r;
    EXPECT_GE(spp[0], 4);
    EXPECT_LT(spp[1], spp[0]) << "accumulation did not restart after the camera moved";

    // The resize recreated the swapchain, and the window shows the new size.
    EXPECT_NE(r.err.find("swapchain recreated at 200x150"), std::string::npos) << r;
    const Png resized = readPng(dir_ / "out" / "resized.png");
    EXPECT_EQ(resized.width, 200);
    EXPECT_EQ(resized.height, 150);
    EXPECT_GT(resized.mean, 10.0);
}

// `--integrator auto` decides in the viewer as in pt render: the probe runs, and the two rooms
// lit through a door ajar get the bidirectional kernel, the Cornell box the path tracer's. B (here
// `toggle integrator`) then switches to the path tracer and to BDPT.
TEST_F(ViewerProcess, AutoIntegratorTakesBdptWhereLightArrivesThroughAGap) {
    SKIP_WITHOUT_XVFB();
    const PtRun ajar = view("wait-spp 1\ntoggle integrator\nwait-spp 1\ntoggle integrator\nwait-spp 1\nquit\n",
        {std::string(PT_SCENES_DIR) + "/ajar/scene.gltf", "--width", "64", "--height", "36"});
    ASSERT_EQ(ajar.status, 0) << ajar;
    EXPECT_NE(ajar.err.find("pt: view: integrator auto: "), std::string::npos) << ajar;
    const size_t toPath = ajar.err.find("pt: view: path nee ");
    EXPECT_NE(toPath, std::string::npos) << ajar;
    EXPECT_NE(ajar.err.find("pt: view: bdpt nee ", toPath), std::string::npos) << ajar;
    const auto features = [](const std::string& err) {
        const size_t at = err.find("kernel features: ");
        return at == std::string::npos ? std::string() : err.substr(at, err.find(';', at) - at);
    };
    EXPECT_NE(features(ajar.err).find(" bdpt"), std::string::npos) << ajar;
    const PtRun box = view("wait-spp 1\nquit\n", {"--width", "64", "--height", "64"});
    ASSERT_EQ(box.status, 0) << box;
    EXPECT_NE(box.err.find("pt: view: integrator auto: "), std::string::npos) << box;
    EXPECT_FALSE(features(box.err).empty()) << box;
    EXPECT_EQ(features(box.err).find(" bdpt"), std::string::npos) << box;
}

// Every debug view (each a pipeline specialisation), the switches, the biased clamp and the
// tone mapping operators run with the validation layer silent and show something.
TEST_F(ViewerProcess, DebugViewsSwitchesAndToneMappingRunClean) {
    SKIP_WITHOUT_XVFB();
    std::string script;
    const std::vector<std::string> views = {"albedo", "normal", "depth", "bvh", "nan"};
    for (const auto& v : views) script += "view " + v + "\nwait-spp 1\nscreenshot out/" + v + ".png\n";
    script += "view none\ntoggle light-tree\nwait-spp 1\ntoggle light-tree\nwait-spp 1\ntoggle light-tree\n"
              "toggle nee\ntoggle rr\ntoggle sampling\nmax-depth 4\nclamp 10\nwait-spp 2\n"
              "tonemap photographic\nwait 2\nscreenshot out/photographic.png\ntonemap aces\nexposure 1\nwait 2\n"
              "screenshot out/aces.png\nsave out/switched.exr\nquit\n";
    const PtRun r = view(script, {"--validation", "--width", "64", "--height", "64"});
    ASSERT_EQ(r.status, 0) << r;
    for (const auto& name : {"albedo", "normal", "depth", "bvh", "nan", "photographic", "aces"}) {
        const Png png = readPng(dir_ / "out" / (std::string(name) + ".png"));
        EXPECT_EQ(png.width, 64) << name;
        EXPECT_GT(png.mean, 5.0) << name << " is black";
    }
    pt::ImageMetadata meta;
    pt::readExr(dir_ / "out" / "switched.exr", &meta);
    EXPECT_EQ(meta["sample_clamp"], "10.000 (biased)");
    EXPECT_NE(meta["integrator"].find("nee=off"), std::string::npos) << meta["integrator"];
    EXPECT_NE(meta["integrator"].find("max-depth=4"), std::string::npos) << meta["integrator"];
    EXPECT_NE(meta["integrator"].find("light-tree=auto"), std::string::npos) << meta["integrator"];
    // G (here `toggle light-tree`) forces the tree on the box, whose one quad light keeps the power
    // CDF under auto, then selection by power.
    const size_t toTree = r.err.find(" light-tree (");
    EXPECT_NE(toTree, std::string::npos) << r;
    EXPECT_NE(r.err.find(" power-lights (", toTree), std::string::npos) << r;
    const std::string treeLine = r.err.substr(toTree, r.err.find('\n', toTree) - toTree);
    EXPECT_NE(treeLine.find("kernel features: triangles diffuse emitters nee mis rr light-tree"), std::string::npos)
        << treeLine;
}

// The viewer's image of the untouched default camera against `pt render`: same camera and
// spp, another seed, compared block by block with the viewer's variance (both renders have
// the same spp, so the same variance: each side's block variance is estimated from it).
TEST_F(ViewerProcess, UntouchedViewMatchesHeadlessRender) {
    SKIP_WITHOUT_XVFB();
    const PtRun v =
        view("wait-spp 16\nsave out/view.exr\nquit\n", {"--width", "128", "--height", "128", "--spp", "16"});
    ASSERT_EQ(v.status, 0) << v;
    // The viewer's passes are uniform; so are the headless renders it is compared with.
    const PtRun r = run({PT_BINARY, "render", "--width", "128", "--height", "128", "--spp", "16", "--seed", "7",
        "--adaptive", "off", "-q", "-o", "out/render.exr"});
    ASSERT_EQ(r.status, 0) << r;
    const PtRun same = run({PT_BINARY, "render", "--width", "128", "--height", "128", "--spp", "16", "--adaptive",
        "off", "-q", "-o", "out/same-seed.exr"});
    ASSERT_EQ(same.status, 0) << same;

    const pt::Image viewed = pt::readExr(dir_ / "out" / "view.exr");
    const pt::Image variance = pt::readExr(dir_ / "out" / "view.var.exr");
    const pt::Image rendered = pt::readExr(dir_ / "out" / "render.exr");
    const pt::AgreementResult a =
        pt::compareBlocks(pt::blockStats(viewed, &variance, 8), pt::blockStats(rendered, &variance, 8));
    // 256 blocks x 3 channels: chi2/dof is 1 +- 0.05 when the images agree; a shifted camera,
    // a lost sample or a wrong exposure gives tens to thousands.
    EXPECT_LT(a.chi2PerDof, 1.6) << "meanZ " << a.meanZ << ", max |z| " << a.maxAbsZ;
    EXPECT_GT(a.chi2PerDof, 0.4) << "suspiciously equal: were the seeds different?";
    EXPECT_LT(std::abs(a.meanZ), 0.25);
    std::printf("view vs render: chi2/dof %.3f over %d cells, mean z %.3f, max |z| %.2f\n", a.chi2PerDof, a.dof,
        a.meanZ, a.maxAbsZ);
    // The tolerance can fail: the same comparison flags the render made 10% brighter.
    pt::Image brighter = rendered;
    for (size_t i = 0; i < brighter.rgba.size(); ++i)
        if (i % 4 != 3) brighter.rgba[i] *= 1.1f;
    EXPECT_GT(
        pt::compareBlocks(pt::blockStats(viewed, &variance, 8), pt::blockStats(brighter, &variance, 8)).chi2PerDof,
        1.6);
    // With the same seed the samples are the same: the sums match to rounding.
    EXPECT_LT(pt::relMse(viewed, pt::readExr(dir_ / "out" / "same-seed.exr")), 1e-8);
}

TEST_F(ViewerProcess, NoDisplayFailsWithOneLine) {
    const PtRun r = run({PT_BINARY, "view"}, {"DISPLAY", "WAYLAND_DISPLAY"});
    EXPECT_EQ(r.status, 1) << r;
    EXPECT_EQ(r.err, "pt: error: pt view: no display (DISPLAY and WAYLAND_DISPLAY are not set); render to a file with "
                     "'pt render' instead\n");
}

TEST_F(ViewerProcess, UnreachableDisplayFailsWithOneLine) {
    const PtRun r = run({PT_BINARY, "view"}, {"WAYLAND_DISPLAY"}, {{"DISPLAY", ":4242"}});
    EXPECT_EQ(r.status, 1) << r;
    EXPECT_EQ(r.err.rfind("pt: error: pt view: cannot open the display", 0), 0u) << r;
    EXPECT_NE(r.err.find("'pt render'"), std::string::npos) << r;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r;
}

} // namespace
