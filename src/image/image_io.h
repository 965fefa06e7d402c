#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>
#include <cstdint>

#include "image/image.h"

namespace pt {

// Free-form key/value pairs stored in the EXR header (render settings, seed,
// sample count, ...) so an output file documents how it was produced.
using ImageMetadata = std::map<std::string, std::string>;

// Writes float32 R,G,B,A with ZIP compression. Each metadata entry becomes a
// string attribute named "pt:<key>", or "<key>" verbatim if the key already
// contains ':' (i.e. it is already namespaced). The file is written to a
// temporary name in the same directory and renamed into place, so readers
// never see a half-written file.
// Throws std::runtime_error("<path>: <problem>") on any failure.
void writeExr(const std::filesystem::path& path, const Image& image, const ImageMetadata& metadata);

// Extra float32 channels (one value per pixel, row-major), written after R, G, B, A: the raw
// accumulation state of a partial render or checkpoint (film/state_file.h).
struct ExrChannel {
    std::string name;
    std::vector<float> values;
};
void writeExr(const std::filesystem::path& path, const Image& image, const ImageMetadata& metadata,
    const std::vector<ExrChannel>& extra);

// Reads the named float channels of an EXR written by writeExr (exactly, as float32), the
// metadata, and the image size (no names: the header alone). Throws "<path>: <problem>" naming
// the first missing channel.
struct ExrChannels {
    int width = 0, height = 0;
    std::vector<ExrChannel> channels; // in the order of `names`
};
ExrChannels readExrChannels(
    const std::filesystem::path& path, const std::vector<std::string>& names, ImageMetadata* metadata = nullptr);

// Reads the data window of a scanline or tiled EXR of any pixel type.
// Channels R,G,B,A are used; a missing A reads as 1, missing R/G/B as 0, and
// a file with only a Y (luminance) channel is expanded to grey R=G=B=Y.
// If metadata is given, it receives every string attribute of the header;
// the "pt:" prefix added by writeExr is stripped, so writeExr -> readExr
// round-trips keys (except keys that themselves start with "pt:").
// Throws std::runtime_error("<path>: <problem>") on missing, corrupt or
// truncated files; never lets an OpenEXR exception escape.
Image readExr(const std::filesystem::path& path, ImageMetadata* metadata = nullptr);

// Encodes 8-bit RGB (3 bytes per pixel, row-major, top row first) as a PNG, written via a
// temporary file in the same directory and a rename, so readers never see a half-written file
// and a failure leaves any previous file untouched. Tone mapping is film/tonemap.h's job.
// Throws std::runtime_error("<path>: <problem>"), also for an empty image or a size that does
// not match the bytes.
void writePngRgb8(const std::filesystem::path& path, int width, int height, const std::vector<uint8_t>& rgb);

} // namespace pt
