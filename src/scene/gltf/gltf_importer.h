#pragma once
// The glTF importer: turns a tinygltf::Model into a Scene, checking everything the model holds.
// Internal to the glTF loader (its API is gltf_loader.h); the class is defined over
//   gltf_importer.cpp        the run, scene extras and the node hierarchy
//   gltf_meshes.cpp          accessors, meshes and their primitives
//   gltf_materials.cpp       materials and textures with their KHR extensions
//   gltf_lights_cameras.cpp  cameras and KHR_lights_punctual lights
#include "scene/gltf/gltf_callbacks.h"
#include "scene/scene.h"
#include "scene/scene_error.h"

#include <tiny_gltf.h>

#include <glm/glm.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace pt::gltf {

constexpr int kMaxNodeDepth = 1024;
// A node may be the child of several parents (glTF forbids it, files do it anyway), so a small
// file can describe an exponential number of instances: 40 nodes that each list the next one
// twice make 2^40. A tree visits each node once, whatever its size; repeat visits are bounded,
// and so are the vertices and triangles of the meshes read.
constexpr size_t kMaxRepeatedNodeVisits = size_t(1) << 12;
constexpr size_t kMaxInstanced = size_t(1) << 27; // vertices, and triangles

inline bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// A number for a note, shortest form ("1.5", "512", "1e-06").
inline std::string formatNumber(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", v);
    return buffer;
}

class GltfImporter {
public:
    GltfImporter(const tinygltf::Model& model, std::string file, DecodedImages& images, std::string variant = "")
        : model_(model), file_(std::move(file)), decoded_(images), variant_(std::move(variant)) {}

    Scene run();

private:
    [[noreturn]] void fail(const std::string& problem) const { throw SceneError(file_, problem); }
    void unsupported(const std::string& what) { unsupportedCounts_[what]++; }

    // ---- gltf_importer.cpp ----
    void readHints();
    std::vector<int> rootNodes();
    glm::mat4 localTransform(const tinygltf::Node& node, int index);
    void visitNode(int index, const glm::mat4& parent, std::vector<bool>& onPath, int depth);
    void noteUnsupportedExtensions();
    void readMaterialVariants();
    int primitiveMaterial(const tinygltf::Primitive& prim, const std::string& label) const;

    // ---- gltf_materials.cpp ----
    double number(const tinygltf::Value& obj, const char* key, double fallback, const std::string& where);
    glm::vec3 color(const tinygltf::Value& obj, const char* key, glm::vec3 fallback, const std::string& where);
    void convertMaterials();
    void convertFactors(const tinygltf::Material& src, const std::string& label, Material& m);
    void convertTextures(const tinygltf::Material& src, const std::string& label, Material& m);
    void convertSpecularGlossiness(const tinygltf::Material& src, const std::string& label, Material& m);
    static int wrap(int mode, const std::string& where, const GltfImporter& self);
    std::optional<uint32_t> extensionTexture(
        const tinygltf::Value* ext, const char* key, Texture::Encoding encoding, const std::string& where);
    std::optional<uint32_t> texture(int index, int texCoord, const tinygltf::ExtensionMap& extensions,
        Texture::Encoding encoding, const std::string& where);
    uint32_t imageIndex(int index, const std::string& where);
    uint32_t defaultMaterial();

    // ---- gltf_meshes.cpp ----
    const unsigned char* accessorData(
        int accessorIndex, const std::string& what, size_t& count, size_t& stride, int& componentType, int& type);
    template <int N>
    std::vector<glm::vec<N, float>> readVectors(int accessorIndex, const std::string& what, bool allowNormalizedInts);
    std::vector<uint32_t> readIndices(int accessorIndex, const std::string& what);
    // The mesh's triangle primitives, each a Mesh, mapped by `transform` (identity: object space).
    std::vector<Mesh> readMesh(const tinygltf::Mesh& mesh, int meshIndex, const glm::mat4& transform);
    // A node's mesh: copied into world space if no other node places it, else an instance of
    // the mesh kept once (Scene::sharedMeshes).
    void placeMesh(int meshIndex, const glm::mat4& world, int nodeIndex);
    uint64_t meshTriangleCount(int meshIndex) const;
    std::vector<uint64_t> placementsPerMesh(const std::vector<int>& roots) const;

    // ---- gltf_lights_cameras.cpp ----
    void addCamera(int cameraIndex, const glm::mat4& world);
    void addLight(const tinygltf::Value& ref, int nodeIndex, const glm::mat4& world);

    const tinygltf::Model& model_;
    std::string file_;
    DecodedImages& decoded_;
    std::string variant_;   // KHR_materials_variants: the variant asked for, or empty
    int variantIndex_ = -1; // its index in the scene's list

    std::map<int, uint32_t> imageIndices_;
    Scene scene_;
    int defaultMaterial_ = -1;
    std::vector<bool> visited_;
    std::vector<uint64_t> placements_;          // per mesh: the nodes that place it
    std::map<int, uint32_t> sharedMeshIndices_; // mesh -> its entry in Scene::sharedMeshes
    size_t repeatedVisits_ = 0, instancedVertices_ = 0, instancedTriangles_ = 0;
    std::map<std::string, int> unsupportedCounts_;
};

} // namespace pt::gltf
