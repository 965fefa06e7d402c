#pragma once
// What the CENG795 course XML loader's tests share (the tests of one element family each are
// the *_test.cpp files beside this one; the format is docs/ceng795-format.md): vector
// comparisons, lookups in a loaded scene, pieces of small scenes, and the fixture that writes a
// scene into a fresh directory, loads it, and checks the one-line error of a bad one.
#include "scene/ceng795/loader.h"
#include "scene/mesh_placement.h"
#include "scene/scene_error.h"
#include "support/test_directory.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace pt::test {

namespace fs = std::filesystem;

inline ::testing::AssertionResult near3(const glm::vec3& a, const glm::vec3& b, float tol = 1e-5f) {
    if (glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec3(tol)))) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "(" << a.x << ", " << a.y << ", " << a.z << ") != (" << b.x << ", " << b.y
                                         << ", " << b.z << ") within " << tol;
}

inline ::testing::AssertionResult near4(const glm::vec4& a, const glm::vec4& b, float tol = 1e-6f) {
    if (glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec4(tol)))) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "(" << a.x << ", " << a.y << ", " << a.z << ", " << a.w << ") != (" << b.x
                                         << ", " << b.y << ", " << b.z << ", " << b.w << ")";
}

inline bool contains(const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) != v.end();
}

inline glm::vec3 geometricNormal(const pt::Mesh& m, size_t triangle) {
    const glm::uvec3 t = m.triangles[triangle];
    return glm::normalize(glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]));
}

// World position of corner `corner` of triangle `triangle`.
inline glm::vec3 corner(const pt::Mesh& m, size_t triangle, int corner) {
    return m.positions[m.triangles[triangle][corner]];
}

inline const pt::Mesh* findMesh(const pt::Scene& s, const std::string& name) {
    for (const auto& m : s.meshes)
        if (m.name == name) return &m;
    return nullptr;
}

// Pieces of small scenes. Vertex ids 1..4 are the unit square in z = 0.
inline const std::string kOneMaterial =
    "<Materials><Material id=\"1\"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance></Material></Materials>";
inline const std::string kSquare = "<VertexData>0 0 0  1 0 0  1 1 0  0 1 0</VertexData>";

inline std::string sceneXml(const std::string& inner) { return "<Scene>" + inner + "</Scene>"; }

// A scene with the square's first triangle as Mesh 1 plus `objects` and `extra` elements.
inline std::string triangleScene(
    const std::string& meshAttributes, const std::string& meshChildren, const std::string& extra = "") {
    return sceneXml(kOneMaterial + kSquare + extra + "<Objects><Mesh id=\"1\"" + meshAttributes +
                    "><Material>1</Material>" + meshChildren + "<Faces>1 2 3</Faces></Mesh></Objects>");
}

class Ceng795 : public ::testing::Test {
protected:
    void SetUp() override { dir_ = freshTestDirectory("ceng795"); }
    void TearDown() override { fs::remove_all(dir_); }

    fs::path write(const std::string& name, const std::string& content) const {
        const fs::path p = dir_ / name;
        fs::create_directories(p.parent_path());
        std::ofstream(p, std::ios::binary) << content;
        return p;
    }

    fs::path writeBinary(const std::string& name, const std::vector<int32_t>& header, const std::vector<float>& floats,
        const std::vector<int32_t>& ints = {}) const {
        const fs::path p = dir_ / name;
        fs::create_directories(p.parent_path());
        std::ofstream out(p, std::ios::binary);
        out.write(reinterpret_cast<const char*>(header.data()), static_cast<std::streamsize>(header.size() * 4));
        out.write(reinterpret_cast<const char*>(floats.data()), static_cast<std::streamsize>(floats.size() * 4));
        out.write(reinterpret_cast<const char*>(ints.data()), static_cast<std::streamsize>(ints.size() * 4));
        return p;
    }

    pt::Scene load(const std::string& xml) const { return pt::loadCeng795File(write("scene.xml", xml)); }
    // The scene with its instances copied into world space (pt::expandInstances), in file order
    // where every mesh is an instance.
    pt::Scene loadExpanded(const std::string& xml) const {
        pt::Scene s = load(xml);
        pt::expandInstances(s);
        return s;
    }

    // Loading must fail with one line "<file>: <label>: ...<problem>...".
    void expectError(const std::string& xml, const std::string& label, const std::string& problem) const {
        const fs::path file = write("scene.xml", xml);
        std::string message = "(no error)";
        try {
            pt::loadCeng795File(file);
        } catch (const pt::SceneError& e) {
            message = e.what();
        }
        const std::string prefix = file.string() + ": ";
        ASSERT_EQ(message.rfind(prefix, 0), 0u) << message;
        const std::string rest = message.substr(prefix.size());
        if (!label.empty()) {
            EXPECT_EQ(rest.rfind(label + ": ", 0), 0u) << message;
        }
        EXPECT_NE(rest.find(problem), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }

    fs::path dir_;
};

} // namespace pt::test
