#include "image/image_io.h"
#include "film/tonemap.h" // writePng
#include "support/test_directory.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <half.h>

// Decoding the PNG back checks the tonemap, not just that a file appeared.
// STB_IMAGE_STATIC keeps these symbols private to this test, so it cannot
// clash with the stb_image copy libtinygltf.so uses should the test ever be
// linked against it.
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

namespace fs = std::filesystem;

namespace {

// A fresh directory per test so parallel ctest runs cannot collide and the
// "no temporary files left behind" check sees only this test's output.
class ImageIoTest : public ::testing::Test {
protected:
    void SetUp() override { dir_ = pt::test::freshTestDirectory("image_io"); }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(dir_, ignored);
    }
    fs::path dir_;
};

std::vector<char> readBytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const fs::path& p, const char* data, std::size_t n) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(data, static_cast<std::streamsize>(n));
}

pt::Image randomImage(int w, int h, uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-2.0f, 8.0f);
    pt::Image im{w, h, std::vector<float>(static_cast<std::size_t>(w) * h * 4)};
    for (float& v : im.rgba) v = u(rng);
    return im;
}

// Expects fn() to throw std::runtime_error whose message names `file` (by its
// file name; callers pass full paths, so the message has it too) and contains
// `needle`, on one line.
template <class Fn>
void expectIoError(Fn fn, const fs::path& file, const std::string& needle = "") {
    try {
        fn();
        ADD_FAILURE() << "no exception for " << file;
    } catch (const std::runtime_error& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find(file.string()), std::string::npos) << msg;
        EXPECT_NE(msg.find(needle), std::string::npos) << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
}

TEST_F(ImageIoTest, ExrRoundTripIsBitExactIncludingMetadata) {
    // Arbitrary bit patterns cover denormals, +-0, Inf and NaN payloads:
    // float32 + ZIP must preserve every one of them.
    const int w = 37, h = 23;
    pt::Image im{w, h, std::vector<float>(w * h * 4)};
    std::mt19937 rng(1234);
    for (float& v : im.rgba) {
        const auto bits = static_cast<uint32_t>(rng());
        std::memcpy(&v, &bits, sizeof v);
    }
    im.rgba[0] = std::numeric_limits<float>::quiet_NaN();
    im.rgba[1] = std::numeric_limits<float>::infinity();
    im.rgba[2] = -0.0f;
    im.rgba[3] = std::numeric_limits<float>::denorm_min();

    const pt::ImageMetadata meta = {{"spp", "1024"}, {"scene", "scenes/cornell box.gltf"},
        {"render:seed", "42"}, // already namespaced
        {"empty", ""}};
    const fs::path file = dir_ / "round trip.exr";
    pt::writeExr(file, im, meta);

    pt::ImageMetadata readMeta;
    const pt::Image back = pt::readExr(file, &readMeta);
    ASSERT_EQ(back.width, w);
    ASSERT_EQ(back.height, h);
    ASSERT_EQ(back.rgba.size(), im.rgba.size());
    EXPECT_EQ(std::memcmp(back.rgba.data(), im.rgba.data(), im.rgba.size() * sizeof(float)), 0);
    for (const auto& [k, v] : meta) {
        ASSERT_TRUE(readMeta.count(k)) << k;
        EXPECT_EQ(readMeta.at(k), v) << k;
    }

    // Only the final file may remain: the temporary was renamed, not copied.
    int entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++entries;
    EXPECT_EQ(entries, 1);
}

TEST_F(ImageIoTest, ExrOverwriteReplacesFile) {
    const fs::path file = dir_ / "a.exr";
    pt::writeExr(file, randomImage(8, 8, 1), {});
    const pt::Image second = randomImage(5, 3, 2);
    pt::writeExr(file, second, {});
    const pt::Image back = pt::readExr(file);
    EXPECT_EQ(back.width, 5);
    EXPECT_EQ(back.rgba, second.rgba);
}

// Writes a file with OpenEXR directly, as other tools would.
void writeForeignExr(const fs::path& file, int w, int h, const std::vector<std::string>& names,
    const std::vector<half>& data, Imath::V2i origin = {0, 0}) {
    Imath::Box2i dw(origin, origin + Imath::V2i(w - 1, h - 1));
    Imf::Header header(dw, dw);
    for (const auto& n : names) header.channels().insert(n, Imf::Channel(Imf::HALF));
    Imf::OutputFile out(file.c_str(), header);
    Imf::FrameBuffer fb;
    const std::size_t nc = names.size();
    for (std::size_t c = 0; c < nc; ++c)
        fb.insert(names[c], Imf::Slice::Make(Imf::HALF, data.data() + c, dw, nc * sizeof(half), nc * sizeof(half) * w));
    out.setFrameBuffer(fb);
    out.writePixels(h);
}

TEST_F(ImageIoTest, ReadsHalfRgbWithoutAlpha) {
    const fs::path file = dir_ / "half_rgb.exr";
    std::vector<half> data;
    for (int i = 0; i < 2 * 2; ++i)
        for (float v : {0.25f * i, 1.5f, -3.0f}) data.push_back(half(v));
    // A non-zero data-window origin must not shift the pixels.
    writeForeignExr(file, 2, 2, {"R", "G", "B"}, data, {10, -4});
    const pt::Image im = pt::readExr(file);
    ASSERT_EQ(im.width, 2);
    ASSERT_EQ(im.height, 2);
    for (int i = 0; i < 4; ++i) {
        const float* p = im.at(i % 2, i / 2);
        EXPECT_EQ(p[0], 0.25f * i);
        EXPECT_EQ(p[1], 1.5f);
        EXPECT_EQ(p[2], -3.0f);
        EXPECT_EQ(p[3], 1.0f); // absent alpha reads as opaque
    }
}

TEST_F(ImageIoTest, ReadsLuminanceOnlyAsGrey) {
    const fs::path file = dir_ / "y.exr";
    writeForeignExr(file, 3, 1, {"Y"}, {half(0.5f), half(2.0f), half(0.0f)});
    const pt::Image im = pt::readExr(file);
    ASSERT_EQ(im.width, 3);
    const float expected[] = {0.5f, 2.0f, 0.0f};
    for (int x = 0; x < 3; ++x) {
        const float* p = im.at(x, 0);
        EXPECT_EQ(p[0], expected[x]);
        EXPECT_EQ(p[1], expected[x]);
        EXPECT_EQ(p[2], expected[x]);
        EXPECT_EQ(p[3], 1.0f);
    }
}

TEST_F(ImageIoTest, TruncatedExrThrowsNamingFile) {
    const fs::path good = dir_ / "good.exr";
    pt::writeExr(good, randomImage(64, 64, 7), {{"k", "v"}});
    const std::vector<char> bytes = readBytes(good);
    ASSERT_GT(bytes.size(), 1000u);
    // Cut inside the magic, the header, the offset table, the pixel data and
    // just before the end.
    for (std::size_t len : {std::size_t(2), std::size_t(40), std::size_t(400), bytes.size() / 2, bytes.size() - 1}) {
        const fs::path file = dir_ / ("truncated_" + std::to_string(len) + ".exr");
        writeBytes(file, bytes.data(), len);
        expectIoError([&] { pt::readExr(file); }, file);
    }
}

TEST_F(ImageIoTest, RandomBytesThrowNotAnExr) {
    std::mt19937 rng(99);
    std::vector<char> junk(4096);
    for (char& c : junk) c = static_cast<char>(rng());
    const fs::path file = dir_ / "junk.exr";
    writeBytes(file, junk.data(), junk.size());
    expectIoError([&] { pt::readExr(file); }, file, "not an OpenEXR file");

    const fs::path empty = dir_ / "empty.exr";
    writeBytes(empty, nullptr, 0);
    expectIoError([&] { pt::readExr(empty); }, empty, "not an OpenEXR file");
}

TEST_F(ImageIoTest, RandomBytesAfterValidMagicThrow) {
    // Gets past our magic check, so OpenEXR's own parser must reject it.
    std::mt19937 rng(5);
    for (int trial = 0; trial < 50; ++trial) {
        std::vector<char> junk(64 + rng() % 4096);
        for (char& c : junk) c = static_cast<char>(rng());
        const char magicAndVersion[] = {0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0};
        std::memcpy(junk.data(), magicAndVersion, sizeof magicAndVersion);
        const fs::path file = dir_ / "junk_magic.exr";
        writeBytes(file, junk.data(), junk.size());
        expectIoError([&] { pt::readExr(file); }, file);
    }
}

TEST_F(ImageIoTest, CorruptedExrNeverCrashes) {
    // Flip a few bytes of a valid file: reading must either succeed (the
    // damage hit a harmless spot) or throw a runtime_error, never crash.
    const fs::path good = dir_ / "good.exr";
    pt::writeExr(good, randomImage(32, 16, 3), {{"k", "v"}});
    const std::vector<char> bytes = readBytes(good);
    std::mt19937 rng(11);
    for (int trial = 0; trial < 300; ++trial) {
        std::vector<char> bad = bytes;
        for (int k = 0; k < 1 + trial % 4; ++k) bad[4 + rng() % (bad.size() - 4)] = static_cast<char>(rng());
        const fs::path file = dir_ / "flipped.exr";
        writeBytes(file, bad.data(), bad.size());
        try {
            pt::readExr(file);
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
        }
    }
}

TEST_F(ImageIoTest, MissingFileAndDirectoryErrors) {
    const fs::path missing = dir_ / "nope.exr";
    expectIoError([&] { pt::readExr(missing); }, missing, "No such file or directory");

    const fs::path noDir = dir_ / "no_such_dir" / "x.exr";
    expectIoError(
        [&] { pt::writeExr(noDir, randomImage(2, 2, 1), {}); }, noDir, "cannot write (No such file or directory)");
    const fs::path noDirPng = dir_ / "no_such_dir" / "x.png";
    expectIoError(
        [&] { pt::writePng(noDirPng, randomImage(2, 2, 1)); }, noDirPng, "cannot write (No such file or directory)");
}

TEST_F(ImageIoTest, InconsistentImageIsRejected) {
    pt::Image bad{4, 4, std::vector<float>(10)};
    expectIoError([&] { pt::writeExr(dir_ / "bad.exr", bad, {}); }, dir_ / "bad.exr");
    expectIoError([&] { pt::writePng(dir_ / "bad.png", bad); }, dir_ / "bad.png");
    EXPECT_FALSE(fs::exists(dir_ / "bad.exr"));
    // OpenEXR would silently truncate attribute names over 255 characters.
    const pt::ImageMetadata longKey = {{std::string(300, 'k'), "v"}};
    expectIoError(
        [&] { pt::writeExr(dir_ / "k.exr", randomImage(2, 2, 1), longKey); }, dir_ / "k.exr", "metadata key too long");
}

TEST_F(ImageIoTest, PngTonemapAndNanMarker) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    // Pixel values and the 8-bit result expected after the sRGB OETF.
    const std::vector<std::pair<float, int>> cases = {{0.0f, 0}, {1.0f, 255},
        {0.5f, 188}, // 1.055*0.5^(1/2.4)-0.055 = 0.7354
        {0.002f, 7}, // linear toe: 12.92*0.002*255 = 6.6
        {-1.0f, 0}, {10.0f, 255}, {0.2f, 124}};
    const int w = static_cast<int>(cases.size()) + 2;
    pt::Image im{w, 1, std::vector<float>(w * 4, 1.0f)};
    for (int x = 0; x < static_cast<int>(cases.size()); ++x) {
        float* p = im.at(x, 0);
        p[0] = p[1] = p[2] = cases[x].first;
    }
    im.at(w - 2, 0)[1] = nan; // one bad channel is enough to flag the pixel
    im.at(w - 1, 0)[0] = inf;

    const fs::path file = dir_ / "out.png";
    pt::writePng(file, im);
    ASSERT_GT(fs::file_size(file), 0u);

    int pw = 0, ph = 0, comp = 0;
    unsigned char* px = stbi_load(file.c_str(), &pw, &ph, &comp, 3);
    ASSERT_NE(px, nullptr);
    EXPECT_EQ(pw, w);
    EXPECT_EQ(ph, 1);
    EXPECT_EQ(comp, 3);
    for (int x = 0; x < static_cast<int>(cases.size()); ++x)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(px[x * 3 + c], cases[x].second) << "pixel " << x;
    for (int x : {w - 2, w - 1}) {
        EXPECT_EQ(px[x * 3 + 0], 255);
        EXPECT_EQ(px[x * 3 + 1], 0);
        EXPECT_EQ(px[x * 3 + 2], 255);
    }
    stbi_image_free(px);
}

TEST_F(ImageIoTest, PngExposure) {
    pt::Image im{1, 1, {0.25f, 0.125f, 1.0f, 1.0f}};
    const fs::path file = dir_ / "exposed.png";
    pt::writePng(file, im, 1.0f); // x2: 0.5, 0.25, 2 (clamped)
    int pw, ph, comp;
    unsigned char* px = stbi_load(file.c_str(), &pw, &ph, &comp, 3);
    ASSERT_NE(px, nullptr);
    EXPECT_EQ(px[0], 188);
    EXPECT_EQ(px[1], 137); // 1.055*0.25^(1/2.4)-0.055 = 0.5371
    EXPECT_EQ(px[2], 255);
    stbi_image_free(px);
}

} // namespace
