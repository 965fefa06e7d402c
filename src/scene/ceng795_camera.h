#pragma once
// <Cameras> of the course format: simple (NearPlane) and lookAt (FovY) cameras, each with the
// settings of its own image (resolution, samples, tone mapping, renderer options).
#include "scene/ceng795_document.h"
#include "scene/scene.h"

#include <optional>

namespace pt::ceng795 {

// `maxDepth` is the scene's MaxRecursionDepth already mapped to the renderer's path depth.
std::vector<Camera> readCameras(Context& ctx, pugi::xml_node scene, std::optional<int> maxDepth);

Camera readCamera(Context& ctx, pugi::xml_node element, std::optional<int> maxDepth);

} // namespace pt::ceng795
