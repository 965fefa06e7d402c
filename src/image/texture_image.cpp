#include "image/texture_image.h"

#include "image/file_read.h"
#include "image/image_io.h"
#include "image/jpeg_decode.h"
#include "image/stb_input_checks.h"

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
#include <cstring>
#include <limits>
#include <memory>
#include <new>
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

// The width and height in a PNG's IHDR chunk (big-endian, right after the signature), clamped to
// INT_MAX; nothing when the data does not start like a PNG.
std::optional<std::pair<int, int>> declaredPngSize(const unsigned char* bytes, size_t size) {
    static const unsigned char kSignature[] = {
        0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R'};
    if (size < 24 || std::memcmp(bytes, kSignature, sizeof(kSignature)) != 0) return std::nullopt;
    auto read = [&](size_t at) {
        const uint32_t v =
            uint32_t(bytes[at]) << 24 | uint32_t(bytes[at + 1]) << 16 | uint32_t(bytes[at + 2]) << 8 | bytes[at + 3];
        return static_cast<int>(std::min<uint32_t>(v, std::numeric_limits<int>::max()));
    };
    return std::pair{read(16), read(20)};
}

struct StbFree {
    void operator()(void* p) const { stbi_image_free(p); }
};

} // namespace

TextureImage decodeTextureImage(const unsigned char* bytes, size_t size, const std::string& source) {
    if (size == 0) fail(source, "image data is empty");
    if (size > static_cast<size_t>(std::numeric_limits<int>::max())) fail(source, "image data is larger than 2 GiB");
    const int length = static_cast<int>(size);
    if (looksLikeJpeg(bytes, size))
        return decodeJpeg(bytes, size, source, kMaxTextureSide, kMaxPixelsPerByte * size + kAlwaysPlausiblePixels);
    rejectInputsStbImageMishandles(bytes, size, source);
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
        fail(source, "image header claims " + std::to_string(width) + "x" + std::to_string(height) +
                         " pixels but the data is only " + std::to_string(size) + " bytes (corrupt or hostile header)");
    TextureImage image;
    image.source = source;
    image.width = width;
    image.height = height;
    if (stbi_is_hdr_from_memory(bytes, length)) {
        std::unique_ptr<float, StbFree> data(stbi_loadf_from_memory(bytes, length, &width, &height, &channels, 4));
        if (!data) fail(source, std::string("cannot decode image (") + stbi_failure_reason() + ")");
        image.rgbaF.resize(pixels);
        std::memcpy(image.rgbaF.data(), data.get(), pixels * sizeof(glm::vec4));
    } else {
        std::unique_ptr<unsigned char, StbFree> data(
            stbi_load_from_memory(bytes, length, &width, &height, &channels, 4));
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
    std::transform(
        ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
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
    // By the input-file policy (file_read.h): regular files only (a scene naming /dev/zero or
    // /dev/stdin would be read forever), in this reader's own words. Empty and oversized files
    // are left to the decoder's checks, which word them for every image source alike.
    const FileRead file = tryReadInputFile(path);
    switch (file.problem) {
    case FileProblem::None: break;
    case FileProblem::NotFound: fail(source, "cannot open image file (not found)");
    case FileProblem::CannotAccess:
    case FileProblem::Directory:
    case FileProblem::NotRegularFile: fail(source, "not a regular file");
    case FileProblem::OutOfMemory: throw std::bad_alloc();
    case FileProblem::ReadFailed:
        fail(source, "read failed (" +
                         (file.reason.empty() ? std::string("the file shrank while being read") : file.reason) + ")");
    default: fail(source, "cannot open image file"); // CannotOpen, SizeUnknown
    }
    return decodeTextureImage(file.bytes.data(), file.bytes.size(), source);
}

Image loadRadianceImage(const std::filesystem::path& path) {
    TextureImage t = loadTextureImage(path);
    if (t.rgbaF.empty())
        fail(path.string(),
            "an environment map needs high dynamic range (OpenEXR or Radiance .hdr), not an 8-bit image");
    Image image;
    image.width = t.width;
    image.height = t.height;
    image.rgba.resize(t.rgbaF.size() * 4);
    std::memcpy(image.rgba.data(), t.rgbaF.data(), image.rgba.size() * sizeof(float));
    return image;
}

} // namespace pt
