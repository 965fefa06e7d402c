#include "image/stb_input_checks.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace pt {
namespace {

[[noreturn]] void fail(const std::string& source, const std::string& problem) {
    throw std::runtime_error(source + ": " + problem);
}

// Debian 12's stb_image (2022-09) has two bugs in binary PNM (P5, P6) that fuzzing found, fixed
// upstream since: header numbers are accumulated in an int that overflows (undefined behaviour),
// and a 16-bit image's channels are converted as if 8-bit before reading twice the buffer
// allocated (a heap overflow). The header is read here first, as stb_image reads it, and such
// files are rejected.
void checkPnmHeader(const unsigned char* bytes, size_t size, const std::string& source) {
    if (size < 2 || bytes[0] != 'P' || (bytes[1] != '5' && bytes[1] != '6')) return;
    auto space = [](unsigned char c) {
        return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r';
    };
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
            if (++digits > kMaxDigits)
                fail(source, "PNM header number with more than " + std::to_string(kMaxDigits) + " digits");
            value = value * 10 + (bytes[i] - '0');
        }
    }
    if (values[2] > 255) fail(source, "16-bit PNM (maxval " + std::to_string(values[2]) + ") is not supported");
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
        if (at + 4 > size)
            fail(source, "Radiance HDR data ends at scanline " + std::to_string(y) + " of " + std::to_string(height));
        if (bytes[at] != 2 || bytes[at + 1] != 2 || (bytes[at + 2] & 0x80)) return; // not run-length encoded
        at += 4;
        for (int channel = 0; channel < 4; ++channel)
            for (int x = 0; x < width;) {
                if (at >= size) fail(source, "Radiance HDR data ends inside scanline " + std::to_string(y));
                int count = bytes[at++];
                if (count == 0)
                    fail(source, "Radiance HDR run of length 0 in scanline " + std::to_string(y) + " (corrupt data)");
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

// PNG: stb_image grows its buffer for the image data to whatever an IDAT chunk's length field
// says before reading the chunk (2 GiB for a hostile 125-byte file, found by fuzz_texture_image's
// long run). Every chunk up to IEND must fit in the data.
void checkPngChunkLengths(const unsigned char* bytes, size_t size, const std::string& source) {
    static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (size < 8 || std::memcmp(bytes, kSignature, 8) != 0) return;
    size_t at = 8;
    while (size - at >= 8) {
        const uint32_t length =
            uint32_t(bytes[at]) << 24 | uint32_t(bytes[at + 1]) << 16 | uint32_t(bytes[at + 2]) << 8 | bytes[at + 3];
        const size_t left = size - at - 8;
        if (length > left)
            fail(source, "cannot decode image (PNG chunk at byte " + std::to_string(at) + " claims " +
                             std::to_string(length) + " bytes but only " + std::to_string(left) +
                             " follow: truncated or corrupt file)");
        if (std::memcmp(bytes + at + 4, "IEND", 4) == 0) return;
        at += 8 + size_t(length) + std::min<size_t>(4, left - length); // the CRC, when present
    }
}

} // namespace

void rejectInputsStbImageMishandles(const unsigned char* bytes, size_t size, const std::string& source) {
    checkPnmHeader(bytes, size, source);
    const auto startsWith = [&](const char* text) {
        return size >= std::strlen(text) && std::memcmp(bytes, text, std::strlen(text)) == 0;
    };
    if (startsWith("#?RADIANCE\n") || startsWith("#?RGBE\n"))
        checkHdrRunLengths(bytes, size, source); // stb_image's test
    checkPngChunkLengths(bytes, size, source);
}

} // namespace pt
