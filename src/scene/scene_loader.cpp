#include "scene/scene_loader.h"

#include "scene/ceng795/loader.h"
#include "scene/default_scene.h"
#include "scene/gltf/gltf_loader.h"
#include "scene/scene_error.h"

#include <algorithm>

namespace pt {

Scene loadScene(const std::filesystem::path& path, const std::string& variant) {
    const bool gltf = [&] {
        std::string ext = path.extension().string();
        std::transform(
            ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        return ext == ".gltf" || ext == ".glb";
    }();
    if (!variant.empty() && !gltf)
        throw SceneError(path.empty() ? std::string("built-in Cornell box") : path.string(),
            "has no material variants (--variant needs a glTF scene with KHR_materials_variants)");
    if (path.empty()) return loadDefaultScene();
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw SceneError(path.string(), "is a directory, not a scene file");
    std::string ext = path.extension().string();
    std::transform(
        ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (gltf) return loadGltfFile(path, variant);
    if (ext == ".xml") return loadCeng795File(path);
    throw SceneError(path.string(), "unknown scene format '" + ext + "' (expected .gltf, .glb or the course's .xml)");
}

} // namespace pt
