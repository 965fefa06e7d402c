#include "scene/ceng795/geometry.h"

#include "image/file_read.h"
#include "scene/ceng795/binary.h"
#include "scene/ceng795/ply_reader.h"
#include "scene/scene_error.h"

#include <cmath>
#include <cstdlib>
#include <unordered_map>

namespace pt::ceng795 {
namespace {

std::vector<glm::vec3> inlineVec3s(const Context& ctx, pugi::xml_node node) {
    const std::vector<double> v = numbers(ctx, node);
    if (v.size() % 3 != 0) ctx.fail(node, std::to_string(v.size()) + " numbers is not a whole number of xyz triples");
    std::vector<glm::vec3> out(v.size() / 3);
    for (size_t i = 0; i < out.size(); ++i) out[i] = glm::vec3(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
    for (const auto& p : out)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) ctx.fail(node, "number out of range");
    return out;
}

std::vector<glm::vec2> inlineVec2s(const Context& ctx, pugi::xml_node node) {
    const std::vector<double> v = numbers(ctx, node);
    if (v.size() % 2 != 0) ctx.fail(node, std::to_string(v.size()) + " numbers is not a whole number of uv pairs");
    std::vector<glm::vec2> out(v.size() / 2);
    for (size_t i = 0; i < out.size(); ++i) out[i] = glm::vec2(v[2 * i], v[2 * i + 1]);
    return out;
}

bool hasAttribute(pugi::xml_node node, const char* name) { return static_cast<bool>(node.attribute(name)); }

std::string outOfRange(long long id, long long offset, size_t count, bool zeroBased) {
    std::string s = "face index " + std::to_string(id);
    if (offset != 0) s += " (vertexOffset " + std::to_string(offset) + ")";
    return s + " out of range (" + std::to_string(count) + " vertices, " + (zeroBased ? "0" : "1") + "-based)";
}

} // namespace

VertexPool readVertexPool(const Context& ctx, pugi::xml_node scene) {
    VertexPool pool;
    for (pugi::xml_node n : scene.children("VertexData")) {
        std::vector<glm::vec3> v = hasAttribute(n, "binaryFile") ? readBinaryVec3s(ctx, n) : inlineVec3s(ctx, n);
        pool.positions.insert(pool.positions.end(), v.begin(), v.end());
    }
    for (pugi::xml_node n : scene.children("TexCoordData")) {
        std::vector<glm::vec2> v = hasAttribute(n, "binaryFile") ? readBinaryVec2s(ctx, n) : inlineVec2s(ctx, n);
        pool.uvs.insert(pool.uvs.end(), v.begin(), v.end());
    }
    if (pugi::xml_node z = scene.child("ZeroBasedIndexing")) pool.zeroBased = booleanValue(ctx, z, textOf(z), "value");
    return pool;
}

long long FaceReader::boundedOffset(pugi::xml_node faces, const char* name) const {
    const long long offset = integerAttribute(ctx_, faces, name, 0);
    if (offset < -kMaxIndexMagnitude || offset > kMaxIndexMagnitude)
        ctx_.fail(faces, std::string(name) + " is out of range");
    return offset;
}

glm::vec3 FaceReader::vertex(pugi::xml_node where, long long id) const {
    const long long i = std::abs(id) > kMaxIndexMagnitude ? -1 : poolIndex(id, 0);
    if (i < 0 || i >= static_cast<long long>(pool_.positions.size()))
        ctx_.fail(where, "vertex " + std::to_string(id) + " out of range (" + std::to_string(pool_.positions.size()) +
                             " vertices, " + (pool_.zeroBased ? "0" : "1") + "-based)");
    return pool_.positions[static_cast<size_t>(i)];
}

ObjectMesh FaceReader::fromIndices(
    pugi::xml_node where, const std::vector<long long>& ids, long long vertexOffset, long long textureOffset) const {
    if (ids.empty()) ctx_.fail(where, "no faces");
    if (ids.size() % 3 != 0)
        ctx_.fail(where, std::to_string(ids.size()) + " indices is not a whole number of triangles");
    ObjectMesh mesh;
    // Pool vertex -> mesh vertex: a mesh keeps only the vertices it uses, shared between its
    // triangles (so smooth normals average across them).
    std::unordered_map<long long, uint32_t> local;
    bool uvsValid = !pool_.uvs.empty();
    std::vector<long long> uvIndex;
    mesh.triangles.resize(ids.size() / 3);
    for (size_t k = 0; k < ids.size(); ++k) {
        const long long g = std::abs(ids[k]) > kMaxIndexMagnitude ? -1 : poolIndex(ids[k], vertexOffset);
        if (g < 0 || g >= static_cast<long long>(pool_.positions.size()))
            ctx_.fail(where, outOfRange(ids[k], vertexOffset, pool_.positions.size(), pool_.zeroBased));
        auto [it, inserted] = local.emplace(g, static_cast<uint32_t>(mesh.positions.size()));
        if (inserted) {
            mesh.positions.push_back(pool_.positions[static_cast<size_t>(g)]);
            // Texture coordinates are indexed like vertices, shifted by textureOffset instead.
            const long long t = poolIndex(ids[k], textureOffset);
            uvsValid = uvsValid && t >= 0 && t < static_cast<long long>(pool_.uvs.size());
            uvIndex.push_back(t);
        }
        mesh.triangles[k / 3][static_cast<int>(k % 3)] = it->second;
    }
    // Textures are not modelled yet, so a file whose uvs do not cover its faces still loads.
    if (uvsValid)
        for (long long t : uvIndex) mesh.uvs.push_back(pool_.uvs[static_cast<size_t>(t)]);
    return mesh;
}

std::shared_ptr<const ObjectMesh> FaceReader::fromPly(pugi::xml_node faces) {
    const std::string relative = faces.attribute("plyFile").value();
    const std::filesystem::path path = ctx_.resolve(relative).lexically_normal();
    if (auto it = plyCache_.find(path); it != plyCache_.end()) return it->second;
    // The input-file policy's first checks (image/file_read.h): anything that is not a regular
    // file is "not found" here; readPly applies the rest in its own words.
    if (checkInputFile(path).notARegularFile()) ctx_.fail(faces, "plyFile " + quote(relative) + " not found");
    PlyMesh ply;
    try {
        ply = readPly(path);
    } catch (const SceneError& e) {
        ctx_.fail(faces, e.what()); // keep the XML file and element in front of the PLY's own message
    }
    auto mesh = std::make_shared<ObjectMesh>();
    mesh->positions = std::move(ply.positions);
    mesh->triangles = std::move(ply.triangles);
    // The PLY's own normals are not used: the course defines smooth shading as the
    // area-weighted average of face normals, and flat shading as none.
    if (ply.uvs.size() == mesh->positions.size()) mesh->uvs = std::move(ply.uvs);
    for (const auto& t : mesh->triangles)
        if (t.x >= mesh->positions.size() || t.y >= mesh->positions.size() || t.z >= mesh->positions.size())
            ctx_.fail(faces, "plyFile " + quote(relative) + ": face index out of range");
    if (mesh->triangles.empty()) ctx_.fail(faces, "plyFile " + quote(relative) + " has no faces");
    if (ply.shortFaces > 0)
        ctx_.note(label(faces) + ": plyFile " + quote(relative) + ": " + std::to_string(ply.shortFaces) +
                  (ply.shortFaces == 1 ? " face" : " faces") + " with fewer than 3 vertices (dropped)");
    plyCache_.emplace(path, mesh);
    return mesh;
}

std::shared_ptr<const ObjectMesh> FaceReader::faces(pugi::xml_node faces) {
    if (hasAttribute(faces, "plyFile")) return fromPly(faces);
    const long long vertexOffset = boundedOffset(faces, "vertexOffset");
    const long long textureOffset = boundedOffset(faces, "textureOffset");
    if (hasAttribute(faces, "binaryFile")) {
        const std::vector<int32_t> raw = readBinaryIndices(ctx_, faces);
        return std::make_shared<ObjectMesh>(
            fromIndices(faces, std::vector<long long>(raw.begin(), raw.end()), vertexOffset, textureOffset));
    }
    return std::make_shared<ObjectMesh>(fromIndices(faces, integers(ctx_, faces), vertexOffset, textureOffset));
}

ObjectMesh FaceReader::triangle(pugi::xml_node indices) const {
    const std::vector<long long> ids = integers(ctx_, indices);
    if (ids.size() != 3) ctx_.fail(indices, "expected 3 vertex ids, found " + std::to_string(ids.size()));
    return fromIndices(indices, ids, 0, 0);
}

std::vector<glm::vec3> smoothNormals(const ObjectMesh& mesh) {
    std::vector<glm::vec3> sum(mesh.positions.size(), glm::vec3(0.0f));
    for (const auto& t : mesh.triangles) {
        // The cross product's length is twice the area: summing it weights by area.
        const glm::vec3 n =
            glm::cross(mesh.positions[t.y] - mesh.positions[t.x], mesh.positions[t.z] - mesh.positions[t.x]);
        sum[t.x] += n;
        sum[t.y] += n;
        sum[t.z] += n;
    }
    for (auto& n : sum) {
        const float len = glm::length(n);
        n = (len > 0.0f && std::isfinite(len)) ? n / len : glm::vec3(0.0f);
    }
    return sum;
}

namespace {

bool nonDegenerate(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    const glm::vec3 n = glm::cross(b - a, c - a);
    const float area2 = glm::dot(n, n);
    return area2 > 0.0f && std::isfinite(area2);
}

std::vector<glm::vec3> worldNormals(const std::vector<glm::vec3>& objectNormals, const glm::mat4& objectToWorld) {
    // Normals map with the inverse transpose (docs/ceng795-format.md §10), which keeps them on the side the
    // object-space winding made the front, also under mirroring transforms.
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(objectToWorld)));
    std::vector<glm::vec3> out(objectNormals.size(), glm::vec3(0.0f));
    for (size_t i = 0; i < out.size(); ++i) {
        const glm::vec3 n = normalMatrix * objectNormals[i];
        const float len = glm::length(n);
        if (len > 0.0f && std::isfinite(len)) out[i] = n / len;
    }
    return out;
}

} // namespace

Mesh toWorld(
    const Context& ctx, pugi::xml_node owner, const ObjectMesh& mesh, const glm::mat4& objectToWorld, bool smooth) {
    Mesh out;
    out.positions.reserve(mesh.positions.size());
    for (const auto& p : mesh.positions) {
        const glm::vec3 w = glm::vec3(objectToWorld * glm::vec4(p, 1.0f));
        if (!std::isfinite(w.x) || !std::isfinite(w.y) || !std::isfinite(w.z))
            ctx.fail(owner, "transformed vertex is not finite");
        out.positions.push_back(w);
    }
    // The renderer takes the front side from the world-space winding. A mirroring transform
    // (negative determinant) reverses that winding while the inverse-transpose normals keep
    // the original front, so swap two corners to keep both on the same (original) side.
    const bool mirrored = glm::determinant(glm::mat3(objectToWorld)) < 0.0f;
    out.triangles.reserve(mesh.triangles.size());
    for (glm::uvec3 t : mesh.triangles) {
        if (mirrored) std::swap(t.y, t.z);
        if (nonDegenerate(out.positions[t.x], out.positions[t.y], out.positions[t.z])) out.triangles.push_back(t);
    }
    out.uvs = mesh.uvs;
    if (smooth) out.normals = worldNormals(smoothNormals(mesh), objectToWorld);
    return out;
}

} // namespace pt::ceng795
