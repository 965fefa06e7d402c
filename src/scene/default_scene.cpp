#include "scene/default_scene.h"

#include "scene/gltf/gltf_loader.h"

namespace pt {

extern const char* const kCornellBoxGltf; // generated from scenes/cornell-box.gltf (CMakeLists.txt)

Scene loadDefaultScene() { return loadGltfText(kCornellBoxGltf, "built-in Cornell box", "."); }

} // namespace pt
