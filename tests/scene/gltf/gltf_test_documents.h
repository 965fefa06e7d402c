#pragma once
// What the glTF loader's tests share (the tests of one part of the loader each are the *_test.cpp
// files beside this one): vector comparisons, material lookups, and tiny hand-written documents
// (one triangle per material, its buffer in a base64 data: URI) loaded from text. In a namespace
// of their own: ceng795_fixture.h has a pt::test::near3 with another default, in the same binary.
#include "scene/gltf/gltf_loader.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace pt::test::gltf {

namespace fs = std::filesystem;

inline ::testing::AssertionResult near3(const glm::vec3& a, const glm::vec3& b, float tol) {
    if (glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec3(tol)))) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "(" << a.x << ", " << a.y << ", " << a.z << ") != (" << b.x << ", " << b.y
                                         << ", " << b.z << ") within " << tol;
}

inline const pt::Material* findMaterial(const pt::Scene& s, const std::string& name) {
    for (const auto& m : s.materials)
        if (m.name == name) return &m;
    return nullptr;
}

inline std::string base64(const std::vector<unsigned char>& bytes) {
    static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        uint32_t v = uint32_t(bytes[i]) << 16;
        if (i + 1 < bytes.size()) v |= uint32_t(bytes[i + 1]) << 8;
        if (i + 2 < bytes.size()) v |= uint32_t(bytes[i + 2]);
        out += k[(v >> 18) & 63];
        out += k[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? k[(v >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? k[v & 63] : '=';
    }
    return out;
}

// The local triangle: normal (-1, 0, 1)/sqrt(2), counter-clockwise seen from that side.
inline const glm::vec3 kP[3] = {{0, 0, 0}, {1, 0, 1}, {0, 1, 0}};
inline const glm::vec3 kN = glm::normalize(glm::vec3(-1, 0, 1));

inline pt::Scene loadText(const std::string& text) {
    return pt::loadGltfText(text, "test.gltf", fs::temp_directory_path());
}

// Material factors, KHR_materials_* and KHR_lights_punctual: one triangle per material, lights
// on their own nodes. `materials` and `lights` are JSON arrays; `lightNodes` are extra nodes
// (after the mesh nodes).
inline std::string materialDocument(const std::string& materials, int materialCount, const std::string& lights = "[]",
    const std::string& lightNodes = "") {
    std::vector<unsigned char> bytes(36);
    for (int i = 0; i < 3; ++i) std::memcpy(bytes.data() + 12 * i, &kP[i], 12);
    std::ostringstream nodes, meshes, roots;
    for (int i = 0; i < materialCount; ++i) {
        nodes << (i ? ", " : "") << R"({"mesh": )" << i << "}";
        meshes << (i ? ", " : "") << R"({"primitives": [{"attributes": {"POSITION": 0}, "material": )" << i << "}]}";
        roots << (i ? ", " : "") << i;
    }
    int next = materialCount;
    if (!lightNodes.empty()) {
        nodes << ", " << lightNodes;
        for (size_t c = 0, depth = 0; c < lightNodes.size(); ++c) {
            // Count the top-level objects of the node list.
            if (lightNodes[c] == '{' && depth++ == 0) roots << ", " << next++;
            if (lightNodes[c] == '}') --depth;
        }
    }
    std::ostringstream d;
    d << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [)" << roots.str() << R"(]}],
  "nodes": [)"
      << nodes.str() << R"(], "meshes": [)" << meshes.str() << R"(],
  "materials": )"
      << materials << R"(,
  "extensions": {"KHR_lights_punctual": {"lights": )"
      << lights << R"(}},
  "extensionsUsed": ["KHR_materials_specular", "KHR_materials_ior", "KHR_materials_transmission",
                     "KHR_materials_volume", "KHR_materials_emissive_strength", "KHR_lights_punctual"],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1]}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}],
  "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,)"
      << base64(bytes) << R"("}]})";
    return d.str();
}

} // namespace pt::test::gltf
