#pragma once
// A small, strict reader for triangle meshes stored as PLY (ascii 1.0, binary_little_endian 1.0,
// binary_big_endian 1.0). Only the "vertex" and "face" elements are interpreted; every other
// element and property is skipped. Anything malformed is rejected with pt::SceneError rather
// than guessed at, because a silently wrong mesh is much harder to debug than a one-line error.
#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace pt {

struct PlyMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;    // empty or one per vertex
    std::vector<glm::vec2> uvs;        // empty or one per vertex
    std::vector<glm::uvec3> triangles; // 0-based; polygons with more than 3 vertices are split as fans
    uint64_t shortFaces = 0;           // faces with fewer than 3 vertices, which yield no triangle
};

// Reads a PLY mesh.
//  - Vertex properties: x y z (required); nx ny nz (all or none); texture coordinates as u/v,
//    s/t, texture_u/texture_v or texture_s/texture_t (both of a pair or neither).
//  - Faces: list property vertex_indices or vertex_index; faces with fewer than 3 vertices are
//    skipped and counted (shortFaces: the caller says so). A file without a face element yields
//    no triangles (a point cloud).
// Throws pt::SceneError(path.string(), problem) (src/scene/scene_error.h) on anything malformed:
// bad magic or header, counts the file cannot hold, truncation, non-numeric ascii values,
// out-of-range indices, non-finite vertex data.
PlyMesh readPly(const std::filesystem::path& path);

// The same for a PLY file already in memory; errors are "<displayName>: <problem>". Used by the
// fuzz target (tests/fuzz/), which must not touch the file system.
PlyMesh parsePly(std::string_view bytes, const std::string& displayName);

} // namespace pt
