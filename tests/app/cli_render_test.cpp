// pt render's successful runs and what they write: EXR with metadata and PNG, seeds, error logs,
// warnings, a course scene's cameras, --target-error and the variance channels.
#include "cli_fixture.h"
#include "support/malformed_corpus.h"
#include "image/image_io.h"
#include "film/metrics.h"
#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>

namespace pt::test {
namespace {

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

// --integrator auto (the default) measures how often light sampling finds the light and takes
// BDPT with vertex merging where it seldom does: the two rooms of scenes/ajar (lit through a door
// ajar), not the box. The measurement, the choice and the merge radius are logged; the choice is
// in the EXR's features.
TEST_F(CliTest, AutoIntegratorTakesBdptWhereLightArrivesThroughAGap) {
    const auto render = [&](const fs::path& scene, const std::string& name) {
        const fs::path exr = dir_ / (name + ".exr");
        const PtRun r =
            run({"render", scene.string(), "-o", exr.string(), "--spp", "1", "--width", "32", "--height", "18"});
        EXPECT_EXIT_STATUS(r, 0);
        EXPECT_NE(r.err.find("integrator auto: "), std::string::npos) << r;
        EXPECT_EQ(r.err.find("vertex merging: radius") != std::string::npos, name == "ajar") << r;
        pt::ImageMetadata meta;
        pt::readExr(exr, &meta);
        return meta["features"];
    };
    const std::string ajar = render(kTests.parent_path() / "scenes" / "ajar" / "scene.gltf", "ajar");
    EXPECT_NE((" " + ajar + " ").find(" bdpt merging "), std::string::npos) << ajar;
    const std::string box = render(kDiffuseScene, "box");
    EXPECT_EQ((" " + box + " ").find(" bdpt "), std::string::npos) << box;
}

// Where vertex merging's light vertices would need more than kAutoMergingMaxBytes, auto renders
// by BDPT alone and says so (960x600 at depth 33: 2.2 GiB); --integrator vcm is still taken.
TEST_F(CliTest, AutoLeavesVertexMergingOutWhereItsBuffersWouldBeTooBig) {
    const fs::path scene = kTests.parent_path() / "scenes" / "ajar" / "scene.gltf";
    ASSERT_GT(pt::mergingBufferSizes(960, 600, 33).bytes, pt::kAutoMergingMaxBytes);
    ASSERT_LT(pt::mergingBufferSizes(320, 180, 33).bytes, pt::kAutoMergingMaxBytes);
    const fs::path exr = dir_ / "big.exr";
    const PtRun r = run({"render", scene.string(), "-o", exr.string(), "--spp", "1", "--width", "960", "--height",
        "600", "--max-depth", "33"});
    EXPECT_EXIT_STATUS(r, 0);
    EXPECT_NE(r.err.find("BDPT without vertex merging: its light vertices would need"), std::string::npos) << r;
    EXPECT_EQ(r.err.find("vertex merging: radius"), std::string::npos) << r;
    pt::ImageMetadata meta;
    pt::readExr(exr, &meta);
    EXPECT_NE((" " + meta["features"] + " ").find(" bdpt "), std::string::npos) << meta["features"];
    EXPECT_EQ((" " + meta["features"] + " ").find(" merging "), std::string::npos) << meta["features"];
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
    for (const char* what : {"EXT_lights_image_based", "EXT_texture_webp", "orthographic cameras"})
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

TEST_F(CliTest, TargetErrorStopsNearTheTrueError) {
    // The estimate needs no reference; the reference here only checks it. With independent
    // samples it is the error's estimate; with the default Sobol' points it overestimates
    // (README), so the render stops later and the true error may be well below the target.
    for (const char* sampler : {"independent", "sobol"}) {
        SCOPED_TRACE(sampler);
        const std::string out = std::string("t-") + sampler + ".exr";
        const PtRun r = run({"render", kDiffuseScene.string(), "--target-error", "0.02", "--sampler", sampler,
                                "--reference", kDiffuseReference.string(), "-o", out, "--quiet"},
            {}, 120);
        EXPECT_EXIT_STATUS(r, 0);
        EXPECT_NE(r.err.find("(target 0.02 reached)"), std::string::npos) << r;
        pt::ImageMetadata meta;
        const pt::Image image = pt::readExr(dir_ / out, &meta);
        const double trueError = pt::relMse(image, pt::readExr(kDiffuseReference));
        std::printf("%s: %s spp, true relMSE %.4f\n", sampler, meta.at("spp").c_str(), trueError);
        EXPECT_LE(std::stod(meta.at("estimated_relmse")), 0.02);
        if (std::string(sampler) == "independent") EXPECT_GT(trueError, 0.02 / 1.5) << meta.at("spp") << " spp";
        EXPECT_LT(trueError, 0.02 * 1.5) << meta.at("spp") << " spp";
        EXPECT_EQ(meta.at("target_error"), "0.02");
    }
}

// Median over pixels of d^2 / (varA + varB) for two renders with different seeds, d the
// difference of their means. For near-Gaussian pixel means that is chi-square with one degree of
// freedom, median 0.455, when the variance channels are the variances of the means.
double medianSpreadOverVariance(
    const std::filesystem::path& dir, const std::function<PtRun(std::vector<std::string>)>& run, const char* sampler) {
    const std::vector<std::string> names{"variance.R", "variance.G", "variance.B"};
    std::vector<pt::ExrChannels> variances;
    std::vector<pt::Image> means;
    for (const char* seed : {"1", "2"}) {
        const std::string file = std::string("v") + sampler + seed + ".exr";
        const PtRun r = run({"render", "--width", "32", "--height", "32", "--spp", "64", "--seed", seed, "--variance",
            "--sampler", sampler, "-o", file, "--quiet"});
        EXPECT_EQ(r.status, 0) << r;
        variances.push_back(pt::readExrChannels(dir / file, names));
        means.push_back(pt::readExr(dir / file));
    }
    std::vector<double> ratios;
    for (int c = 0; c < 3; ++c)
        for (size_t i = 0; i < variances[0].channels[c].values.size(); ++i) {
            const double va = variances[0].channels[c].values[i], vb = variances[1].channels[c].values[i];
            EXPECT_TRUE(std::isfinite(va) && va >= 0 && std::isfinite(vb) && vb >= 0);
            if (va + vb <= 0) continue; // black pixels: nothing to compare
            const double d = means[0].rgba[4 * i + c] - means[1].rgba[4 * i + c];
            ratios.push_back(d * d / (va + vb));
        }
    EXPECT_GT(ratios.size(), 1000u);
    if (ratios.empty()) return 0;
    std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
    return ratios[ratios.size() / 2];
}

TEST_F(CliTest, VarianceChannelsMatchTheSpreadOfSeeds) {
    // Path tracing's tails make sums of d^2 erratic, hence medians. With independent samples the
    // channels are the variance of the mean; with the default Sobol' points the means vary less
    // than the samples' own variance says, so the channels are an upper bound (README).
    auto runPt = [this](std::vector<std::string> args) { return run(args); };
    const double independent = medianSpreadOverVariance(dir_, runPt, "independent");
    const double sobol = medianSpreadOverVariance(dir_, runPt, "sobol");
    std::printf("median d^2 / (varA + varB): independent %.3f, sobol %.3f (0.455 when exact)\n", independent, sobol);
    EXPECT_GT(independent, 0.3);  // a variance twice too large gives 0.23
    EXPECT_LT(independent, 0.65); // half as large, 0.9
    EXPECT_LT(sobol, 0.455);      // never an underestimate
}

} // namespace
} // namespace pt::test
