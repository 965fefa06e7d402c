#pragma once
// The METU CENG795 "Advanced Ray Tracing" course's XML scene format (HW1-HW6), specified in
// docs/ceng795-format.md, into the scene model. Features the model lacks are mapped to
// the nearest supported thing and listed in Scene::unsupported.
#include "scene/scene.h"

#include <filesystem>
#include <string>
#include <string_view>

namespace pt {

// Throws SceneError naming the file and the element for anything malformed, e.g.
// "scene.xml: Mesh id=3: Faces: face index 12 out of range (8 vertices, 1-based)".
Scene loadCeng795File(const std::filesystem::path& xml);

// `xml` is a document's text; relative paths (plyFile, binaryFile) resolve against `baseDir`.
Scene loadCeng795Text(std::string_view xml, const std::string& displayName, const std::filesystem::path& baseDir);

} // namespace pt
