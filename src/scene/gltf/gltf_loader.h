#pragma once
// glTF 2.0 (.gltf and .glb) into the scene model, through tinygltf.
#include "scene/scene.h"

#include <filesystem>
#include <string_view>

namespace pt {

// Throws SceneError naming the file and the problem for anything malformed. `variant`: a
// KHR_materials_variants variant by name, whose materials replace the primitives' defaults
// (empty: the default materials; Scene::materialVariants lists the names either way).
Scene loadGltfFile(const std::filesystem::path& path, const std::string& variant = "");

// `text` is a .gltf JSON document; relative URIs resolve against `baseDir`.
Scene loadGltfText(std::string_view text, const std::string& displayName, const std::filesystem::path& baseDir,
    const std::string& variant = "");

// A .gltf (JSON) or .glb (binary, recognised by its magic) file already in memory; relative URIs
// resolve against `baseDir`. Used by the fuzz target (tests/fuzz/).
Scene loadGltfMemory(std::string_view bytes, const std::string& displayName, const std::filesystem::path& baseDir);

} // namespace pt
