#include "support/load_contract.h"

#include "scene/scene_error.h"

#include <cmath>
#include <exception>
#include <new>

namespace pt::test {
namespace {

// Long enough for any honest message (a file name, an element path and a sentence); a message
// longer than this echoes the input back unbounded.
constexpr size_t kMaxProblemLength = 1000;

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finite(const glm::vec4& v) { return finite(glm::vec3(v)) && std::isfinite(v.w); }

std::string meshInconsistency(const Mesh& m, size_t materialCount) {
    const size_t n = m.positions.size();
    if (m.material >= materialCount)
        return "mesh '" + m.name + "' has material " + std::to_string(m.material) + " of " +
               std::to_string(materialCount);
    if (!m.normals.empty() && m.normals.size() != n)
        return "mesh '" + m.name + "' has a normal count that differs from its position count";
    if (!m.uvs.empty() && m.uvs.size() != n)
        return "mesh '" + m.name + "' has a uv count that differs from its position count";
    if (!m.tangents.empty() && m.tangents.size() != n)
        return "mesh '" + m.name + "' has a tangent count that differs from its position count";
    for (const glm::vec3& p : m.positions)
        if (!finite(p)) return "mesh '" + m.name + "' has a non-finite position";
    for (const glm::uvec3& t : m.triangles)
        if (t.x >= n || t.y >= n || t.z >= n) return "mesh '" + m.name + "' has a vertex index out of range";
    if (!finite(m.motion)) return "mesh '" + m.name + "' has non-finite motion";
    return "";
}

std::string textureInconsistency(const Scene& s, const std::optional<uint32_t>& t, const std::string& what) {
    if (!t) return "";
    if (*t >= s.textures.size())
        return what + " texture " + std::to_string(*t) + " of " + std::to_string(s.textures.size());
    const Texture& tex = s.textures[*t];
    if (tex.type == Texture::Type::Image && tex.image >= s.textureImages.size())
        return what + " texture refers to a missing image";
    return "";
}

} // namespace

std::string sceneInconsistency(const Scene& s) {
    // A mesh several nodes place is kept once (sharedMeshes) with an instance per placement: a scene
    // of instances alone has something to render.
    if (s.meshes.empty() && s.spheres.empty() && s.instances.empty())
        return "a scene with nothing to render was accepted";
    for (const Mesh& m : s.meshes)
        if (std::string p = meshInconsistency(m, s.materials.size()); !p.empty()) return p;
    for (const SharedMesh& shared : s.sharedMeshes)
        for (const Mesh& m : shared.parts)
            if (std::string p = meshInconsistency(m, s.materials.size()); !p.empty()) return p;
    for (const MeshInstance& instance : s.instances) {
        const std::string name = "instance '" + instance.name + "'";
        if (instance.mesh >= s.sharedMeshes.size()) return name + " places a mesh that does not exist";
        if (s.sharedMeshes[instance.mesh].parts.empty()) return name + " places a mesh with no triangles";
        if (instance.material && *instance.material >= s.materials.size()) return name + " has a material out of range";
        for (int c = 0; c < 4; ++c)
            if (!finite(glm::vec4(instance.objectToWorld[c]))) return name + " has a non-finite transform";
        if (!finite(instance.motion)) return name + " has a non-finite motion";
    }
    for (const Sphere& sp : s.spheres) {
        if (sp.material >= s.materials.size()) return "sphere '" + sp.name + "' has a material out of range";
        for (int c = 0; c < 4; ++c)
            if (!finite(glm::vec3(sp.objectToWorld[c]))) return "sphere '" + sp.name + "' has a non-finite transform";
    }
    for (const Material& m : s.materials) {
        const std::string name = "material '" + m.name + "'";
        for (const auto& [t, what] : {std::pair{&m.baseColorTexture, "base colour"}, {&m.specularTexture, "specular"},
                 {&m.metallicRoughnessTexture, "metallic-roughness"}, {&m.normalTexture, "normal"},
                 {&m.emissiveTexture, "emissive"}})
            if (std::string p = textureInconsistency(s, *t, name + ": " + what); !p.empty()) return p;
        if (!finite(m.baseColor) || !finite(m.emission)) return name + " has a non-finite colour";
    }
    if (std::string p = textureInconsistency(s, s.backgroundTexture, "background"); !p.empty()) return p;
    for (const TextureImage& image : s.textureImages) {
        const size_t pixels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
        if (image.width <= 0 || image.height <= 0 || (image.rgba8.size() != pixels && image.rgbaF.size() != pixels))
            return "image '" + image.source + "' has a pixel count that differs from its size";
    }
    for (const Camera& c : s.cameras)
        if (!finite(c.position) || !finite(c.forward) || !finite(c.up) || !std::isfinite(c.yfov))
            return "camera '" + c.name + "' is not finite";
    for (const PunctualLight& l : s.punctualLights)
        if (!finite(l.position) || !finite(l.direction) || !finite(l.intensity))
            return "a punctual light is not finite";
    return "";
}

std::string messageProblem(const std::string& message, const std::string& displayName) {
    const std::string prefix = displayName + ": ";
    if (message.rfind(prefix, 0) != 0) return "the message does not start with '" + prefix + "': " + message;
    const std::string problem = message.substr(prefix.size());
    if (problem.empty()) return "the message names no problem";
    if (problem.size() > kMaxProblemLength)
        return "the message is " + std::to_string(problem.size()) + " characters long";
    for (unsigned char c : problem)
        if (c < 0x20 && c != '\t')
            return "the message contains control character " + std::to_string(c) + ": " + message;
    return "";
}

std::string checkLoadContract(const std::string& displayName, const std::function<Scene()>& load) {
    try {
        const Scene scene = load();
        const std::string p = sceneInconsistency(scene);
        return p.empty() ? "" : "accepted an inconsistent scene: " + p;
    } catch (const SceneError& e) {
        return messageProblem(e.what(), displayName);
    } catch (const std::bad_alloc&) {
        return "std::bad_alloc escaped the loader (an allocation sized by the input?)";
    } catch (const std::exception& e) {
        return std::string("an exception other than SceneError escaped the loader: ") + e.what();
    }
}

} // namespace pt::test
