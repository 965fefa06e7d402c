#pragma once
#include "scene/scene.h"

#include <filesystem>

namespace pt {

// Loads a scene file by its extension (.gltf, .glb, the CENG795 course's .xml); an empty path
// gives the built-in Cornell box. `variant`: a glTF KHR_materials_variants variant by name
// (empty: the default materials); other formats have none and refuse one.
Scene loadScene(const std::filesystem::path& path, const std::string& variant = "");

} // namespace pt
