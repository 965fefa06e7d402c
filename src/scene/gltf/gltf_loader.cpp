// The glTF loader's entry points (gltf_loader.h): the file checks before tinygltf parses it,
// tinygltf configured with our callbacks (gltf_callbacks.h), and its result handed to the
// importer (gltf_importer.h).
#include "scene/gltf/gltf_loader.h"

#include "image/file_read.h"
#include "scene/gltf/gltf_callbacks.h"
#include "scene/gltf/gltf_importer.h"
#include "scene/scene_error.h"

#include <tiny_gltf.h>

#include <cstring>
#include <fstream>
#include <limits>

namespace pt {
namespace {

using gltf::configureLoader;
using gltf::DecodedImages;
using gltf::GltfImporter;

// tinygltf's first error line, made safe to print: it can echo the file's bytes (a URI, a JSON
// excerpt), so control characters become '?' (a hostile file must not drive the terminal) and
// the length is bounded.
std::string firstLine(const std::string& s) {
    constexpr size_t kMaxLength = 300;
    std::string line = s.substr(0, s.find('\n'));
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    for (char& c : line)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    if (line.size() > kMaxLength) line = line.substr(0, kMaxLength) + "...";
    return line;
}

Scene importModel(bool ok, const tinygltf::Model& model, const std::string& err, const std::string& displayName,
    DecodedImages& images, const std::string& variant = "") {
    if (!ok)
        throw SceneError(displayName, "invalid glTF: " + (err.empty() ? std::string("unknown error") : firstLine(err)));
    return GltfImporter(model, displayName, images, variant).run();
}

} // namespace

Scene loadGltfFile(const std::filesystem::path& path, const std::string& variant) {
    const std::string name = path.string();
    // The input-file policy's first checks (image/file_read.h); tinygltf then reads the whole file
    // through our readWholeFile callback, which applies the rest. Here only the magic is peeked at.
    const InputFileCheck file = checkInputFile(path, {.streamNonRegular = true});
    if (file.problem == FileProblem::NotFound || file.problem == FileProblem::CannotAccess)
        throw SceneError(name, "file not found");
    if (file.problem == FileProblem::Directory) throw SceneError(name, "is a directory, not a glTF file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw SceneError(name, "cannot open for reading");
    char magic[4] = {};
    in.read(magic, 4);
    const bool binary = in.gcount() == 4 && std::memcmp(magic, "glTF", 4) == 0;
    if (!binary && path.extension() == ".glb") throw SceneError(name, "not a binary glTF file (bad magic)");
    if (in.gcount() == 0) throw SceneError(name, "empty file");

    tinygltf::TinyGLTF loader;
    DecodedImages images;
    configureLoader(loader, images);
    tinygltf::Model model;
    std::string err, warn;
    bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, name)
                     : loader.LoadASCIIFromFile(&model, &err, &warn, name);
    return importModel(ok, model, err, name, images, variant);
}

Scene loadGltfText(std::string_view text, const std::string& displayName, const std::filesystem::path& baseDir,
    const std::string& variant) {
    tinygltf::TinyGLTF loader;
    DecodedImages images;
    configureLoader(loader, images);
    tinygltf::Model model;
    std::string err, warn;
    bool ok = loader.LoadASCIIFromString(
        &model, &err, &warn, text.data(), static_cast<unsigned int>(text.size()), baseDir.string());
    return importModel(ok, model, err, displayName, images, variant);
}

Scene loadGltfMemory(std::string_view bytes, const std::string& displayName, const std::filesystem::path& baseDir) {
    if (bytes.empty()) throw SceneError(displayName, "empty file");
    // tinygltf takes the length as an unsigned int.
    if (bytes.size() > std::numeric_limits<unsigned int>::max())
        throw SceneError(displayName, "file larger than 4 GiB");
    if (bytes.size() < 4 || std::memcmp(bytes.data(), "glTF", 4) != 0) return loadGltfText(bytes, displayName, baseDir);
    tinygltf::TinyGLTF loader;
    DecodedImages images;
    configureLoader(loader, images);
    tinygltf::Model model;
    std::string err, warn;
    const bool ok =
        loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
            static_cast<unsigned int>(bytes.size()), baseDir.string());
    return importModel(ok, model, err, displayName, images);
}

} // namespace pt
