#pragma once
// <Cameras> of the course format: simple (NearPlane) and lookAt (FovY) cameras, each with the
// settings of its own image (resolution, samples, tone mapping, renderer options).
#include "scene/ceng795/document.h"
#include "scene/scene.h"

#include <optional>

namespace pt::ceng795 {

// `maxDepth` is the scene's MaxRecursionDepth already mapped to the renderer's path depth.
std::vector<Camera> readCameras(Context& ctx, pugi::xml_node scene, std::optional<int> maxDepth);

// One <Camera>, the index-th in the file (named "camera <id>", or by position without an id).
Camera readCamera(Context& ctx, pugi::xml_node element, size_t index, std::optional<int> maxDepth);

} // namespace pt::ceng795
