#pragma once
// The callbacks tinygltf calls while it reads a file, ours instead of its own: image decoding
// (image/texture_image.h's decoder and limits for every image, whatever its source) and access
// to the external files that buffers and images name (by image/file_read.h's policy).
#include "image/texture_image.h"

#include <optional>
#include <vector>

namespace tinygltf {
class TinyGLTF;
}

namespace pt::gltf {

// Images decoded as tinygltf reads them (from data URIs, files or buffer views), with our own
// decoder: one code path and one set of size limits for every image, and the error names the
// image. Indexed like the model's images; an image no texture uses is decoded all the same.
struct DecodedImages {
    std::vector<std::optional<TextureImage>> images;
};

// Installs both on `loader`; decoded images land in `images`.
void configureLoader(tinygltf::TinyGLTF& loader, DecodedImages& images);

} // namespace pt::gltf
