#pragma once
// glTF 2.0 (.gltf and .glb) into the scene model, through tinygltf.
#include "scene/scene.h"

#include <filesystem>
#include <string_view>

namespace pt {

// Throws SceneError naming the file and the problem for anything malformed.
Scene loadGltfFile(const std::filesystem::path& path);

// `text` is a .gltf JSON document; relative URIs resolve against `baseDir`.
Scene loadGltfText(std::string_view text, const std::string& displayName, const std::filesystem::path& baseDir);

// A .gltf (JSON) or .glb (binary, recognised by its magic) file already in memory; relative URIs
// resolve against `baseDir`. Used by the fuzz target (tests/fuzz/).
Scene loadGltfMemory(std::string_view bytes, const std::string& displayName, const std::filesystem::path& baseDir);

} // namespace pt
