// Against the CENG795 course's official renders: every camera of both HW6 Cornell boxes
// (tests/data/ceng795/cornellbox_jaroslav_path_{diffuse,glass}.xml, eight each: the 2^3
// combinations of NEE, importance sampling and Russian roulette), rendered with the camera's
// settings at the depth pt gives course cameras by default (src/app/scene_setup.cpp,
// chooseMaxDepth: MaxRecursionDepth + 1 without NEE, + 2 with NEE, no cap with Russian roulette),
// 64x64 at 256 spp, compared in total flux and in the means of 8x8-pixel blocks with the official
// image reduced to 64x64 by 8x8 box averaging (tests/data/ceng795/official/README.md), which a
// 64x64 render converges to. The bounds and what they rest on are with kCapped and kRoulette;
// bench/RESULTS.md has the same numbers at 4096 spp and at the old depth. Re-measure with
// --gtest_also_run_disabled_tests --gtest_filter='CourseReferenceMeasurement.*'.
#include "image/image_io.h"
#include "film/metrics.h"
#include "scene/ceng795/loader.h"
#include "support/gpu_test_support.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <ostream>

namespace pt::test {
namespace {

constexpr int kSize = 64;           // the official 512x512 images reduced 8x (box filter)
constexpr int kBlock = 8;           // 8x8 blocks of 8x8 pixels (64x64 pixels of the official image)
constexpr uint32_t kUncapped = 256; // src/app/scene_setup.h, kUncappedDepth
constexpr uint32_t kTestSpp = 256;

const Scene& courseScene(const char* file) {
    static std::map<std::string, std::unique_ptr<Scene>> scenes;
    auto& s = scenes[file];
    if (!s) s = std::make_unique<Scene>(loadCeng795File(testDataDir() / "data" / "ceng795" / file));
    return *s;
}

const Camera& courseCamera(const Scene& scene, int id) {
    for (const auto& c : scene.cameras)
        if (c.id == id) return c;
    throw std::runtime_error("no camera " + std::to_string(id));
}

// The camera's own switches, as `pt render` takes them (src/app/scene_setup.cpp, makeJob).
IntegratorSettings cameraSettings(const Camera& camera) {
    IntegratorSettings s = independentSettings();
    s.nee = camera.settings.nee.value_or(true);
    s.rr = camera.settings.russianRoulette.value_or(true);
    s.sampling =
        camera.settings.importanceSampling.value_or(true) ? DirectionSampling::Cosine : DirectionSampling::Uniform;
    return s;
}

// The course's depth convention, as chooseMaxDepth applies it (the CLI test checks the app's
// log line for the same cameras). `oldRule`: MaxRecursionDepth + 1 for every capped camera.
uint32_t courseDepth(const Camera& camera, bool oldRule = false) {
    const CameraRenderSettings& cs = camera.settings;
    if (!cs.maxDepth) return kUncapped; // Russian roulette: no cap
    return static_cast<uint32_t>(*cs.maxDepth + (cs.nee.value_or(false) && !oldRule ? 1 : 0));
}

struct Comparison {
    double fluxDiff = 0;   // (pt - official) / official, total over pixels and channels
    double fluxSigma = 0;  // pt's standard error of that, relative (from its per-pixel variances)
    double blockDiff = 0;  // mean |relative difference| of the 8x8 block means (8x8-pixel blocks)
    double blockShape = 0; // the same after scaling pt's image to the official flux
    double chi2 = 0;       // mean z^2 of the blocks, z from pt's variance only
};

Comparison compare(const Renderer::Readback& r, const Image& official) {
    Comparison c;
    double ours = 0, theirs = 0, variance = 0;
    for (size_t i = 0; i < official.rgba.size(); ++i)
        if (i % 4 != 3) ours += r.mean.rgba[i], theirs += official.rgba[i], variance += r.varianceOfMean.rgba[i];
    c.fluxDiff = (ours - theirs) / theirs;
    c.fluxSigma = std::sqrt(variance) / theirs;
    const AgreementResult a =
        compareBlocks(blockStats(r.mean, &r.varianceOfMean, kBlock), blockStats(official, nullptr, kBlock));
    c.blockDiff = a.meanRelDiff;
    c.chi2 = a.chi2PerDof;
    Image scaled = r.mean;
    for (float& v : scaled.rgba) v = static_cast<float>(v * theirs / ours);
    c.blockShape =
        compareBlocks(blockStats(scaled, &r.varianceOfMean, kBlock), blockStats(official, nullptr, kBlock)).meanRelDiff;
    return c;
}

Image officialImage(const Camera& camera) {
    std::string stem = camera.settings.imageName;
    stem = stem.substr(0, stem.rfind('.'));
    Image image = readExr(testDataDir() / "data" / "ceng795" / "official" / (stem + ".8x_box.exr"));
    if (image.width != kSize || image.height != kSize) throw std::runtime_error(stem + ": not 64x64");
    return image;
}

Comparison renderAndCompare(const char* file, int id, uint32_t spp, uint32_t depth, uint32_t seed = 0) {
    const Scene& scene = courseScene(file);
    const Camera& camera = courseCamera(scene, id);
    IntegratorSettings s = cameraSettings(camera);
    s.maxDepth = depth;
    s.seed = seed;
    const auto r = renderScene(scene, s, camera, kSize, kSize, spp);
    EXPECT_EQ(r.droppedSamples, 0u) << file << " camera " << id;
    return compare(r, officialImage(camera));
}

void print(const char* file, int id, const Camera& camera, uint32_t depth, const Comparison& c) {
    std::printf("[          ] %s camera %d (%s, depth %u): flux %+.2f%% (pt's sigma %.2f%%), blocks %.2f%% "
                "(%.2f%% at equal flux), chi2/dof %.2f\n",
        file, id, camera.settings.imageName.c_str(), depth, 100 * c.fluxDiff, 100 * c.fluxSigma, 100 * c.blockDiff,
        100 * c.blockShape, c.chi2);
}

// What one camera must show: its total flux difference within [fluxLo, fluxHi], and its block
// difference below maxBlock. For a Russian-roulette camera the official image is brighter than
// any unbiased render can be (see kRoulette below): the band then records how much, and the block
// bound applies at equal flux (the image's shape).
struct Expectation {
    const char* file;
    int id;
    double fluxLo, fluxHi;
    double maxBlock;
    bool atEqualFlux = false;
};

void PrintTo(const Expectation& e, std::ostream* os) { *os << e.file << " camera " << e.id; }

class CourseReference : public GpuTest, public ::testing::WithParamInterface<Expectation> {};

TEST_P(CourseReference, AgreesWithTheOfficialImage) {
    const Expectation& e = GetParam();
    const Camera& camera = courseCamera(courseScene(e.file), e.id);
    const uint32_t depth = courseDepth(camera);
    const Comparison c = renderAndCompare(e.file, e.id, kTestSpp, depth);
    print(e.file, e.id, camera, depth, c);
    EXPECT_GT(c.fluxDiff, e.fluxLo) << camera.settings.imageName;
    EXPECT_LT(c.fluxDiff, e.fluxHi) << camera.settings.imageName;
    EXPECT_LT(e.atEqualFlux ? c.blockShape : c.blockDiff, e.maxBlock) << camera.settings.imageName;
}

constexpr const char* kDiffuse = "cornellbox_jaroslav_path_diffuse.xml";
constexpr const char* kGlass = "cornellbox_jaroslav_path_glass.xml";

// The bounds, from CourseReferenceMeasurement.NoiseAtTheTestsSpp (8 seeds at 256 spp, lavapipe,
// 2026-12-02): each is at least the camera's mean over the seeds plus 4 of their standard
// deviations, rounded up (with 0.5% to spare where that came close); the roulette bands are the
// mean +- (4 sd + 0.5%).
// Measured (flux mean +- sd; blocks mean +- sd):
//   diffuse 1 NEE            -0.35 +- 0.16%; 1.75 +- 0.20%    glass 1 NEE            -1.52 +- 0.24%; 3.98 +- 0.17%
//   diffuse 3 NEE+IS         -0.52 +- 0.12%; 1.39 +- 0.10%    glass 3 NEE+IS         -1.82 +- 0.21%; 4.16 +- 0.22%
//   diffuse 5 IS             +0.13 +- 0.40%; 4.79 +- 0.41%    glass 5 (uniform)      -1.43 +- 0.38%; 7.80 +- 0.39%
//   diffuse 7 IS             +0.25 +- 0.40%; 4.80 +- 0.38%    glass 7 IS             -1.05 +- 0.36%; 6.43 +- 0.36%
// The NEE cameras meet bounds as tight as their non-NEE siblings' or tighter; at the old depth
// (MaxRecursionDepth + 1) they would not: at 4096 spp their flux is then -3.8% (diffuse) and
// -5.5%, -5.9% (glass), their blocks 6.2% and 12-13% off, against -0.3 .. -1.8% and 0.8 .. 3.8%
// at MaxRecursionDepth + 2. The glass box keeps a -1.1 .. -1.8% flux deficit with and without NEE.
const Expectation kCapped[] = {
    {kDiffuse, 1, -0.012, 0.012, 0.03},
    {kDiffuse, 3, -0.012, 0.012, 0.03},
    {kDiffuse, 5, -0.02, 0.02, 0.07},
    {kDiffuse, 7, -0.02, 0.02, 0.07},
    {kGlass, 1, -0.03, 0.03, 0.055},
    {kGlass, 3, -0.03, 0.03, 0.055},
    {kGlass, 5, -0.035, 0.035, 0.10},
    {kGlass, 7, -0.035, 0.035, 0.10},
};

// The Russian-roulette cameras (2, 4, 6, 8 of each box) render, as the course's did, with no
// depth cap (docs/ceng795-format.md section 8). Their official images are 16-29% brighter than
// pt's render, and pt's render is the infinite-bounce limit: pt's roulette is unbiased (with
// roulette and without it at depth 64 the glass box's camera 6 agrees to 0.006% in flux,
// bench/RESULTS.md), and capped renders are darker still (diffuse camera 6: -30.7% at depth 4,
// -28.6% at 5, -26.3% uncapped). An image brighter than the limit is no depth convention, and it
// is no global scale either: at equal flux its 8x8 blocks still differ by 11-21% at 4096 spp (the
// capped cameras: 0.8-3.7%, noise included). The excess depends on the direction sampling (NEE with
// uniform sampling 1.40x, with cosine sampling 1.29x in the diffuse box), which points at a
// roulette weight that does not match its survival probability; the course's renderer is not in
// the collected material, so its exact rule cannot be read off, and pt keeps the unbiased
// estimate. What holds, and is asserted: the excess as measured (the band), and the shape bound.
//   diffuse 2 NEE+RR     -28.62 +- 0.11%; shape 13.37 +- 0.13%    glass 2     -22.58 +- 0.19%; 11.80 +- 0.22%
//   diffuse 4 NEE+IS+RR  -22.29 +- 0.09%; shape 13.94 +- 0.15%    glass 4     -16.01 +- 0.18%; 15.52 +- 0.16%
//   diffuse 6 RR         -26.30 +- 0.27%; shape 21.16 +- 0.51%    glass 6     -23.64 +- 0.25%; 18.48 +- 0.56%
//   diffuse 8 IS+RR      -25.89 +- 0.28%; shape 20.83 +- 0.28%    glass 8     -25.74 +- 0.28%; 18.63 +- 0.47%
const Expectation kRoulette[] = {
    {kDiffuse, 2, -0.296, -0.277, 0.145, true},
    {kDiffuse, 4, -0.232, -0.214, 0.15, true},
    {kDiffuse, 6, -0.279, -0.247, 0.235, true},
    {kDiffuse, 8, -0.275, -0.243, 0.225, true},
    {kGlass, 2, -0.239, -0.213, 0.13, true},
    {kGlass, 4, -0.173, -0.148, 0.165, true},
    {kGlass, 6, -0.252, -0.221, 0.21, true},
    {kGlass, 8, -0.274, -0.241, 0.21, true},
};

std::string testName(const ::testing::TestParamInfo<Expectation>& info) {
    const std::string box = info.param.file == kDiffuse ? "Diffuse" : "Glass";
    return box + "Camera" + std::to_string(info.param.id);
}

INSTANTIATE_TEST_SUITE_P(Capped, CourseReference, ::testing::ValuesIn(kCapped), testName);
INSTANTIATE_TEST_SUITE_P(RussianRoulette, CourseReference, ::testing::ValuesIn(kRoulette), testName);

class CourseReferenceMeasurement : public GpuTest {};

// Every camera at both depth rules (and the roulette cameras also capped at 4 and 5) at
// PT_COURSE_SPP (default 4096: pt's noise well below the differences that matter); prints the
// table bench/RESULTS.md records.
TEST_F(CourseReferenceMeasurement, DISABLED_EveryCameraAtBothDepths) {
    const uint32_t spp = std::getenv("PT_COURSE_SPP") ? std::stoul(std::getenv("PT_COURSE_SPP")) : 4096;
    const uint32_t seed = std::getenv("PT_COURSE_SEED") ? std::stoul(std::getenv("PT_COURSE_SEED")) : 0;
    for (const char* file : {kDiffuse, kGlass})
        for (int id = 1; id <= 8; ++id) {
            const Camera& camera = courseCamera(courseScene(file), id);
            const uint32_t depth = courseDepth(camera), oldDepth = courseDepth(camera, true);
            print(file, id, camera, depth, renderAndCompare(file, id, spp, depth, seed));
            if (oldDepth != depth) print(file, id, camera, oldDepth, renderAndCompare(file, id, spp, oldDepth, seed));
            if (!camera.settings.maxDepth) // Russian roulette: also with the cap of its capped siblings
                for (uint32_t d : {4u, 5u}) print(file, id, camera, d, renderAndCompare(file, id, spp, d, seed));
        }
}

// The spread of the tests' own statistics over seeds at the tests' spp (PT_COURSE_SEEDS, default 8),
// from which their bounds are set.
TEST_F(CourseReferenceMeasurement, DISABLED_NoiseAtTheTestsSpp) {
    const int seeds = std::getenv("PT_COURSE_SEEDS") ? std::stoi(std::getenv("PT_COURSE_SEEDS")) : 8;
    for (const char* file : {kDiffuse, kGlass})
        for (int id = 1; id <= 8; ++id) {
            const Camera& camera = courseCamera(courseScene(file), id);
            double lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9}, sum[3] = {}, sum2[3] = {};
            for (int seed = 1; seed <= seeds; ++seed) {
                const Comparison c = renderAndCompare(file, id, kTestSpp, courseDepth(camera), seed);
                const double v[3] = {c.fluxDiff, c.blockDiff, c.blockShape};
                for (int k = 0; k < 3; ++k)
                    lo[k] = std::min(lo[k], v[k]), hi[k] = std::max(hi[k], v[k]), sum[k] += v[k],
                    sum2[k] += v[k] * v[k];
            }
            std::printf("[          ] %s camera %d (%s):", file, id, camera.settings.imageName.c_str());
            for (int k = 0; k < 3; ++k) {
                const double mean = sum[k] / seeds, sd = std::sqrt(std::max(0.0, sum2[k] / seeds - mean * mean));
                std::printf(" %s mean %+.2f%% sd %.2f%% [%+.2f%%, %+.2f%%];",
                    k == 0   ? "flux"
                    : k == 1 ? "blocks"
                             : "shape",
                    100 * mean, 100 * sd, 100 * lo[k], 100 * hi[k]);
            }
            std::printf("\n");
        }
}

} // namespace
} // namespace pt::test
