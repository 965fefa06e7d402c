#pragma once
// JPEG textures through libjpeg-turbo: Debian 12's stb_image mis-decodes hostile JPEG entropy
// data (out-of-bounds table reads and writes that fuzzing found faster than they could be
// screened for), while libjpeg-turbo is the reference decoder and is fuzzed continuously
// upstream (OSS-Fuzz).
#include "image/texture_image.h"

#include <cstddef>
#include <string>

namespace pt {

// True when the data starts like a JPEG (0xFF fill bytes, then the start-of-image marker).
bool looksLikeJpeg(const unsigned char* bytes, size_t size);

// Decodes to 8-bit RGBA (alpha 255). Throws std::runtime_error("SOURCE: cannot decode image
// (...)") on corrupt data, and on images with a side over maxSide or more pixels than maxPixels
// (judged from the header, before anything is allocated for the pixels).
TextureImage decodeJpeg(
    const unsigned char* bytes, size_t size, const std::string& source, int maxSide, size_t maxPixels);

} // namespace pt
