#include "scene/mesh_placement.h"

#include <glm/gtc/matrix_inverse.hpp>

#include <cmath>

namespace pt {

Mesh placeMesh(const Mesh& part, const glm::mat4& objectToWorld) {
    const glm::mat3 linear(objectToWorld);
    const glm::mat3 normalMatrix = glm::inverseTranspose(linear);
    const bool mirrored = glm::determinant(linear) < 0.0f;
    Mesh out;
    out.name = part.name;
    out.material = part.material;
    out.motion = part.motion;
    out.uvs = part.uvs;
    out.positions.reserve(part.positions.size());
    for (const glm::vec3& p : part.positions) out.positions.push_back(glm::vec3(objectToWorld * glm::vec4(p, 1.0f)));
    out.normals.reserve(part.normals.size());
    for (const glm::vec3& n : part.normals) {
        const glm::vec3 w = normalMatrix * n;
        const float len = glm::length(w);
        out.normals.push_back(n != glm::vec3(0.0f) && std::isfinite(len) && len > 0.0f ? w / len : glm::vec3(0.0f));
    }
    out.tangents.reserve(part.tangents.size());
    for (const glm::vec4& t : part.tangents) {
        const glm::vec3 w = linear * glm::vec3(t);
        const float len = glm::length(w);
        const bool ok = t.w != 0.0f && std::isfinite(len) && len > 0.0f;
        out.tangents.push_back(ok ? glm::vec4(w / len, mirrored ? -t.w : t.w) : glm::vec4(0.0f));
    }
    out.triangles.reserve(part.triangles.size());
    for (const glm::uvec3& t : part.triangles) out.triangles.push_back(mirrored ? glm::uvec3(t.x, t.z, t.y) : t);
    return out;
}

std::vector<Mesh> placeInstance(const Scene& scene, const MeshInstance& instance) {
    std::vector<Mesh> placed;
    for (const Mesh& part : scene.sharedMeshes.at(instance.mesh).parts) {
        Mesh m = placeMesh(part, instance.objectToWorld);
        if (instance.material) m.material = *instance.material;
        m.motion = instance.motion;
        if (!instance.name.empty()) m.name = instance.name;
        placed.push_back(std::move(m));
    }
    return placed;
}

void expandInstances(Scene& scene) {
    for (const MeshInstance& instance : scene.instances)
        for (Mesh& m : placeInstance(scene, instance)) scene.meshes.push_back(std::move(m));
    scene.instances.clear();
    scene.sharedMeshes.clear();
}

bool isPlaceable(const glm::mat4& m) {
    const float det = glm::determinant(glm::mat3(m));
    if (!std::isfinite(det) || det == 0.0f) return false;
    const glm::mat4 inverse = glm::inverse(m);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r]) || !std::isfinite(inverse[c][r])) return false;
    return true;
}

} // namespace pt
