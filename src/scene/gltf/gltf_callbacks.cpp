#include "scene/gltf/gltf_callbacks.h"

#include "image/file_read.h"

#include <tiny_gltf.h>

#include <filesystem>
#include <new>
#include <stdexcept>
#include <string>

namespace pt::gltf {
namespace {

bool decodeImage(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
    const unsigned char* bytes, int size, void* user) {
    auto* decoded = static_cast<DecodedImages*>(user);
    const std::string name = "image " + std::to_string(index) +
                             (image->uri.empty() || image->uri.rfind("data:", 0) == 0 ? "" : " '" + image->uri + "'");
    try {
        if (index < 0) throw std::runtime_error(name + ": bad index");
        if (decoded->images.size() <= static_cast<size_t>(index)) decoded->images.resize(index + 1);
        decoded->images[index] = decodeTextureImage(bytes, size < 0 ? 0 : static_cast<size_t>(size), name);
    } catch (const std::exception& e) {
        if (err) *err += e.what();
        return false;
    }
    image->width = decoded->images[index]->width;
    image->height = decoded->images[index]->height;
    return true;
}

// ---- file access for external buffers and images ----
// tinygltf's own callbacks trust the file: a URI naming a directory made its ReadWholeFile ask for
// 2^63 bytes (found by fuzzing), a device such as /dev/zero has no end, and its path expansion
// runs wordexp() on the URI. Ours take the path as written (relative to the scene's folder) and
// read it by the input-file policy (image/file_read.h): regular files only, not empty, at most
// 4 GiB. tinygltf puts our words into its own message ("File read error : <uri> : File <problem>
// : <path>"), so these keep the words tinygltf's messages use.
constexpr uint64_t kMaxExternalFileBytes = uint64_t(1) << 32;

bool fileExists(const std::string& path, void*) {
    std::error_code ec;
    return std::filesystem::exists(path, ec);
}

std::string pathAsWritten(const std::string& path, void*) { return path; }

const char* problemWords(FileProblem problem) {
    switch (problem) {
    case FileProblem::NotFound: return "not found";
    case FileProblem::SizeUnknown: return "size unreadable";
    case FileProblem::Empty: return "is empty";
    case FileProblem::TooLarge: return "is larger than 4 GiB";
    case FileProblem::CannotOpen: return "cannot be opened";
    case FileProblem::ReadFailed: return "read failed";
    default: return "is not a regular file"; // CannotAccess, Directory, NotRegularFile
    }
}

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
    FileRead file = tryReadInputFile(path, {.maxBytes = kMaxExternalFileBytes, .refuseEmpty = true});
    if (file.problem == FileProblem::OutOfMemory) throw std::bad_alloc(); // as a failed resize of `out` would
    if (!file) {
        if (err) *err += "File " + std::string(problemWords(file.problem)) + " : " + path + "\n";
        return false;
    }
    *out = std::move(file.bytes);
    return true;
}

bool refuseWrite(std::string* err, const std::string& path, const std::vector<unsigned char>&, void*) {
    if (err) *err += "pt never writes glTF files: " + path + "\n";
    return false;
}

} // namespace

void configureLoader(tinygltf::TinyGLTF& loader, DecodedImages& images) {
    loader.SetImageLoader(&decodeImage, &images);
    loader.SetFsCallbacks(tinygltf::FsCallbacks{&fileExists, &pathAsWritten, &readWholeFile, &refuseWrite, nullptr});
}

} // namespace pt::gltf
