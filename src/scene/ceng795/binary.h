#pragma once
// The course's binary geometry files (HW6, sponza): a little-endian int32 count N, then N
// packed elements (vertices: 3 float32, uvs: 2 float32, faces: 3 int32).
#include "scene/ceng795/document.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace pt::ceng795 {

// `where` is the element whose binaryFile attribute names the file.
std::vector<glm::vec3> readBinaryVec3s(const Context& ctx, pugi::xml_node where);
std::vector<glm::vec2> readBinaryVec2s(const Context& ctx, pugi::xml_node where);
// Face indices as stored (the caller applies the index base and vertexOffset).
std::vector<int32_t> readBinaryIndices(const Context& ctx, pugi::xml_node where);

} // namespace pt::ceng795
