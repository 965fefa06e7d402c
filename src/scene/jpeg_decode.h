#pragma once
// JPEG textures through libjpeg-turbo: Debian 12's stb_image mis-decodes hostile JPEG entropy
// data (out-of-bounds table reads and writes that fuzzing found faster than they could be
// screened for), while libjpeg-turbo is the reference decoder and is fuzzed continuously
// upstream (OSS-Fuzz).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace pt {

// True when the data starts like a JPEG (0xFF fill bytes, then the start-of-image marker).
bool looksLikeJpeg(const unsigned char* bytes, size_t size);

struct DecodedJpeg {
    int width = 0;
    int height = 0;
    std::vector<uint32_t> rgba8; // R in the low byte, alpha 255
};

// Decodes to 8-bit RGBA. Throws std::runtime_error("SOURCE: cannot decode image (...)") on
// corrupt data, and on images with a side over maxSide or more pixels than maxPixels (checked
// from the header, before anything is allocated for the pixels).
DecodedJpeg decodeJpeg(const unsigned char* bytes, size_t size, const std::string& source, int maxSide, size_t maxPixels);

} // namespace pt
