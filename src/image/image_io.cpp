#include "image/image_io.h"

#include "image/atomic_file.h"
#include "image/file_read.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfName.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <ImfVersion.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <new>
#include <stdexcept>
#include <system_error>
#include <limits>
#include <string>
#include <vector>

// STB_IMAGE_WRITE_STATIC keeps the stbi_write_* symbols (and its globals) private to this
// file: libtinygltf.so imports stbi_write_png_to_func from libstb.so, which a global
// definition here would interpose on.
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

namespace pt {
namespace {

// Our own errors already carry the "<path>: " prefix; the distinct type lets
// the catch-all handlers below rethrow them untouched instead of wrapping
// them a second time.
struct IoError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Library messages (OpenEXR's especially) can span several lines; the
// contract is a one-line message, so fold whitespace runs into one space.
std::string oneLine(const std::string& s) {
    std::string out;
    bool pendingSpace = false;
    for (char c : s) {
        if (c == '\n' || c == '\r' || c == '\t' || c == ' ') {
            pendingSpace = !out.empty();
        } else {
            if (pendingSpace) out += ' ';
            pendingSpace = false;
            out += c;
        }
    }
    return out;
}

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& problem) {
    throw IoError(path.string() + ": " + oneLine(problem));
}

std::string errnoText(int err) { return std::generic_category().message(err); }

void checkImage(const std::filesystem::path& path, const Image& image) {
    if (image.width <= 0 || image.height <= 0)
        fail(path,
            "cannot write an empty image (" + std::to_string(image.width) + "x" + std::to_string(image.height) + ")");
    const std::size_t expected = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 4;
    if (image.rgba.size() != expected)
        fail(path, "pixel buffer holds " + std::to_string(image.rgba.size()) + " floats, expected " +
                       std::to_string(expected) + " for " + std::to_string(image.width) + "x" +
                       std::to_string(image.height) + " RGBA");
}

// OpenEXR output stream on top of AtomicFile. ~OutputFile() writes the
// scanline offset table and swallows any exception doing so, so a failure
// there must be remembered here and re-checked after the OutputFile is gone.
class ExrOutStream : public Imf::OStream {
public:
    explicit ExrOutStream(AtomicFile& f) : Imf::OStream(f.path().c_str()), f_(f) {}
    void write(const char c[], int n) override {
        try {
            f_.write(c, static_cast<std::size_t>(n));
        } catch (...) {
            failed_ = true;
            throw;
        }
    }
    uint64_t tellp() override {
        long pos = std::ftell(f_.file());
        if (pos < 0) {
            failed_ = true;
            fail(f_.path(), "cannot query write position (" + errnoText(errno) + ")");
        }
        return static_cast<uint64_t>(pos);
    }
    void seekp(uint64_t pos) override {
        if (std::fseek(f_.file(), static_cast<long>(pos), SEEK_SET) != 0) {
            failed_ = true;
            fail(f_.path(), "seek failed (" + errnoText(errno) + ")");
        }
    }
    bool failed() const { return failed_; }

private:
    AtomicFile& f_;
    bool failed_ = false;
};

// OpenEXR input stream over an in-memory copy of the file. Reading the whole
// file up front lets us report open errors with errno and check the magic
// number ourselves; bounds checks here turn truncation into an exception
// instead of a read past the end.
class ExrMemStream : public Imf::IStream {
public:
    ExrMemStream(const std::string& name, const std::vector<unsigned char>& data)
        : Imf::IStream(name.c_str()), data_(data) {}
    bool read(char c[], int n) override {
        if (n < 0 || static_cast<uint64_t>(n) > data_.size() - pos_) throw std::runtime_error("unexpected end of file");
        std::memcpy(c, data_.data() + pos_, static_cast<std::size_t>(n));
        pos_ += static_cast<uint64_t>(n);
        return pos_ < data_.size();
    }
    uint64_t tellg() override { return pos_; }
    void seekg(uint64_t pos) override {
        // Seeking past the end is not an error by itself (like a real file);
        // the next read() will fail.
        pos_ = std::min<uint64_t>(pos, data_.size());
    }

private:
    const std::vector<unsigned char>& data_;
    uint64_t pos_ = 0;
};

// By the input-file policy (file_read.h), in this reader's words, which predate it: the
// system's reason in brackets ("cannot open (No such file or directory)", "read failed (Is a
// directory)"). Unlike the other readers it streams devices and FIFOs to their end (a state file
// or reference can come through a pipe) and has no size limit of its own: the data window check
// below bounds what is decoded, and a stream too big to hold ends as out of memory.
std::vector<unsigned char> readWholeFile(const std::filesystem::path& path) {
    FileRead file = tryReadInputFile(path, {.streamNonRegular = true});
    switch (file.problem) {
    case FileProblem::None: return std::move(file.bytes);
    case FileProblem::NotFound:
    case FileProblem::CannotAccess:
    case FileProblem::CannotOpen: fail(path, "cannot open (" + file.reason + ")");
    case FileProblem::Directory: fail(path, "read failed (" + errnoText(EISDIR) + ")");
    case FileProblem::OutOfMemory: throw std::bad_alloc();
    case FileProblem::ReadFailed:
        fail(path, "read failed (" +
                       (file.reason.empty() ? std::string("the file shrank while being read") : file.reason) + ")");
    default: fail(path, "read failed (" + file.reason + ")"); // SizeUnknown
    }
}

// A corrupt header can claim an enormous data window; refuse it before we
// try to allocate it. 2^27 pixels (e.g. 16384x8192) is far beyond any render
// this project produces but still allocatable (2 GiB of float RGBA).
constexpr int64_t kMaxPixels = int64_t(1) << 27;

// Every string attribute, with the "pt:" prefix writeExr adds stripped.
void readMetadata(const Imf::Header& header, ImageMetadata& metadata) {
    metadata.clear();
    for (auto it = header.begin(); it != header.end(); ++it) {
        const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute());
        if (!s) continue;
        std::string key = it.name();
        if (key.rfind("pt:", 0) == 0) key.erase(0, 3);
        metadata[key] = s->value();
    }
}

// The whole file in memory, refused unless it starts like an OpenEXR file.
std::vector<unsigned char> readExrBytes(const std::filesystem::path& path) {
    std::vector<unsigned char> bytes = readWholeFile(path);
    if (bytes.size() < 4 || !Imf::isImfMagic(reinterpret_cast<const char*>(bytes.data())))
        fail(path, "not an OpenEXR file");
    return bytes;
}

// An EXR file opened from memory, with the checks every reader makes before it reads pixels: a
// plausible data window, and a complete file (checked before readPixels() so truncation gets a
// clear message rather than whatever the decoder says when it runs out of bytes).
struct OpenedExr {
    explicit OpenedExr(const std::filesystem::path& path)
        : bytes(readExrBytes(path)), stream(path.string(), bytes), in(stream), header(in.header()),
          dw(header.dataWindow()), w(int64_t(dw.max.x) - dw.min.x + 1), h(int64_t(dw.max.y) - dw.min.y + 1) {
        if (w <= 0 || h <= 0 || w * h > kMaxPixels)
            fail(path, "implausible data window " + std::to_string(w) + "x" + std::to_string(h) + " (corrupt header?)");
        if (!in.isComplete()) fail(path, "truncated or incomplete OpenEXR file");
    }

    // In construction order: each member reads the one before it.
    std::vector<unsigned char> bytes;
    ExrMemStream stream;
    Imf::InputFile in;
    const Imf::Header& header;
    const Imath::Box2i dw;
    const int64_t w, h;
};

Image readExrImpl(const std::filesystem::path& path, ImageMetadata* metadata) {
    OpenedExr exr(path);
    Imf::InputFile& in = exr.in;
    const Imf::Header& header = exr.header;
    const Imath::Box2i dw = exr.dw;
    const int64_t w = exr.w, h = exr.h;

    const Imf::ChannelList& channels = header.channels();
    const bool hasRgb = channels.findChannel("R") || channels.findChannel("G") || channels.findChannel("B");
    const bool lumaOnly = !hasRgb && channels.findChannel("Y");
    if (!hasRgb && !lumaOnly) fail(path, "no R, G, B or Y channel");
    for (const char* name : {"R", "G", "B", "A", "Y"}) {
        const Imf::Channel* c = channels.findChannel(name);
        if (c && (c->xSampling != 1 || c->ySampling != 1))
            fail(path, std::string("channel ") + name + " is subsampled (not supported)");
    }

    Image image;
    image.width = static_cast<int>(w);
    image.height = static_cast<int>(h);
    image.rgba.assign(static_cast<std::size_t>(w * h * 4), 0.0f);

    // Slices for channels absent from the file are filled with fillValue by
    // OpenEXR, which gives us "A = 1 if absent" for free. Any stored pixel
    // type (HALF, UINT, FLOAT) is converted to FLOAT by the library.
    const std::size_t xStride = 4 * sizeof(float);
    const std::size_t yStride = xStride * static_cast<std::size_t>(w);
    float* base = image.rgba.data();
    auto slice = [&](int offset, double fill) {
        return Imf::Slice::Make(Imf::FLOAT, base + offset, dw, xStride, yStride, 1, 1, fill);
    };
    Imf::FrameBuffer fb;
    if (lumaOnly) {
        fb.insert("Y", slice(0, 0.0));
    } else {
        fb.insert("R", slice(0, 0.0));
        fb.insert("G", slice(1, 0.0));
        fb.insert("B", slice(2, 0.0));
    }
    fb.insert("A", slice(3, 1.0));
    in.setFrameBuffer(fb);
    in.readPixels(dw.min.y, dw.max.y);

    if (lumaOnly) {
        for (std::size_t i = 0; i < image.rgba.size(); i += 4) image.rgba[i + 1] = image.rgba[i + 2] = image.rgba[i];
    }

    if (metadata) readMetadata(header, *metadata);
    return image;
}

ExrChannels readExrChannelsImpl(
    const std::filesystem::path& path, const std::vector<std::string>& names, ImageMetadata* metadata) {
    OpenedExr exr(path);
    Imf::InputFile& in = exr.in;
    const Imf::Header& header = exr.header;
    const Imath::Box2i dw = exr.dw;
    const int64_t w = exr.w, h = exr.h;
    ExrChannels result;
    result.width = static_cast<int>(w);
    result.height = static_cast<int>(h);
    Imf::FrameBuffer fb;
    for (const std::string& name : names) {
        const Imf::Channel* c = header.channels().findChannel(name);
        if (!c) fail(path, "no channel '" + name + "' (not written by pt render --samples or --checkpoint?)");
        if (c->type != Imf::FLOAT || c->xSampling != 1 || c->ySampling != 1)
            fail(path, "channel '" + name + "' is not full-resolution float32");
        result.channels.push_back({name, std::vector<float>(static_cast<std::size_t>(w * h))});
    }
    for (ExrChannel& c : result.channels)
        fb.insert(c.name, Imf::Slice::Make(Imf::FLOAT, c.values.data(), dw, sizeof(float),
                              sizeof(float) * static_cast<std::size_t>(w)));
    if (!names.empty()) { // none: the header alone
        in.setFrameBuffer(fb);
        in.readPixels(dw.min.y, dw.max.y);
    }
    if (metadata) readMetadata(header, *metadata);
    return result;
}

void writeExrImpl(const std::filesystem::path& path, const Image& image, const ImageMetadata& metadata,
    const std::vector<ExrChannel>& extra) {
    checkImage(path, image);
    const std::size_t pixels = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
    for (const ExrChannel& c : extra)
        if (c.values.size() != pixels || c.name.empty())
            fail(path, "extra channel '" + c.name + "' holds " + std::to_string(c.values.size()) +
                           " values, expected " + std::to_string(pixels));

    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    for (const char* name : {"R", "G", "B", "A"}) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    for (const ExrChannel& c : extra) header.channels().insert(c.name, Imf::Channel(Imf::FLOAT));
    for (const auto& [key, value] : metadata) {
        if (key.empty()) fail(path, "empty metadata key");
        // Namespacing our keys keeps them from colliding with standard
        // attributes such as "channels" or "compression".
        const std::string name = key.find(':') == std::string::npos ? "pt:" + key : key;
        // Imf::Name silently truncates longer names, which would corrupt keys.
        if (name.size() > static_cast<std::size_t>(Imf::Name::MAX_LENGTH))
            fail(path, "metadata key too long (" + std::to_string(name.size()) + " characters with prefix, max " +
                           std::to_string(Imf::Name::MAX_LENGTH) + ")");
        header.insert(name, Imf::StringAttribute(value));
    }

    AtomicFile file(path);
    ExrOutStream stream(file);
    {
        Imf::OutputFile out(stream, header);
        const std::size_t xStride = 4 * sizeof(float);
        const std::size_t yStride = xStride * static_cast<std::size_t>(image.width);
        // OpenEXR takes non-const pointers even for writing; it only reads.
        char* base = reinterpret_cast<char*>(const_cast<float*>(image.rgba.data()));
        Imf::FrameBuffer fb;
        const char* names[] = {"R", "G", "B", "A"};
        for (int c = 0; c < 4; ++c)
            fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xStride, yStride));
        for (const ExrChannel& c : extra)
            fb.insert(c.name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(c.values.data())),
                                  sizeof(float), sizeof(float) * static_cast<std::size_t>(image.width)));
        out.setFrameBuffer(fb);
        out.writePixels(image.height);
    } // ~OutputFile writes the offset table here.
    if (stream.failed()) fail(path, "write failed while finalising the file");
    file.commit();
}

} // namespace

// Runs an OpenEXR read, turning every failure into one "<path>: <problem>" error.
template <class Read>
auto withExrErrors(const std::filesystem::path& path, Read read) -> decltype(read()) {
    try {
        return read();
    } catch (const IoError&) {
        throw;
    } catch (const FileWriteError&) {
        throw;
    } catch (const std::bad_alloc&) {
        fail(path, "out of memory while reading (corrupt header?)");
    } catch (const std::exception& e) {
        // Iex::BaseExc derives from std::exception, so this also covers
        // every OpenEXR error on a corrupt or truncated file.
        fail(path, std::string("corrupt or truncated OpenEXR file (") + e.what() + ")");
    } catch (...) {
        fail(path, "corrupt or truncated OpenEXR file (unknown error)");
    }
}

ExrChannels readExrChannels(
    const std::filesystem::path& path, const std::vector<std::string>& names, ImageMetadata* metadata) {
    return withExrErrors(path, [&] { return readExrChannelsImpl(path, names, metadata); });
}

Image readExr(const std::filesystem::path& path, ImageMetadata* metadata) {
    return withExrErrors(path, [&] { return readExrImpl(path, metadata); });
}

void writeExr(const std::filesystem::path& path, const Image& image, const ImageMetadata& metadata) {
    writeExr(path, image, metadata, {});
}

void writeExr(const std::filesystem::path& path, const Image& image, const ImageMetadata& metadata,
    const std::vector<ExrChannel>& extra) {
    try {
        writeExrImpl(path, image, metadata, extra);
    } catch (const IoError&) {
        throw;
    } catch (const FileWriteError&) {
        throw;
    } catch (const std::exception& e) {
        fail(path, std::string("cannot write OpenEXR file (") + e.what() + ")");
    } catch (...) {
        fail(path, "cannot write OpenEXR file (unknown error)");
    }
}

void writePngRgb8(const std::filesystem::path& path, int width, int height, const std::vector<uint8_t>& rgb) {
    if (width <= 0 || height <= 0)
        fail(path, "cannot write an empty image (" + std::to_string(width) + "x" + std::to_string(height) + ")");
    // stb takes int sizes and an int row stride.
    if (width > std::numeric_limits<int>::max() / 3) fail(path, "image too wide for PNG");
    if (rgb.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3)
        fail(path, "PNG data does not match the image size");

    // Encode to memory first: stbi's own file writer only reports "failed", whereas writing
    // the bytes ourselves gives errno-based messages and the atomic temp file + rename.
    std::vector<uint8_t> encoded;
    auto sink = [](void* ctx, void* data, int size) {
        auto* dst = static_cast<std::vector<uint8_t>*>(ctx);
        const auto* bytes = static_cast<const uint8_t*>(data);
        dst->insert(dst->end(), bytes, bytes + size);
    };
    if (!stbi_write_png_to_func(sink, &encoded, width, height, 3, rgb.data(), width * 3))
        fail(path, "PNG encoding failed");

    AtomicFile file(path);
    file.write(encoded.data(), encoded.size());
    file.commit();
}

} // namespace pt
