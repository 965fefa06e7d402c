#include "image/jpeg_decode.h"

#include <csetjmp>
#include <cstdio> // jpeglib.h needs FILE
#include <cstring>
#include <new>
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

// Decodes into `image` (its size and pixels); returns false with `message` set on any error.
bool decodeInto(
    const unsigned char* bytes, size_t size, int maxSide, size_t maxPixels, TextureImage* image, char* message) {
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
    image->width = static_cast<int>(cinfo.image_width);
    image->height = static_cast<int>(cinfo.image_height);
    const size_t pixels = size_t(cinfo.image_width) * cinfo.image_height;
    if (image->width <= 0 || image->height <= 0 || image->width > maxSide || image->height > maxSide ||
        pixels > maxPixels) {
        std::snprintf(message, JMSG_LENGTH_MAX, "JPEG of %dx%d pixels is empty, too large or implausible for its data",
            image->width, image->height);
        jpeg_destroy_decompress(&cinfo);
        return false;
    }
    try {
        image->rgba8.assign(pixels, 0u);
    } catch (const std::bad_alloc&) {
        std::snprintf(message, JMSG_LENGTH_MAX, "out of memory for %dx%d pixels", image->width, image->height);
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
        JSAMPROW row =
            reinterpret_cast<JSAMPROW>(image->rgba8.data() + size_t(cinfo.output_scanline) * cinfo.output_width);
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

TextureImage decodeJpeg(
    const unsigned char* bytes, size_t size, const std::string& source, int maxSide, size_t maxPixels) {
    TextureImage image;
    image.source = source;
    char message[JMSG_LENGTH_MAX] = {};
    if (!decodeInto(bytes, size, maxSide, maxPixels, &image, message))
        throw std::runtime_error(source + ": cannot decode image (" + message + ")");
    return image;
}

} // namespace pt
