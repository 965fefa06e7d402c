// glTF meshes into the scene model (gltf_importer.h): accessors read with every bound checked
// against their buffer view and buffer, and each triangle primitive (list, strip or fan) with
// its positions, normals, tangents and TEXCOORD_0, in world space for a mesh one node places and
// in object space, kept once, for a mesh several nodes place.
#include "scene/gltf/gltf_importer.h"

#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>
#include <cstring>

namespace pt::gltf {

// ---- accessors ----
// Checks that `count` elements of `elementBytes` each, `stride` apart, fit in the buffer
// view and the buffer, and returns a pointer to the first one.
const unsigned char* GltfImporter::accessorData(
    int accessorIndex, const std::string& what, size_t& count, size_t& stride, int& componentType, int& type) {
    if (accessorIndex < 0 || accessorIndex >= static_cast<int>(model_.accessors.size()))
        fail(what + ": accessor " + std::to_string(accessorIndex) + " out of range");
    const tinygltf::Accessor& acc = model_.accessors[accessorIndex];
    const std::string label = what + " (accessor " + std::to_string(accessorIndex) + ")";
    if (acc.sparse.isSparse) fail(label + ": sparse accessors are not supported");
    if (acc.bufferView < 0 || acc.bufferView >= static_cast<int>(model_.bufferViews.size()))
        fail(label + ": missing or out-of-range bufferView");
    const tinygltf::BufferView& view = model_.bufferViews[acc.bufferView];
    if (view.buffer < 0 || view.buffer >= static_cast<int>(model_.buffers.size()))
        fail(label + ": buffer index out of range");
    const tinygltf::Buffer& buffer = model_.buffers[view.buffer];
    int componentBytes = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(acc.componentType));
    int components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(acc.type));
    if (componentBytes <= 0 || components <= 0) fail(label + ": invalid componentType or type");
    const uint64_t elementBytes = static_cast<uint64_t>(componentBytes) * components;
    stride = view.byteStride ? view.byteStride : elementBytes;
    count = acc.count;
    if (count == 0) fail(label + ": count is 0");
    const uint64_t viewEnd = static_cast<uint64_t>(view.byteOffset) + view.byteLength;
    if (view.byteOffset > buffer.data.size() || viewEnd > buffer.data.size())
        fail(label + ": bufferView exceeds its buffer (" + std::to_string(buffer.data.size()) + " bytes)");
    if (count > view.byteLength / std::max<uint64_t>(1, stride) + 1)
        fail(label + ": count " + std::to_string(count) + " exceeds the bufferView");
    const uint64_t last = static_cast<uint64_t>(acc.byteOffset) + (count - 1) * stride + elementBytes;
    if (last > view.byteLength) fail(label + ": count " + std::to_string(count) + " exceeds the bufferView");
    componentType = acc.componentType;
    type = acc.type;
    return buffer.data.data() + view.byteOffset + acc.byteOffset;
}

template <int N>
std::vector<glm::vec<N, float>> GltfImporter::readVectors(
    int accessorIndex, const std::string& what, bool allowNormalizedInts) {
    size_t count, stride;
    int componentType, type;
    const unsigned char* data = accessorData(accessorIndex, what, count, stride, componentType, type);
    const int expectedType = N == 2 ? TINYGLTF_TYPE_VEC2 : (N == 3 ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4);
    if (type != expectedType)
        fail(what + " (accessor " + std::to_string(accessorIndex) + "): expected VEC" + std::to_string(N));
    std::vector<glm::vec<N, float>> out(count);
    for (size_t i = 0; i < count; ++i) {
        const unsigned char* e = data + i * stride;
        for (int c = 0; c < N; ++c) {
            float v;
            if (componentType == TINYGLTF_COMPONENT_TYPE_FLOAT)
                std::memcpy(&v, e + 4 * c, 4);
            else if (allowNormalizedInts && componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE)
                v = e[c] / 255.0f;
            else if (allowNormalizedInts && componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
                uint16_t s;
                std::memcpy(&s, e + 2 * c, 2);
                v = s / 65535.0f;
            } else
                fail(what + " (accessor " + std::to_string(accessorIndex) + "): unsupported component type " +
                     std::to_string(componentType));
            out[i][c] = v;
        }
    }
    return out;
}

std::vector<uint32_t> GltfImporter::readIndices(int accessorIndex, const std::string& what) {
    size_t count, stride;
    int componentType, type;
    const unsigned char* data = accessorData(accessorIndex, what, count, stride, componentType, type);
    if (type != TINYGLTF_TYPE_SCALAR) fail(what + ": indices must be SCALAR");
    std::vector<uint32_t> out(count);
    for (size_t i = 0; i < count; ++i) {
        const unsigned char* e = data + i * stride;
        switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: out[i] = e[0]; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v;
            std::memcpy(&v, e, 2);
            out[i] = v;
            break;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: std::memcpy(&out[i], e, 4); break;
        default: fail(what + ": index component type must be unsigned byte, short or int");
        }
    }
    return out;
}

// ---- meshes ----
std::vector<Mesh> GltfImporter::readMesh(const tinygltf::Mesh& mesh, int meshIndex, const glm::mat4& world) {
    std::vector<Mesh> parts;
    const glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(world));
    // A mirroring transform turns counter-clockwise into clockwise: swap to keep front faces.
    const bool mirrored = glm::determinant(glm::mat3(world)) < 0.0f;
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
        const tinygltf::Primitive& prim = mesh.primitives[p];
        const std::string label = "mesh " + std::to_string(meshIndex) +
                                  (mesh.name.empty() ? "" : " '" + mesh.name + "'") + " primitive " + std::to_string(p);
        int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
        if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            mode != TINYGLTF_MODE_TRIANGLE_FAN) {
            unsupported("point and line primitives (skipped)");
            continue;
        }
        auto pos = prim.attributes.find("POSITION");
        if (pos == prim.attributes.end()) fail(label + ": no POSITION attribute");
        Mesh out;
        out.name = mesh.name.empty() ? "mesh " + std::to_string(meshIndex) : mesh.name;
        out.positions = readVectors<3>(pos->second, label + " POSITION", false);
        for (size_t i = 0; i < out.positions.size(); ++i)
            if (!finite(out.positions[i]))
                fail(label + " POSITION: vertex " + std::to_string(i) + " is non-finite (NaN or Inf)");
        for (auto& v : out.positions) v = glm::vec3(world * glm::vec4(v, 1.0f));
        for (size_t i = 0; i < out.positions.size(); ++i)
            if (!finite(out.positions[i]))
                fail(label + ": vertex " + std::to_string(i) + " overflows after transformation");
        if (auto n = prim.attributes.find("NORMAL"); n != prim.attributes.end()) {
            out.normals = readVectors<3>(n->second, label + " NORMAL", false);
            if (out.normals.size() != out.positions.size()) fail(label + ": NORMAL count differs from POSITION count");
            // Invalid normals become zero: the triangle then shades with its geometric normal.
            bool invalid = false;
            for (auto& v : out.normals) {
                glm::vec3 w = normalMatrix * v;
                float len = glm::length(w);
                invalid = invalid || !(std::isfinite(len) && len > 0.0f);
                v = (std::isfinite(len) && len > 0.0f) ? w / len : glm::vec3(0.0f);
            }
            if (invalid) unsupported("zero or non-finite NORMAL vectors (the geometric normal used there)");
        }
        if (auto t = prim.attributes.find("TANGENT"); t != prim.attributes.end() && !out.normals.empty()) {
            // Tangents map with the model matrix (they lie in the surface); a mirroring
            // transform flips the bitangent's handedness.
            out.tangents = readVectors<4>(t->second, label + " TANGENT", false);
            if (out.tangents.size() != out.positions.size())
                fail(label + ": TANGENT count differs from POSITION count");
            const float handedness = mirrored ? -1.0f : 1.0f;
            bool invalid = false;
            for (auto& v : out.tangents) {
                const glm::vec3 w = glm::mat3(world) * glm::vec3(v);
                const float len = glm::length(w);
                const bool ok = std::isfinite(len) && len > 0.0f && std::isfinite(v.w);
                invalid = invalid || !ok;
                v = ok ? glm::vec4(w / len, (v.w < 0.0f ? -1.0f : 1.0f) * handedness) : glm::vec4(0.0f);
            }
            if (invalid) unsupported("zero or non-finite TANGENT vectors (the triangle's own frame used there)");
        }
        if (auto t = prim.attributes.find("TEXCOORD_0"); t != prim.attributes.end()) {
            out.uvs = readVectors<2>(t->second, label + " TEXCOORD_0", true);
            if (out.uvs.size() != out.positions.size()) fail(label + ": TEXCOORD_0 count differs from POSITION count");
        }
        std::vector<uint32_t> indices;
        if (prim.indices >= 0) {
            indices = readIndices(prim.indices, label + " indices");
            for (size_t i = 0; i < indices.size(); ++i)
                if (indices[i] >= out.positions.size())
                    fail(label + ": index " + std::to_string(indices[i]) + " at position " + std::to_string(i) +
                         " is out of range (" + std::to_string(out.positions.size()) + " vertices)");
        } else {
            indices.resize(out.positions.size());
            for (size_t i = 0; i < indices.size(); ++i) indices[i] = static_cast<uint32_t>(i);
        }
        auto addTriangle = [&](uint32_t a, uint32_t b, uint32_t c) {
            out.triangles.push_back(mirrored ? glm::uvec3(a, c, b) : glm::uvec3(a, b, c));
        };
        if (mode == TINYGLTF_MODE_TRIANGLES) {
            if (indices.size() % 3 != 0)
                unsupported("triangle lists whose length is not a multiple of 3 (tail dropped)");
            for (size_t i = 0; i + 2 < indices.size(); i += 3) addTriangle(indices[i], indices[i + 1], indices[i + 2]);
        } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            for (size_t i = 0; i + 2 < indices.size(); ++i)
                if (i % 2 == 0)
                    addTriangle(indices[i], indices[i + 1], indices[i + 2]);
                else
                    addTriangle(indices[i + 1], indices[i], indices[i + 2]);
        } else {
            for (size_t i = 1; i + 1 < indices.size(); ++i) addTriangle(indices[0], indices[i], indices[i + 1]);
        }
        const int material = primitiveMaterial(prim, label);
        if (material >= static_cast<int>(model_.materials.size())) fail(label + ": material index out of range");
        out.material = material >= 0 ? static_cast<uint32_t>(material) : defaultMaterial();
        instancedVertices_ += out.positions.size();
        instancedTriangles_ += out.triangles.size();
        if (instancedTriangles_ > kMaxInstanced || instancedVertices_ > kMaxInstanced)
            fail("more than " + std::to_string(kMaxInstanced) + " vertices or triangles in its meshes");
        if (!out.triangles.empty()) parts.push_back(std::move(out));
    }
    return parts;
}

void GltfImporter::placeMesh(int meshIndex, const glm::mat4& world, int nodeIndex) {
    const tinygltf::Mesh& mesh = model_.meshes[meshIndex];
    if (placements_.at(meshIndex) < 2) {
        for (Mesh& part : readMesh(mesh, meshIndex, world)) scene_.meshes.push_back(std::move(part));
        return;
    }
    auto shared = sharedMeshIndices_.find(meshIndex);
    if (shared == sharedMeshIndices_.end()) {
        SharedMesh s;
        s.name = mesh.name.empty() ? "mesh " + std::to_string(meshIndex) : mesh.name;
        s.parts = readMesh(mesh, meshIndex, glm::mat4(1.0f));
        shared = sharedMeshIndices_.emplace(meshIndex, static_cast<uint32_t>(scene_.sharedMeshes.size())).first;
        scene_.sharedMeshes.push_back(std::move(s));
    }
    MeshInstance instance;
    instance.name = "node " + std::to_string(nodeIndex) +
                    (model_.nodes[nodeIndex].name.empty() ? "" : " '" + model_.nodes[nodeIndex].name + "'");
    instance.mesh = shared->second;
    instance.objectToWorld = world;
    scene_.instances.push_back(std::move(instance));
}

// The triangles a mesh's primitives claim (index or POSITION counts, each bounded by what its
// buffer view can hold, so a false count does not inflate the estimate), before reading any.
uint64_t GltfImporter::meshTriangleCount(int meshIndex) const {
    if (meshIndex < 0 || meshIndex >= static_cast<int>(model_.meshes.size())) return 0;
    uint64_t triangles = 0;
    for (const tinygltf::Primitive& prim : model_.meshes[meshIndex].primitives) {
        int accessor = prim.indices;
        if (accessor < 0) {
            auto pos = prim.attributes.find("POSITION");
            accessor = pos == prim.attributes.end() ? -1 : pos->second;
        }
        if (accessor < 0 || accessor >= static_cast<int>(model_.accessors.size())) continue;
        const tinygltf::Accessor& acc = model_.accessors[accessor];
        uint64_t count = acc.count;
        if (acc.bufferView >= 0 && acc.bufferView < static_cast<int>(model_.bufferViews.size())) {
            const tinygltf::BufferView& view = model_.bufferViews[acc.bufferView];
            const int bytes = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(acc.componentType)) *
                              tinygltf::GetNumComponentsInType(static_cast<uint32_t>(acc.type));
            const uint64_t stride = view.byteStride ? view.byteStride : static_cast<uint64_t>(std::max(bytes, 1));
            count = std::min<uint64_t>(count, view.byteLength / stride + 1);
        }
        const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
        if (mode == TINYGLTF_MODE_TRIANGLES)
            triangles += count / 3;
        else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN)
            triangles += count >= 2 ? count - 2 : 0;
    }
    return triangles;
}

// How many nodes place each mesh, walking the hierarchy as visitNode will; a cycle or too many
// repeated visits stops the count (visitNode then reports them).
std::vector<uint64_t> GltfImporter::placementsPerMesh(const std::vector<int>& roots) const {
    const size_t nodes = model_.nodes.size();
    std::vector<uint64_t> placements(model_.meshes.size(), 0);
    std::vector<bool> seen(nodes, false);
    size_t repeats = 0;
    std::vector<std::pair<int, int>> stack; // (node, depth)
    for (int root : roots) stack.emplace_back(root, 0);
    while (!stack.empty()) {
        const auto [index, depth] = stack.back();
        stack.pop_back();
        if (index < 0 || index >= static_cast<int>(nodes) || depth > kMaxNodeDepth) continue;
        if (seen[index] && ++repeats > kMaxRepeatedNodeVisits) break;
        seen[index] = true;
        const tinygltf::Node& node = model_.nodes[index];
        if (node.mesh >= 0 && node.mesh < static_cast<int>(placements.size())) placements[node.mesh]++;
        for (int child : node.children) stack.emplace_back(child, depth + 1);
    }
    return placements;
}

} // namespace pt::gltf
