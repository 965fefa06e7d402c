#include "scene/gltf/gltf_callbacks.h"

#include <tiny_gltf.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace pt::gltf {
namespace {

bool decodeImage(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
    const unsigned char* bytes, int size, void* user) {
    auto* decoded = static_cast<DecodedImages*>(user);
    const std::string name = "image " + std::to_string(index) + (image->uri.empty() || image->uri.rfind("data:", 0) == 0 ? "" : " '" + image->uri + "'");
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
// runs wordexp() on the URI. Ours take the path as written (relative to the scene's folder),
// read regular files only and bound their size.
constexpr uint64_t kMaxExternalFileBytes = uint64_t(1) << 32;

bool fileExists(const std::string& path, void*) {
    std::error_code ec;
    return std::filesystem::exists(path, ec);
}

std::string pathAsWritten(const std::string& path, void*) { return path; }

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
    auto problem = [&](const std::string& what) {
        if (err) *err += "File " + what + " : " + path + "\n";
        return false;
    };
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (status.type() == std::filesystem::file_type::not_found) return problem("not found");
    if (!std::filesystem::is_regular_file(status)) return problem("is not a regular file");
    const uint64_t size = std::filesystem::file_size(path, ec);
    if (ec) return problem("size unreadable");
    if (size == 0) return problem("is empty");
    if (size > kMaxExternalFileBytes) return problem("is larger than 4 GiB");
    std::ifstream in(path, std::ios::binary);
    if (!in) return problem("cannot be opened");
    out->resize(size);
    if (!in.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(size))) return problem("read failed");
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
