#pragma once
#include "scene/scene.h"

namespace pt {

// The built-in Cornell box (scenes/cornell-box.gltf, embedded at build time): the scene
// rendered when none is given, identical to the cbox-diffuse reference scene.
Scene loadDefaultScene();

} // namespace pt
