#include "scene/texture_image.h"

#include "render/image_io.h"

// STB_IMAGE_STATIC keeps stb_image's symbols private to this file: tinygltf's shared library
// carries its own copy, and a global definition here would interpose on it.
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_FAILURE_USERMSG
// stb_image calls memcpy(NULL, src, 0) for an empty PNG IDAT chunk: formally undefined, harmless
// in practice (nothing is copied), and in a system header we cannot fix. Only that one check is
// switched off for stb_image's functions; every other UBSan check still covers them.
#ifdef __clang__
#pragma clang attribute push(__attribute__((no_sanitize("nonnull-attribute"))), apply_to = function)
#endif
#include <stb/stb_image.h>
#ifdef __clang__
#pragma clang attribute pop
#endif

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <optional>
#include <utility>
#include <stdexcept>

namespace pt {
namespace {

[[noreturn]] void fail(const std::string& source, const std::string& problem) {
    throw std::runtime_error(source + ": " + problem);
}

void checkSize(int width, int height, const std::string& source) {
    if (width <= 0 || height <= 0) fail(source, "image has no pixels");
    if (width > kMaxTextureSide || height > kMaxTextureSide)
        fail(source, "image is " + std::to_string(width) + "x" + std::to_string(height) + ", larger than the " +
                         std::to_string(kMaxTextureSide) + " pixels per side textures may have");
}

// No format stb_image reads packs more pixels into a byte than this: deflate (PNG) expands at
// most 1032:1 and a 1-bit PNG holds 8 pixels a byte (8256), GIF's 12-bit LZW under 3000, TGA and
// PSD run lengths 64, Radiance RLE about 16, JPEG at best one bit for a block of 64 pixels (512).
// A header claiming more (a 43-byte TGA of 7423x3822, found by fuzzing) would make stb_image
// allocate and fill the whole image from nothing; it is rejected before decoding.
constexpr size_t kMaxPixelsPerByte = 16384;
constexpr size_t kAlwaysPlausiblePixels = 1 << 16;

// Debian 12's stb_image (2022-09) has two bugs in binary PNM (P5, P6) that fuzzing found, fixed
// upstream since: header numbers are accumulated in an int that overflows (undefined behaviour),
// and a 16-bit image's channels are converted as if 8-bit before reading twice the buffer
// allocated (a heap overflow). The header is read here first, as stb_image reads it, and such
// files are rejected.
void checkPnmHeader(const unsigned char* bytes, size_t size, const std::string& source) {
    if (size < 2 || bytes[0] != 'P' || (bytes[1] != '5' && bytes[1] != '6')) return;
    auto space = [](unsigned char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r'; };
    constexpr int kMaxDigits = 8; // the largest side allowed, 16384, has 5
    size_t i = 2;
    long values[3] = {};
    for (long& value : values) {
        for (;;) { // whitespace, and comments from '#' to the end of the line
            while (i < size && space(bytes[i])) ++i;
            if (i >= size || bytes[i] != '#') break;
            while (i < size && bytes[i] != '\n' && bytes[i] != '\r') ++i;
        }
        for (int digits = 0; i < size && bytes[i] >= '0' && bytes[i] <= '9'; ++i) {
            if (++digits > kMaxDigits) fail(source, "PNM header number with more than " + std::to_string(kMaxDigits) + " digits");
            value = value * 10 + (bytes[i] - '0');
        }
    }
    if (values[2] > 255) fail(source, "16-bit PNM (maxval " + std::to_string(values[2]) + ") is not supported");
}

// The width and height in a PNG's IHDR chunk (big-endian, right after the signature), clamped to
// INT_MAX; nothing when the data does not start like a PNG.
std::optional<std::pair<int, int>> declaredPngSize(const unsigned char* bytes, size_t size) {
    static const unsigned char kSignature[] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R'};
    if (size < 24 || std::memcmp(bytes, kSignature, sizeof(kSignature)) != 0) return std::nullopt;
    auto read = [&](size_t at) {
        const uint32_t v = uint32_t(bytes[at]) << 24 | uint32_t(bytes[at + 1]) << 16 | uint32_t(bytes[at + 2]) << 8 | bytes[at + 3];
        return static_cast<int>(std::min<uint32_t>(v, std::numeric_limits<int>::max()));
    };
    return std::pair{read(16), read(20)};
}

// Radiance .hdr run-length data: stb_image's decoder loops forever on a run count of 0, which
// is also what it reads past the end of truncated data (found by fuzz_texture_image). Walk the
// scanlines as it will and reject such files first; anything else odd is left to stb_image,
// which reports it.
void checkHdrRunLengths(const unsigned char* bytes, size_t size, const std::string& source) {
    size_t at = 0;
    // One header line as stb_image sees it: a C string, so a NUL byte ends it (a line starting
    // with NUL is the blank line that ends the header; found by the fuzzer's long run).
    auto line = [&] {
        std::string text;
        while (at < size && bytes[at] != '\n') text += static_cast<char>(bytes[at++]);
        if (at < size) ++at;
        return text.substr(0, text.find('\0'));
    };
    while (at < size && !line().empty()) {} // header lines up to the blank one
    int height = 0, width = 0;
    if (std::sscanf(line().c_str(), "-Y %d +X %d", &height, &width) != 2) return;
    if (width < 8 || width >= 32768 || height <= 0) return; // stored flat: read to the end, no loop
    for (int y = 0; y < height; ++y) {
        if (at + 4 > size) fail(source, "Radiance HDR data ends at scanline " + std::to_string(y) + " of " + std::to_string(height));
        if (bytes[at] != 2 || bytes[at + 1] != 2 || (bytes[at + 2] & 0x80)) return; // not run-length encoded
        at += 4;
        for (int channel = 0; channel < 4; ++channel)
            for (int x = 0; x < width;) {
                if (at >= size) fail(source, "Radiance HDR data ends inside scanline " + std::to_string(y));
                int count = bytes[at++];
                if (count == 0) fail(source, "Radiance HDR run of length 0 in scanline " + std::to_string(y) + " (corrupt data)");
                if (count > 128) {
                    count -= 128;
                    ++at; // the repeated value
                } else {
                    at += count; // literal values
                }
                if (count > width - x) return; // stb_image reports "bad RLE data"
                x += count;
            }
    }
}

struct StbFree {
    void operator()(void* p) const { stbi_image_free(p); }
};

} // namespace

TextureImage decodeTextureImage(const unsigned char* bytes, size_t size, const std::string& source) {
    if (size == 0) fail(source, "image data is empty");
    if (size > static_cast<size_t>(std::numeric_limits<int>::max())) fail(source, "image data is larger than 2 GiB");
    const int length = static_cast<int>(size);
    checkPnmHeader(bytes, size, source);
    int width = 0, height = 0, channels = 0;
    if (!stbi_info_from_memory(bytes, length, &width, &height, &channels)) {
        // stb_image refuses a PNG over 2^30 bytes decoded but then reports "not of any known type";
        // the size its header declares is the more useful message.
        if (const auto png = declaredPngSize(bytes, size)) checkSize(png->first, png->second, source);
        fail(source, std::string("cannot decode image (") + stbi_failure_reason() + ")");
    }
    checkSize(width, height, source);
    const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
    if (pixels > kMaxPixelsPerByte * size + kAlwaysPlausiblePixels)
        fail(source, "image header claims " + std::to_string(width) + "x" + std::to_string(height) + " pixels but the data is only " +
                         std::to_string(size) + " bytes (corrupt or hostile header)");
    TextureImage image;
    image.source = source;
    image.width = width;
    image.height = height;
    if (stbi_is_hdr_from_memory(bytes, length)) {
        checkHdrRunLengths(bytes, size, source);
        std::unique_ptr<float, StbFree> data(stbi_loadf_from_memory(bytes, length, &width, &height, &channels, 4));
        if (!data) fail(source, std::string("cannot decode image (") + stbi_failure_reason() + ")");
        image.rgbaF.resize(pixels);
        std::memcpy(image.rgbaF.data(), data.get(), pixels * sizeof(glm::vec4));
    } else {
        std::unique_ptr<unsigned char, StbFree> data(stbi_load_from_memory(bytes, length, &width, &height, &channels, 4));
        if (!data) fail(source, std::string("cannot decode image (") + stbi_failure_reason() + ")");
        // RGBA bytes in memory order are one little-endian uint with R in the low byte,
        // which is what the kernel's unpackUnorm4x8 expects.
        image.rgba8.resize(pixels);
        std::memcpy(image.rgba8.data(), data.get(), pixels * 4);
    }
    return image;
}

TextureImage loadTextureImage(const std::filesystem::path& path) {
    const std::string source = path.string();
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (ext == ".exr") {
        const Image exr = readExr(path); // its errors name the file already
        checkSize(exr.width, exr.height, source);
        TextureImage image;
        image.source = source;
        image.width = exr.width;
        image.height = exr.height;
        image.rgbaF.resize(static_cast<size_t>(exr.width) * static_cast<size_t>(exr.height));
        std::memcpy(image.rgbaF.data(), exr.rgba.data(), image.rgbaF.size() * sizeof(glm::vec4));
        return image;
    }
    // A device or FIFO (a scene naming /dev/zero or /dev/stdin) would be read forever.
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (status.type() == std::filesystem::file_type::not_found) fail(source, "cannot open image file (not found)");
    if (!std::filesystem::is_regular_file(status)) fail(source, "not a regular file");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(source, "cannot open image file");
    std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return decodeTextureImage(bytes.data(), bytes.size(), source);
}

Image loadRadianceImage(const std::filesystem::path& path) {
    TextureImage t = loadTextureImage(path);
    if (t.rgbaF.empty()) fail(path.string(), "an environment map needs high dynamic range (OpenEXR or Radiance .hdr), not an 8-bit image");
    Image image;
    image.width = t.width;
    image.height = t.height;
    image.rgba.resize(t.rgbaF.size() * 4);
    std::memcpy(image.rgba.data(), t.rgbaF.data(), image.rgba.size() * sizeof(float));
    return image;
}

} // namespace pt
