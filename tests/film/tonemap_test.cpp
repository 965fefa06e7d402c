#include "film/tonemap.h"
#include "support/test_directory.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

// Decoding the PNG back checks that the file holds exactly tonemapToRgb8's bytes.
// STB_IMAGE_STATIC keeps these symbols private to this file (image_io_test.cpp, linked
// into the same test binary, has its own static copy).
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

namespace fs = std::filesystem;
using pt::Image;
using pt::TonemapSettings;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// A width x 1 image of grey pixels R = G = B = values[i], alpha 1.
Image greyRow(const std::vector<float>& values) {
    Image im{static_cast<int>(values.size()), 1, {}};
    for (float v : values) im.rgba.insert(im.rgba.end(), {v, v, v, 1.0f});
    return im;
}

Image constant(int w, int h, float r, float g, float b) {
    Image im{w, h, {}};
    for (int i = 0; i < w * h; ++i) im.rgba.insert(im.rgba.end(), {r, g, b, 1.0f});
    return im;
}

// Photographic with a linear display (gamma 1), so the bytes show Ld directly.
TonemapSettings photographic(float key, float burn = 0.0f, float saturation = 1.0f) {
    TonemapSettings s;
    s.op = TonemapSettings::Operator::Photographic;
    s.key = key;
    s.burnPercent = burn;
    s.saturation = saturation;
    s.srgb = false;
    s.gamma = 1.0f;
    return s;
}

TonemapSettings clampOp(bool srgb, float gamma = 1.0f) {
    TonemapSettings s;
    s.op = TonemapSettings::Operator::Clamp;
    s.srgb = srgb;
    s.gamma = gamma;
    return s;
}

// Byte c (0 = R) of pixel i in a tonemapToRgb8 result.
int px(const std::vector<uint8_t>& rgb, std::size_t i, int c) { return rgb[3 * i + c]; }

void expectGrey(const std::vector<uint8_t>& rgb, std::size_t i, int value) {
    for (int c = 0; c < 3; ++c) EXPECT_EQ(px(rgb, i, c), value) << "pixel " << i << " c" << c;
}

void expectMagenta(const std::vector<uint8_t>& rgb, std::size_t i) {
    EXPECT_EQ(px(rgb, i, 0), 255) << "pixel " << i;
    EXPECT_EQ(px(rgb, i, 1), 0) << "pixel " << i;
    EXPECT_EQ(px(rgb, i, 2), 255) << "pixel " << i;
}

// ---- Clamp operator and the display curves ----

TEST(Tonemap, ClampSrgbMatchesWritePngValues) {
    // Same table as image_io_test's PngTonemapAndNanMarker: Clamp + sRGB is writePng.
    const auto rgb = pt::tonemapToRgb8(greyRow({0.0f, 1.0f, 0.5f, 0.002f, -1.0f, 10.0f, 0.2f}), clampOp(true));
    ASSERT_EQ(rgb.size(), 7u * 3);
    const int expected[] = {0, 255, 188, 7, 0, 255, 124};
    for (int i = 0; i < 7; ++i) expectGrey(rgb, i, expected[i]);
}

TEST(Tonemap, Gamma22VersusSrgbCurve) {
    // 255 * v^(1/2.2) against 255 * (1.055 v^(1/2.4) - 0.055) (linear 12.92 v below
    // 0.0031308): 0.5 -> 186.08 | 187.52, 0.2 -> 122.69 | 123.55, 0.05 -> 65.34 | 63.19,
    // 0.8 -> 230.40 | 231.11, 0.002 -> 15.13 | 6.59 (the sRGB linear toe).
    const Image im = greyRow({0.5f, 0.2f, 0.05f, 0.8f, 0.002f});
    const auto gamma = pt::tonemapToRgb8(im, clampOp(false, 2.2f));
    const auto srgb = pt::tonemapToRgb8(im, clampOp(true, 2.2f)); // gamma ignored with srgb
    const int g[] = {186, 123, 65, 230, 15};
    const int s[] = {188, 124, 63, 231, 7};
    for (int i = 0; i < 5; ++i) {
        expectGrey(gamma, i, g[i]);
        expectGrey(srgb, i, s[i]);
    }
    // Gamma 1 is the course's "no Tonemap" PNG: clamp and scale only.
    const auto linear = pt::tonemapToRgb8(greyRow({0.2f, 0.8f, 1.5f}), clampOp(false, 1.0f));
    expectGrey(linear, 0, 51);
    expectGrey(linear, 1, 204);
    expectGrey(linear, 2, 255);
}

TEST(Tonemap, ClampExposureAndLayout) {
    // Distinct pixels in a 2x2 image check row-major, top-row-first order; +1 stop doubles.
    Image im{2, 2,
        {0.1f, 0.0f, 0.0f, 1.0f, 0.0f, 0.2f, 0.0f, 1.0f,      // top row
            0.0f, 0.0f, 0.3f, 1.0f, 0.4f, 0.4f, 0.4f, 1.0f}}; // bottom row
    const auto rgb = pt::tonemapToRgb8(im, clampOp(false), 1.0f);
    const std::vector<uint8_t> expected = {51, 0, 0, 0, 102, 0, 0, 0, 153, 204, 204, 204};
    EXPECT_EQ(rgb, expected);
}

// ---- Photographic operator, step by step ----

TEST(Tonemap, LogAverageKeyMapping) {
    // Y = 0.01 and 1: L_avg = exp((ln 0.010001 + ln 1.000001) / 2) = 0.1000050, so with key
    // 0.18, L = 0.0179991 and 1.7999091, Ld = L/(1+L) = 0.0176808 and 0.6428455 -> 4.51 and
    // 163.93. (An arithmetic mean, 0.505, would give 1 and 67.)
    const auto rgb = pt::tonemapToRgb8(greyRow({0.01f, 1.0f}), photographic(0.18f));
    expectGrey(rgb, 0, 5);
    expectGrey(rgb, 1, 164);
}

TEST(Tonemap, DeltaKeepsBlackPixelsFinite) {
    // Y = 0 and 1: L_avg = sqrt(1e-6 * 1.000001) = 0.0010000005, L = 179.99991, Ld = 0.9944751
    // -> 253.59. delta 1e-4 would give 242, 1e-5 251; without delta L_avg would be 0.
    const auto rgb = pt::tonemapToRgb8(greyRow({0.0f, 1.0f}), photographic(0.18f));
    expectGrey(rgb, 0, 0);
    expectGrey(rgb, 1, 254);
}

TEST(Tonemap, ConstantImageMapsToKeyOverOnePlusKey) {
    // L_avg = delta + Y, so L = key * Y/(Y + delta) ~ key and Ld ~ key/(1+key), at any level.
    for (float level : {0.3f, 1.0f, 50.0f}) {
        for (auto [key, expected] : {std::pair{0.18f, 39}, // 38.90
                 std::pair{0.5f, 85},                      // 84.99
                 std::pair{2.0f, 170}}) {                  // 169.99
            const auto rgb = pt::tonemapToRgb8(constant(3, 2, level, level, level), photographic(key));
            for (std::size_t i = 0; i < 6; ++i) expectGrey(rgb, i, expected);
        }
    }
    // The same through the display curves: Ld = 0.152530 -> sRGB 108.87, ^(1/2.2) 108.48.
    TonemapSettings s = photographic(0.18f);
    s.srgb = true;
    expectGrey(pt::tonemapToRgb8(constant(1, 1, 1.0f, 1.0f, 1.0f), s), 0, 109);
    s.srgb = false;
    s.gamma = 2.2f;
    expectGrey(pt::tonemapToRgb8(constant(1, 1, 1.0f, 1.0f, 1.0f), s), 0, 108);
}

TEST(Tonemap, BurnPercentileWhitePoint) {
    // Grey ramp Y = i/n, i = 1..n, in shuffled positions so the percentile cannot depend
    // on pixel order. With burn 1 the brightest 1% (n = 100: one pixel, n = 200: two) sit
    // at or above L_white and reach exactly 1.0; the next one is visibly below (n = 100:
    // 251.5). With burn 0 there is no white point: the brightest is only 81.9 (n = 100).
    for (int n : {100, 200}) {
        std::vector<float> values(n);
        // 37 is coprime to n, so i -> 37i mod n is a permutation.
        for (int i = 0; i < n; ++i) values[(i * 37) % n] = float(i + 1) / float(n);
        const Image im = greyRow(values);
        const auto burn1 = pt::tonemapToRgb8(im, photographic(0.18f, 1.0f));
        const auto burn0 = pt::tonemapToRgb8(im, photographic(0.18f, 0.0f));
        const int burned = n / 100;
        for (int i = 0; i < n; ++i) {
            const int pos = i * 37 % n; // where value (i+1)/n sits
            if (i >= n - burned)
                expectGrey(burn1, pos, 255);
            else
                EXPECT_LT(px(burn1, pos, 0), 255) << "n " << n << " value " << i + 1;
            EXPECT_LT(px(burn0, pos, 0), 255);
            EXPECT_GE(px(burn1, pos, 0), px(burn0, pos, 0)); // the white term only brightens
        }
        if (n == 100) {
            EXPECT_EQ(px(burn1, (98 * 37) % n, 0), 252);
            EXPECT_EQ(px(burn0, (99 * 37) % n, 0), 82);
        }
    }
}

TEST(Tonemap, FractionalBurnCountsPixelsNotFloatNoise) {
    // 0.1f is 0.100000001 as a float: 0.1% of 1000 pixels must burn 1 pixel, not 2.
    std::vector<float> values(1000);
    // A ramp up to 0.4995 and one pixel at 1: the runner-up is far below the brightest, so
    // it reaches 255 only if it wrongly becomes the white point.
    for (int i = 0; i < 999; ++i) values[i] = float(i + 1) / 2000.0f;
    values[999] = 1.0f;
    const auto rgb = pt::tonemapToRgb8(greyRow(values), photographic(0.18f, 0.1f));
    EXPECT_EQ(px(rgb, 999, 0), 255);
    EXPECT_LT(px(rgb, 998, 0), 255);
}

TEST(Tonemap, BurnEverythingIncludingDegenerateWhite) {
    // burn 100: L_white is the darkest pixel, so every pixel burns. If that pixel is black,
    // L_white = 0; non-black pixels must then saturate and black stay black, with no NaN.
    const auto all = pt::tonemapToRgb8(greyRow({0.2f, 0.5f, 3.0f}), photographic(0.18f, 100.0f));
    for (int i = 0; i < 3; ++i) expectGrey(all, i, 255);

    Image im = greyRow({0.0f, 0.0f, 0.0f, 0.5f});
    im.at(3, 0)[2] = 0.0f; // a coloured pixel, so a zero channel meets the infinite term
    const auto degenerate = pt::tonemapToRgb8(im, photographic(0.18f, 100.0f, 0.5f));
    for (int i = 0; i < 3; ++i) expectGrey(degenerate, i, 0);
    EXPECT_EQ(px(degenerate, 3, 0), 255);
    EXPECT_EQ(px(degenerate, 3, 1), 255);
    EXPECT_EQ(px(degenerate, 3, 2), 0);
}

TEST(Tonemap, SaturationRestoresColour) {
    // One pixel C = (0.8, 0.4, 0.2): Y = 0.4706, key 0.5 -> L = 0.49989, Ld = 0.333284.
    // C/Y = (1.7000, 0.8500, 0.4250).
    const Image im = constant(1, 1, 0.8f, 0.4f, 0.2f);
    // s = 1 keeps the hue ratios 4:2:1: 255 Ld C/Y = 144.48, 72.24, 36.12.
    const auto s1 = pt::tonemapToRgb8(im, photographic(0.5f, 0.0f, 1.0f));
    EXPECT_EQ(px(s1, 0, 0), 144);
    EXPECT_EQ(px(s1, 0, 1), 72);
    EXPECT_EQ(px(s1, 0, 2), 36);
    // s = 0.5: 255 Ld sqrt(C/Y) = 110.81, 78.35, 55.40.
    const auto s05 = pt::tonemapToRgb8(im, photographic(0.5f, 0.0f, 0.5f));
    EXPECT_EQ(px(s05, 0, 0), 111);
    EXPECT_EQ(px(s05, 0, 1), 78);
    EXPECT_EQ(px(s05, 0, 2), 55);
    // s = 0 gives grey at the mapped luminance, even for a zero channel (0^0 = 1).
    expectGrey(pt::tonemapToRgb8(im, photographic(0.5f, 0.0f, 0.0f)), 0, 85);
    expectGrey(pt::tonemapToRgb8(constant(1, 1, 0.9f, 0.0f, 0.0f), photographic(0.5f, 0, 0)), 0, 85);
}

TEST(Tonemap, NonFinitePixelsAreMagentaAndIgnored) {
    // The finite pixels must map exactly as in an image without the bad ones: they are
    // left out of L_avg and of the percentile.
    const Image clean = greyRow({0.01f, 1.0f, 0.3f, 2.0f});
    Image dirty = greyRow({0.01f, 1.0f, 0.3f, 2.0f, kNaN, kInf, -kInf, 1.0f});
    dirty.at(7, 0)[1] = kNaN; // one bad channel is enough
    for (const TonemapSettings& s : {photographic(0.18f), photographic(0.18f, 1.0f), photographic(0.18f, 50.0f, 0.5f),
             clampOp(true), clampOp(false, 2.2f)}) {
        const auto a = pt::tonemapToRgb8(clean, s);
        const auto b = pt::tonemapToRgb8(dirty, s);
        for (std::size_t i = 0; i < 4; ++i)
            for (int c = 0; c < 3; ++c) EXPECT_EQ(px(a, i, c), px(b, i, c)) << "pixel " << i;
        for (std::size_t i = 4; i < 8; ++i) expectMagenta(b, i);
    }
    // Nothing finite at all: every pixel magenta, no crash.
    const auto allBad = pt::tonemapToRgb8(greyRow({kNaN, kInf}), photographic(0.18f, 1.0f));
    expectMagenta(allBad, 0);
    expectMagenta(allBad, 1);
}

TEST(Tonemap, AllBlackImageStaysBlack) {
    const Image black = constant(4, 3, 0.0f, 0.0f, 0.0f);
    for (const TonemapSettings& s : {photographic(0.18f), photographic(0.18f, 1.0f), photographic(0.18f, 100.0f, 0.5f),
             photographic(0.18f, 0.0f, 0.0f), clampOp(true), clampOp(false, 2.2f)}) {
        for (float exposure : {0.0f, 5.0f}) {
            const auto rgb = pt::tonemapToRgb8(black, s, exposure);
            ASSERT_EQ(rgb.size(), 4u * 3 * 3);
            for (uint8_t v : rgb) EXPECT_EQ(v, 0);
        }
    }
}

TEST(Tonemap, NegativeChannelsClampToZero) {
    // (0.5, -0.5, -2) tone maps as (0.5, 0, 0); an all-negative pixel is black. Both images
    // also have a mid-grey pixel so L_avg is the same.
    const Image neg{3, 1, {0.5f, -0.5f, -2.0f, 1.0f, -1.0f, -1.0f, -1.0f, 1.0f, 0.4f, 0.4f, 0.4f, 1.0f}};
    const Image pos{3, 1, {0.5f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 1.0f, 0.4f, 0.4f, 0.4f, 1.0f}};
    for (const TonemapSettings& s : {photographic(0.18f), photographic(0.18f, 1.0f, 0.7f), clampOp(true)})
        EXPECT_EQ(pt::tonemapToRgb8(neg, s), pt::tonemapToRgb8(pos, s));
}

TEST(Tonemap, ExposureIsAppliedBeforePhotographic) {
    // +2 stops equals multiplying the image by 4 (exact in float).
    Image im = greyRow({0.0f, 0.01f, 0.2f, 1.5f});
    im.at(1, 0)[0] = 0.07f;
    Image times4 = im;
    for (float& v : times4.rgba) v *= 4.0f;
    for (const TonemapSettings& s : {photographic(0.18f), photographic(0.18f, 25.0f)})
        EXPECT_EQ(pt::tonemapToRgb8(im, s, 2.0f), pt::tonemapToRgb8(times4, s, 0.0f));
}

TEST(Tonemap, RejectsBadArguments) {
    const Image ok = greyRow({0.5f});
    const Image inconsistent{2, 2, std::vector<float>(10)};
    EXPECT_THROW(pt::tonemapToRgb8(inconsistent, clampOp(true)), std::invalid_argument);
    EXPECT_THROW(pt::tonemapToRgb8(Image{-1, 1, {}}, clampOp(true)), std::invalid_argument);
    EXPECT_THROW(pt::tonemapToRgb8(ok, clampOp(true), kNaN), std::invalid_argument);
    EXPECT_THROW(pt::tonemapToRgb8(ok, clampOp(true), 200.0f), std::invalid_argument);
    EXPECT_THROW(pt::tonemapToRgb8(ok, clampOp(false, 0.0f)), std::invalid_argument);
    EXPECT_NO_THROW(pt::tonemapToRgb8(ok, clampOp(true, 0.0f))); // gamma unused with sRGB
    EXPECT_THROW(pt::tonemapToRgb8(ok, photographic(0.0f)), std::invalid_argument);
    EXPECT_THROW(pt::tonemapToRgb8(ok, photographic(kNaN)), std::invalid_argument);
    EXPECT_THROW(pt::tonemapToRgb8(ok, photographic(0.18f, -1.0f)), std::invalid_argument);
    EXPECT_THROW(pt::tonemapToRgb8(ok, photographic(0.18f, 101.0f)), std::invalid_argument);
    EXPECT_THROW(pt::tonemapToRgb8(ok, photographic(0.18f, kNaN)), std::invalid_argument);
    EXPECT_THROW(pt::tonemapToRgb8(ok, photographic(0.18f, 0.0f, -0.5f)), std::invalid_argument);
    // Key, burn and saturation are not looked at by Clamp.
    TonemapSettings c = photographic(0.0f, -5.0f, -1.0f);
    c.op = TonemapSettings::Operator::Clamp;
    EXPECT_NO_THROW(pt::tonemapToRgb8(ok, c));
    EXPECT_TRUE(pt::tonemapToRgb8(Image{}, photographic(0.18f)).empty());
}

// ---- PNG output ----

class TonemapPngTest : public ::testing::Test {
protected:
    // A fresh directory per test so parallel ctest runs cannot collide and the
    // "no temporary file left behind" checks see only this test's output.
    void SetUp() override { dir_ = pt::test::freshTestDirectory("tonemap"); }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }
    std::size_t entries() const {
        return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
    }
    fs::path dir_;
};

// Expects fn() to throw std::runtime_error naming `file` and containing `needle`.
template <class Fn>
void expectPathError(Fn fn, const fs::path& file, const std::string& needle) {
    try {
        fn();
        ADD_FAILURE() << "no exception for " << file;
    } catch (const std::runtime_error& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.rfind(file.string() + ": ", 0), 0u) << msg;
        EXPECT_NE(msg.find(needle), std::string::npos) << msg;
    }
}

TEST_F(TonemapPngTest, WrittenPngDecodesToTheSameBytes) {
    // A varied 7x5 image with a NaN, through photographic with burn and the sRGB curve.
    Image im{7, 5, {}};
    for (int i = 0; i < 35; ++i)
        im.rgba.insert(im.rgba.end(), {0.05f * float(i), 0.3f * float(i % 4), float(i % 3), 1});
    im.at(2, 3)[0] = kNaN;
    TonemapSettings s = photographic(0.18f, 1.0f, 0.8f);
    s.srgb = true;
    const auto expected = pt::tonemapToRgb8(im, s, 0.5f);

    const fs::path file = dir_ / "out.png";
    { std::ofstream(file) << "old contents"; } // replaced atomically
    pt::writeTonemappedPng(file, im, s, 0.5f);

    int w = 0, h = 0, comp = 0;
    unsigned char* data = stbi_load(file.c_str(), &w, &h, &comp, 3);
    ASSERT_NE(data, nullptr) << stbi_failure_reason();
    EXPECT_EQ(w, 7);
    EXPECT_EQ(h, 5);
    EXPECT_EQ(comp, 3);
    EXPECT_EQ(std::vector<uint8_t>(data, data + 7 * 5 * 3), expected);
    stbi_image_free(data);
    EXPECT_EQ(entries(), 1u); // no temporary left behind
}

TEST_F(TonemapPngTest, ErrorsNameThePathAndLeaveNoFile) {
    const Image ok = greyRow({0.5f});
    const fs::path missingDir = dir_ / "no" / "such" / "dir.png";
    expectPathError([&] { pt::writeTonemappedPng(missingDir, ok, clampOp(true)); }, missingDir,
        "cannot write (No such file or directory)");

    const fs::path bad = dir_ / "bad.png";
    expectPathError([&] { pt::writeTonemappedPng(bad, ok, photographic(-1.0f)); }, bad, "key value");
    expectPathError([&] { pt::writeTonemappedPng(bad, Image{}, clampOp(true)); }, bad, "empty image");
    expectPathError(
        [&] {
            pt::writeTonemappedPng(bad, Image{2, 2, std::vector<float>(3)}, clampOp(true));
        },
        bad, "pixel buffer");
    EXPECT_EQ(entries(), 0u);

    // A failed write keeps the previous file intact.
    const fs::path keep = dir_ / "keep.png";
    pt::writeTonemappedPng(keep, ok, clampOp(true));
    const auto size = fs::file_size(keep);
    expectPathError([&] { pt::writeTonemappedPng(keep, ok, clampOp(false, -2.0f)); }, keep, "gamma");
    EXPECT_EQ(fs::file_size(keep), size);
    EXPECT_EQ(entries(), 1u);
}

} // namespace
