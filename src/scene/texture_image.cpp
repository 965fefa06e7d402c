#include "scene/texture_image.h"

#include "render/image_io.h"

// STB_IMAGE_STATIC keeps stb_image's symbols private to this file: tinygltf's shared library
// carries its own copy, and a global definition here would interpose on it.
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_FAILURE_USERMSG
#include <stb/stb_image.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
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

struct StbFree {
    void operator()(void* p) const { stbi_image_free(p); }
};

} // namespace

TextureImage decodeTextureImage(const unsigned char* bytes, size_t size, const std::string& source) {
    if (size == 0) fail(source, "image data is empty");
    if (size > static_cast<size_t>(std::numeric_limits<int>::max())) fail(source, "image data is larger than 2 GiB");
    const int length = static_cast<int>(size);
    int width = 0, height = 0, channels = 0;
    if (!stbi_info_from_memory(bytes, length, &width, &height, &channels))
        fail(source, std::string("cannot decode image (") + stbi_failure_reason() + ")");
    checkSize(width, height, source);
    TextureImage image;
    image.source = source;
    image.width = width;
    image.height = height;
    const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
    if (stbi_is_hdr_from_memory(bytes, length)) {
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
