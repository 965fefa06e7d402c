// Image decoding for textures and environment maps (src/image/texture_image.cpp): formats,
// the packing the kernel expects, and hostile headers.
#include "image/texture_image.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <utility>
#include <string>

namespace fs = std::filesystem;

namespace {

std::string rgbe(int width, int height, const std::string& pixels) {
    return "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " + std::to_string(width) +
           "\n" + pixels;
}

fs::path writeTemp(const std::string& name, const std::string& bytes) {
    const fs::path p = fs::temp_directory_path() / ("pt_texture_image_" + std::to_string(::getpid()) + "_" + name);
    std::ofstream(p, std::ios::binary) << bytes;
    return p;
}

TEST(TextureImage, EightBitImagesArePackedRgbaWithRedInTheLowByte) {
    const std::string ppm = std::string("P6\n2 1\n255\n") + std::string("\x10\x20\x30\xff\x00\x80", 6);
    const pt::TextureImage t =
        pt::decodeTextureImage(reinterpret_cast<const unsigned char*>(ppm.data()), ppm.size(), "mem");
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
    EXPECT_NE(message([&] {
        pt::decodeTextureImage(reinterpret_cast<const unsigned char*>(garbage.data()), garbage.size(), "img 3");
    }).find("img 3: cannot decode image"),
        std::string::npos);
    // A header claiming 20000 x 20000 pixels is refused before anything is allocated.
    const std::string huge = "P6\n20000 20000\n255\n";
    EXPECT_NE(message([&] {
        pt::decodeTextureImage(reinterpret_cast<const unsigned char*>(huge.data()), huge.size(), "big");
    }).find("larger than the 16384 pixels"),
        std::string::npos);
    EXPECT_NE(message([&] { pt::decodeTextureImage(nullptr, 0, "empty"); }).find("empty: image data is empty"),
        std::string::npos);
    EXPECT_NE(message([] { pt::loadTextureImage("/nonexistent/wall.png"); }).find("/nonexistent/wall.png: cannot open"),
        std::string::npos);
    const fs::path ldr = writeTemp("ldr.ppm", std::string("P6\n1 1\n255\n\x01\x02\x03", 14));
    EXPECT_NE(message([&] { pt::loadRadianceImage(ldr); }).find("needs high dynamic range"), std::string::npos);
    fs::remove(ldr);
}

// Found by fuzz_texture_image: run-length data with a run of length 0, or ending inside a
// scanline, made stb_image loop forever. Both must be quick one-line errors naming the source.
TEST(TextureImage, CorruptRadianceRunLengthsAreErrorsNotHangs) {
    auto message = [](const std::string& bytes) {
        try {
            pt::decodeTextureImage(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), "sky.hdr");
        } catch (const std::exception& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2 +X 8\n";
    const std::string scanlineStart("\x02\x02\x00\x08", 4);
    // The fuzzer's input (base64 Iz9SQURJQU5DRQpGT1JNQVQ9MzItYml0X3JsZV9yZ2JlCgotWSAgMitYIDgK...).
    const std::string fuzzed =
        "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y  2+X 8\n" +
        std::string(
            "\x02\x02\x00\x08\x88\x28\x88\x32\x88\x3c\x88\x81\x02\x02\x00\x08\x88\x28\x88\x32\x88\x3c\x01\x00", 24);
    EXPECT_NE(message(fuzzed), "(no error)");
    EXPECT_NE(message(header + scanlineStart + std::string("\x00", 1)).find("sky.hdr: Radiance HDR run of length 0"),
        std::string::npos);
    EXPECT_NE(message(header + scanlineStart + std::string("\x88\x10", 2))
                  .find("sky.hdr: Radiance HDR data ends inside scanline 0"),
        std::string::npos);
    // A well-formed run-length file still decodes: two scanlines, each channel one run of 8.
    std::string good = header;
    for (int y = 0; y < 2; ++y) good += scanlineStart + std::string("\x88\x80\x88\x40\x88\x20\x88\x82", 8);
    const pt::TextureImage image =
        pt::decodeTextureImage(reinterpret_cast<const unsigned char*>(good.data()), good.size(), "good.hdr");
    ASSERT_EQ(image.rgbaF.size(), 16u);
    EXPECT_NEAR(image.rgbaF[15].x, 2.0f, 0.02f);
}

} // namespace

namespace {

std::string readCorpusFile(const std::string& name) {
    std::ifstream in(fs::path(PT_TEST_DATA_DIR) / "fuzz" / "corpus" / "texture_image" / name, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

pt::TextureImage decodeString(const std::string& bytes, const std::string& source) {
    return pt::decodeTextureImage(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), source);
}

} // namespace

// The checks run before stb_image (src/image/stb_input_checks.cpp) walk JPEG markers and PNG
// chunks; they must pass every well-formed file: baseline and progressive JPEG (Huffman tables
// between scans), PNG with several chunks.
TEST(TextureImage, WellFormedJpegAndPngPassTheInputChecks) {
    for (const char* name : {"baseline.jpg", "progressive.jpg", "rgba.png", "palette.png", "grey16.png"}) {
        const std::string bytes = readCorpusFile(name);
        ASSERT_FALSE(bytes.empty()) << name;
        const pt::TextureImage t = decodeString(bytes, name);
        EXPECT_GT(t.width, 0) << name;
        EXPECT_EQ(t.rgba8.size(), size_t(t.width) * t.height) << name;
    }
    const pt::TextureImage jpeg = decodeString(readCorpusFile("baseline.jpg"), "baseline.jpg");
    EXPECT_EQ(jpeg.width, 24);
    EXPECT_EQ(jpeg.height, 16);
}

// Inputs found by the long fuzz run, on which Debian 12's stb_image wrote or read out of bounds
// or allocated 2 GiB: JPEG Huffman tables of more than 256 codes, entropy data decoded through
// an unassigned code (JPEG is now decoded by libjpeg-turbo), and a PNG chunk claiming 2.3 GB in
// a 125-byte file. Each is a one-line error naming the source.
TEST(TextureImage, HostileHuffmanTablesAndChunkLengthsAreErrors) {
    const std::pair<const char*, const char*> cases[] = {
        {"crash-jpeg-dht-over-256-codes.jpg", "Huffman table"},
        {"crash-jpeg-fill-bytes-before-start.jpg", "Not a JPEG file"}, // 0xFF 0xFF 0xD8
        {"oom-png-idat-length-2gib.png", "PNG chunk at byte"},
        {"oom-jpeg-progressive-huge-header.jpg", "implausible for its data"}, // 4 GB of coefficients otherwise
    };
    for (auto [name, problem] : cases) {
        std::string message = "(no error)";
        try {
            decodeString(readCorpusFile(name), name);
        } catch (const std::exception& e) {
            message = e.what();
        }
        EXPECT_EQ(message.rfind(std::string(name) + ": cannot decode image (", 0), 0u) << message;
        EXPECT_NE(message.find(problem), std::string::npos) << message;
    }
}
