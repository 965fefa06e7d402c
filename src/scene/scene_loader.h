#pragma once
#include "scene/scene.h"

#include <filesystem>

namespace pt {

// Loads a scene file by its extension (.gltf, .glb, the CENG795 course's .xml); an empty path
// gives the built-in Cornell box.
Scene loadScene(const std::filesystem::path& path);

} // namespace pt
