#pragma once
// Decoding the images textures read: PNG, BMP, TGA and the like through stb_image and JPEG through
// libjpeg-turbo (kept as 8-bit RGBA), Radiance .hdr through stb_image and OpenEXR through OpenEXR
// (kept as float).
#include "image/image.h"

#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace pt {

// An image a texture reads: 8-bit RGBA (packed, as in the file) or float RGBA.
struct TextureImage {
    int width = 0, height = 0;
    std::vector<uint32_t> rgba8;  // row 0 at the top; R in the low byte
    std::vector<glm::vec4> rgbaF; // used instead when the file is HDR
    std::string source;           // file name, for messages
};

// Largest texture side accepted: a hostile header must not make us allocate gigabytes.
constexpr int kMaxTextureSide = 16384;

// Throws std::runtime_error "<source>: <problem>" when the file is missing or undecodable.
TextureImage loadTextureImage(const std::filesystem::path& path);

// A radiance map (environment): OpenEXR or Radiance .hdr, as a float image. Throws
// "<file>: <problem>" for missing files and for 8-bit images, which cannot hold radiance.
Image loadRadianceImage(const std::filesystem::path& path);

// Decodes an image held in memory (glTF buffer views and data URIs); `source` names it in errors.
TextureImage decodeTextureImage(const unsigned char* bytes, size_t size, const std::string& source);

} // namespace pt
