#pragma once
// The renderer's scene model: what every loader (glTF, course XML) produces and everything
// downstream (BVH, light table, GPU upload) consumes. World space, no hierarchy left.
#include <glm/glm.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace pt {

enum class MaterialType { Diffuse, Mirror, Dielectric };

struct Material {
    std::string name;
    MaterialType type = MaterialType::Diffuse;
    glm::vec3 baseColor{0.8f}; // diffuse albedo; mirror F0; dielectric transmission tint
    glm::vec3 emission{0.0f};  // emitted radiance
    bool doubleSided = false;
    float ior = 1.5f;
    // Beer-Lambert inside a dielectric: transmittance attenuationColor after attenuationDistance.
    glm::vec3 attenuationColor{1.0f};
    float attenuationDistance = std::numeric_limits<float>::infinity();

    bool emissive() const { return emission.x > 0 || emission.y > 0 || emission.z > 0; }
};

struct Mesh {
    std::string name;
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals; // empty, or one per position (unit length where valid)
    std::vector<glm::vec2> uvs;     // empty, or one per position
    std::vector<glm::uvec3> triangles;
    uint32_t material = 0;
};

struct Camera {
    std::string name;
    glm::vec3 position{0.0f};
    glm::vec3 forward{0.0f, 0.0f, -1.0f}; // unit
    glm::vec3 up{0.0f, 1.0f, 0.0f};       // unit, orthogonal to forward
    float yfov = 0.8f;                    // radians
    float aspectRatio = 0.0f;             // width / height, 0 when the file does not say
};

// Settings a scene file may carry for itself; the command line overrides them.
struct RenderHints {
    std::optional<int> width;
    std::optional<int> height;
    std::optional<int> maxDepth;
};

struct Scene {
    std::string source; // file name, or "built-in Cornell box"
    std::vector<Material> materials;
    std::vector<Mesh> meshes;
    std::vector<Camera> cameras;
    glm::vec3 background{0.0f};
    RenderHints hints;
    // Things the file uses that the renderer does not model yet (shown as one warning).
    std::vector<std::string> unsupported;

    size_t triangleCount() const {
        size_t n = 0;
        for (const auto& m : meshes) n += m.triangles.size();
        return n;
    }
};

} // namespace pt
