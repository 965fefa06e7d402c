// Image decoding for textures and environment maps (src/scene/texture_image.cpp): formats,
// the packing the kernel expects, and hostile headers.
#include "scene/texture_image.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;

namespace {

std::string rgbe(int width, int height, const std::string& pixels) {
    return "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " + std::to_string(width) + "\n" + pixels;
}

fs::path writeTemp(const std::string& name, const std::string& bytes) {
    const fs::path p = fs::temp_directory_path() / ("pt_texture_image_" + std::to_string(::getpid()) + "_" + name);
    std::ofstream(p, std::ios::binary) << bytes;
    return p;
}

TEST(TextureImage, EightBitImagesArePackedRgbaWithRedInTheLowByte) {
    const std::string ppm = std::string("P6\n2 1\n255\n") + std::string("\x10\x20\x30\xff\x00\x80", 6);
    const pt::TextureImage t = pt::decodeTextureImage(reinterpret_cast<const unsigned char*>(ppm.data()), ppm.size(), "mem");
    ASSERT_EQ(t.width, 2);
    ASSERT_EQ(t.height, 1);
    ASSERT_EQ(t.rgba8.size(), 2u);
    EXPECT_TRUE(t.rgbaF.empty());
    EXPECT_EQ(t.rgba8[0], 0xff302010u); // opaque alpha added
    EXPECT_EQ(t.rgba8[1], 0xff8000ffu);
}

TEST(TextureImage, RadianceHdrDecodesToFloat) {
    // RGBE (128, 64, 32, 130): mantissas / 256 * 2^(130 - 128) = (2, 1, 0.5).
    const std::string file = rgbe(2, 1, std::string("\x80\x40\x20\x82\x80\x40\x20\x82", 8));
    const fs::path p = writeTemp("sky.hdr", file);
    const pt::Image img = pt::loadRadianceImage(p);
    ASSERT_EQ(img.width, 2);
    EXPECT_NEAR(img.rgba[0], 2.0f, 0.02f);
    EXPECT_NEAR(img.rgba[1], 1.0f, 0.01f);
    EXPECT_NEAR(img.rgba[2], 0.5f, 0.005f);
    fs::remove(p);
}

TEST(TextureImage, BadImagesAreErrorsNamingTheSource) {
    auto message = [](auto&& f) {
        try {
            f();
        } catch (const std::exception& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    const std::string garbage = "not an image at all";
    EXPECT_NE(message([&] { pt::decodeTextureImage(reinterpret_cast<const unsigned char*>(garbage.data()), garbage.size(), "img 3"); })
                  .find("img 3: cannot decode image"),
        std::string::npos);
    // A header claiming 20000 x 20000 pixels is refused before anything is allocated.
    const std::string huge = "P6\n20000 20000\n255\n";
    EXPECT_NE(message([&] { pt::decodeTextureImage(reinterpret_cast<const unsigned char*>(huge.data()), huge.size(), "big"); })
                  .find("larger than the 16384 pixels"),
        std::string::npos);
    EXPECT_NE(message([&] { pt::decodeTextureImage(nullptr, 0, "empty"); }).find("empty: image data is empty"), std::string::npos);
    EXPECT_NE(message([] { pt::loadTextureImage("/nonexistent/wall.png"); }).find("/nonexistent/wall.png: cannot open"), std::string::npos);
    const fs::path ldr = writeTemp("ldr.ppm", std::string("P6\n1 1\n255\n\x01\x02\x03", 14));
    EXPECT_NE(message([&] { pt::loadRadianceImage(ldr); }).find("needs high dynamic range"), std::string::npos);
    fs::remove(ldr);
}

} // namespace
