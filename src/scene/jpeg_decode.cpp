#include "scene/jpeg_decode.h"

#include <csetjmp>
#include <cstdio> // jpeglib.h needs FILE
#include <cstring>
#include <stdexcept>

#include <jpeglib.h>

namespace pt {
namespace {

// libjpeg reports fatal errors through error_exit, which must not return: it jumps back to
// decodeInto's setjmp. No C++ object with a destructor lives in that function's frame, so the
// jump skips nothing.
struct ErrorManager {
    jpeg_error_mgr pub;
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX];
};

[[noreturn]] void onError(j_common_ptr cinfo) {
    ErrorManager* err = reinterpret_cast<ErrorManager*>(cinfo->err);
    err->pub.format_message(cinfo, err->message);
    std::longjmp(err->jump, 1);
}

void ignoreMessage(j_common_ptr, int) {} // warnings (such as "premature end of data") are not printed

struct Header {
    int width = 0, height = 0;
};

// Decodes into `pixels` (resized by `reserve` once the header is read); returns false with
// `message` set on any error.
bool decodeInto(const unsigned char* bytes, size_t size, Header* header, std::vector<uint32_t>* pixels,
    bool (*reserve)(const Header&, std::vector<uint32_t>*, char*), char* message) {
    jpeg_decompress_struct cinfo;
    ErrorManager err;
    cinfo.err = jpeg_std_error(&err.pub);
    err.pub.error_exit = onError;
    err.pub.emit_message = ignoreMessage;
    if (setjmp(err.jump)) {
        jpeg_destroy_decompress(&cinfo);
        std::strncpy(message, err.message, JMSG_LENGTH_MAX - 1);
        message[JMSG_LENGTH_MAX - 1] = '\0';
        return false;
    }
    jpeg_create_decompress(&cinfo);
    jpeg_mem_src(&cinfo, bytes, static_cast<unsigned long>(size));
    jpeg_read_header(&cinfo, TRUE);
    // The size is judged from the header, before jpeg_start_decompress: for a progressive JPEG
    // that allocates coefficients for the whole image (4 GB for a hostile 156-byte file).
    header->width = static_cast<int>(cinfo.image_width);
    header->height = static_cast<int>(cinfo.image_height);
    if (!reserve(*header, pixels, message)) {
        jpeg_destroy_decompress(&cinfo);
        return false;
    }
    cinfo.out_color_space = JCS_EXT_RGBA; // libjpeg-turbo: RGBA bytes, alpha 255
    jpeg_start_decompress(&cinfo);
    if (cinfo.output_width != cinfo.image_width || cinfo.output_height != cinfo.image_height) {
        std::snprintf(message, JMSG_LENGTH_MAX, "JPEG output size differs from its header");
        jpeg_destroy_decompress(&cinfo);
        return false;
    }
    while (cinfo.output_scanline < cinfo.output_height) {
        JSAMPROW row = reinterpret_cast<JSAMPROW>(pixels->data() + size_t(cinfo.output_scanline) * cinfo.output_width);
        jpeg_read_scanlines(&cinfo, &row, 1);
    }
    jpeg_finish_decompress(&cinfo);
    jpeg_destroy_decompress(&cinfo);
    return true;
}

} // namespace

bool looksLikeJpeg(const unsigned char* bytes, size_t size) {
    if (size < 2 || bytes[0] != 0xFF) return false;
    size_t at = 1;
    while (at < size && bytes[at] == 0xFF) ++at;
    return at < size && bytes[at] == 0xD8;
}

DecodedJpeg decodeJpeg(const unsigned char* bytes, size_t size, const std::string& source, int maxSide, size_t maxPixels) {
    // The limits reach the C-style reserve callback through these (one decode per thread at a time).
    static thread_local int sideLimit;
    static thread_local size_t pixelLimit;
    sideLimit = maxSide;
    pixelLimit = maxPixels;
    auto reserve = [](const Header& h, std::vector<uint32_t>* pixels, char* message) {
        if (h.width <= 0 || h.height <= 0 || h.width > sideLimit || h.height > sideLimit ||
            size_t(h.width) * size_t(h.height) > pixelLimit) {
            std::snprintf(message, JMSG_LENGTH_MAX, "JPEG of %dx%d pixels is empty, too large or implausible for its data",
                h.width, h.height);
            return false;
        }
        pixels->assign(size_t(h.width) * size_t(h.height), 0u);
        return true;
    };
    DecodedJpeg out;
    Header header;
    char message[JMSG_LENGTH_MAX] = {};
    if (!decodeInto(bytes, size, &header, &out.rgba8, reserve, message))
        throw std::runtime_error(source + ": cannot decode image (" + message + ")");
    out.width = header.width;
    out.height = header.height;
    return out;
}

} // namespace pt
