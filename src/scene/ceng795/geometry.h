#pragma once
// Triangle geometry of the course format: the scene-wide <VertexData>/<TexCoordData> pools,
// faces given inline, by plyFile or by binaryFile, and the move to world space.
#include "scene/ceng795/document.h"
#include "scene/scene.h"

#include <glm/glm.hpp>

#include <map>
#include <memory>

namespace pt::ceng795 {

// Far beyond any real vertex count; keeps index arithmetic on hostile values from overflowing.
constexpr long long kMaxIndexMagnitude = 1LL << 40;

// The vertices that inline faces, <Triangle>s and sphere <Center>s refer to by id.
struct VertexPool {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec2> uvs; // <TexCoordData>, parallel to positions (may be empty)
    bool zeroBased = false;     // <ZeroBasedIndexing>: ids start at 0 instead of 1
};

VertexPool readVertexPool(const Context& ctx, pugi::xml_node scene);

// One mesh in its own (object) space. Vertices are shared between its triangles, so smooth
// normals can be averaged over them.
struct ObjectMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec2> uvs; // empty or one per position
    std::vector<glm::uvec3> triangles;
};

class FaceReader {
public:
    FaceReader(Context& ctx, const VertexPool& pool) : ctx_(ctx), pool_(pool) {}

    // The <Faces> of a Mesh or LightMesh. PLY files used by several meshes are read once.
    std::shared_ptr<const ObjectMesh> faces(pugi::xml_node faces);
    // The <Indices> of a Triangle.
    ObjectMesh triangle(pugi::xml_node indices) const;
    // The vertex a file id refers to (a Sphere's <Center>).
    glm::vec3 vertex(pugi::xml_node where, long long id) const;

private:
    ObjectMesh fromIndices(
        pugi::xml_node where, const std::vector<long long>& ids, long long vertexOffset, long long textureOffset) const;
    std::shared_ptr<const ObjectMesh> fromPly(pugi::xml_node faces);
    // Ids and offsets are bounded (kMaxIndexMagnitude) before this sum, so it cannot overflow.
    long long poolIndex(long long id, long long offset) const { return id + offset - (pool_.zeroBased ? 0 : 1); }
    long long boundedOffset(pugi::xml_node faces, const char* name) const;

    Context& ctx_; // notes what a PLY file leaves out
    const VertexPool& pool_;
    std::map<std::filesystem::path, std::shared_ptr<const ObjectMesh>> plyCache_;
};

// Per-vertex normals, each the area-weighted average of the adjacent face normals (the
// course's "smooth" shading); zero for vertices on no triangle of non-zero area.
std::vector<glm::vec3> smoothNormals(const ObjectMesh& mesh);

// The mesh mapped by objectToWorld into a scene Mesh (name and material left to the caller):
// triangles of zero area are dropped (the course asks for degenerate triangles to be skipped),
// and `smooth` adds normals. `owner` is the element named in errors.
Mesh toWorld(
    const Context& ctx, pugi::xml_node owner, const ObjectMesh& mesh, const glm::mat4& objectToWorld, bool smooth);

} // namespace pt::ceng795
