// The PLY reader on real sample files (tests/data/ply/README.md), on synthesized files in all three
// formats, and on hostile input: every malformed file must give one SceneError line that starts
// with the file name, never a crash, a hang or a huge allocation.
#include "scene/ceng795/ply_reader.h"
#include "scene/scene_error.h"
#include "support/test_directory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

// The real build defines this as the absolute path of tests/; a standalone build runs from the
// repository root.
#ifndef PT_TEST_DATA_DIR
#define PT_TEST_DATA_DIR "tests"
#endif

namespace fs = std::filesystem;

namespace {

// ---------------------------------------------------------------------------------------------
// Building PLY files

// Appends `value` as a binary PLY value of the named type in the requested byte order.
void putBinary(std::string& out, const std::string& type, double value, bool bigEndian) {
    auto append = [&](auto v) {
        char bytes[sizeof(v)];
        std::memcpy(bytes, &v, sizeof(v));
        if (bigEndian != (std::endian::native == std::endian::big)) std::reverse(bytes, bytes + sizeof(v));
        out.append(bytes, sizeof(v));
    };
    if (type == "char" || type == "int8")
        append(static_cast<int8_t>(value));
    else if (type == "uchar" || type == "uint8")
        append(static_cast<uint8_t>(value));
    else if (type == "short" || type == "int16")
        append(static_cast<int16_t>(value));
    else if (type == "ushort" || type == "uint16")
        append(static_cast<uint16_t>(value));
    else if (type == "int" || type == "int32")
        append(static_cast<int32_t>(value));
    else if (type == "uint" || type == "uint32")
        append(static_cast<uint32_t>(value));
    else if (type == "float" || type == "float32")
        append(static_cast<float>(value));
    else if (type == "double" || type == "float64")
        append(value);
    else
        ADD_FAILURE() << "test bug: unknown type " << type;
}

// A value as ascii PLY text. 17 significant digits of a float widened to double are exact, so the
// ascii and binary versions of a file hold identical values.
std::string asciiValue(double value) {
    char text[64];
    std::snprintf(text, sizeof(text), "%.17g", value);
    return text;
}

std::string formatLine(const std::string& format) { return "format " + format + " 1.0\n"; }

// A small mesh with everything the reader interprets: a quad and a triangle, normals and uvs.
struct Vertex {
    float p[3], n[3], uv[2];
};
const std::vector<Vertex> kVertices = {
    {{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f}, {0.0f, 0.0f}},
    {{1.0f, 0.0f, 0.0f}, {0.0f, 0.6f, 0.8f}, {1.0f, 0.0f}},
    {{1.0f, 1.0f, 0.0f}, {0.0f, 0.0f, -1.0f}, {1.0f, 1.0f}},
    {{0.0f, 1.0f, 0.0f}, {-0.6f, 0.0f, 0.8f}, {0.0f, 1.0f}},
    {{2.5f, -0.1f, 1e-3f}, {1.0f, 0.0f, 0.0f}, {0.25f, 0.7f}},
};
const std::vector<std::vector<int>> kFaces = {{0, 1, 2, 3}, {1, 4, 2}};
const std::vector<glm::uvec3> kTriangles = {{0, 1, 2}, {0, 2, 3}, {1, 4, 2}};

std::string fullMeshHeader(const std::string& format) {
    return "ply\n" + formatLine(format) + "comment written by ply_reader_test\n" +
           "element vertex 5\n"
           "property float x\nproperty float y\nproperty float z\n"
           "property float nx\nproperty float ny\nproperty float nz\n"
           "property float u\nproperty float v\n"
           "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
}

std::string fullMeshAscii() {
    std::string out = fullMeshHeader("ascii");
    for (const Vertex& v : kVertices) {
        for (float x : {v.p[0], v.p[1], v.p[2], v.n[0], v.n[1], v.n[2], v.uv[0], v.uv[1]}) out += asciiValue(x) + " ";
        out += "\n";
    }
    for (const auto& f : kFaces) {
        out += std::to_string(f.size());
        for (int i : f) out += " " + std::to_string(i);
        out += "\n";
    }
    return out;
}

std::string fullMeshBinary(bool bigEndian) {
    std::string out = fullMeshHeader(bigEndian ? "binary_big_endian" : "binary_little_endian");
    for (const Vertex& v : kVertices)
        for (float x : {v.p[0], v.p[1], v.p[2], v.n[0], v.n[1], v.n[2], v.uv[0], v.uv[1]})
            putBinary(out, "float", x, bigEndian);
    for (const auto& f : kFaces) {
        putBinary(out, "uchar", static_cast<double>(f.size()), bigEndian);
        for (int i : f) putBinary(out, "int", i, bigEndian);
    }
    return out;
}

// A unit square (two triangles from one quad) in binary little endian with chosen list types.
std::string squareBinary(const std::string& countType, const std::string& indexType) {
    std::string out = "ply\n" + formatLine("binary_little_endian") +
                      "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                      "element face 1\nproperty list " +
                      countType + " " + indexType + " vertex_index\nend_header\n";
    for (float x : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 1.f, 1.f, 0.f, 0.f, 1.f, 0.f}) putBinary(out, "float", x, false);
    putBinary(out, countType, 4, false);
    for (int i : {0, 1, 2, 3}) putBinary(out, indexType, i, false);
    return out;
}

// The same square in ascii, with a header and face line given by the caller.
const char* const kSquareVerticesAscii = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n";
std::string squareAscii(const std::string& faceLines) {
    return "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
           "element face 1\nproperty list uchar int vertex_indices\nend_header\n" +
           std::string(kSquareVerticesAscii) + faceLines;
}

// ---------------------------------------------------------------------------------------------
// Checks

::testing::AssertionResult sameMesh(const pt::PlyMesh& a, const pt::PlyMesh& b) {
    if (a.positions != b.positions) return ::testing::AssertionFailure() << "positions differ";
    if (a.normals != b.normals) return ::testing::AssertionFailure() << "normals differ";
    if (a.uvs != b.uvs) return ::testing::AssertionFailure() << "uvs differ";
    if (a.triangles != b.triangles) return ::testing::AssertionFailure() << "triangles differ";
    return ::testing::AssertionSuccess();
}

// What every successfully read mesh must satisfy, whatever the input was.
::testing::AssertionResult consistent(const pt::PlyMesh& m) {
    if (!m.normals.empty() && m.normals.size() != m.positions.size())
        return ::testing::AssertionFailure() << "normal count";
    if (!m.uvs.empty() && m.uvs.size() != m.positions.size()) return ::testing::AssertionFailure() << "uv count";
    for (const glm::vec3& p : m.positions)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return ::testing::AssertionFailure() << "non-finite position";
    for (const glm::uvec3& t : m.triangles)
        if (t.x >= m.positions.size() || t.y >= m.positions.size() || t.z >= m.positions.size())
            return ::testing::AssertionFailure() << "index out of range";
    return ::testing::AssertionSuccess();
}

class PlyReader : public ::testing::Test {
protected:
    void SetUp() override { dir_ = pt::test::freshTestDirectory("ply_test"); }
    void TearDown() override {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }

    fs::path write(const std::string& name, const std::string& bytes) const {
        const fs::path path = dir_ / name;
        std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        return path;
    }

    // Reads `bytes` (written as `name`) and expects a SceneError: one line, starting with the
    // path, whose problem part (after the path, so that file names cannot help) contains `word`.
    void expectError(const std::string& name, const std::string& bytes, const std::string& word) const {
        expectErrorAt(write(name, bytes), word);
    }

    static void expectErrorAt(const fs::path& path, const std::string& word) {
        try {
            (void)pt::readPly(path);
            ADD_FAILURE() << "no error for " << path.filename() << " (expected '" << word << "')";
        } catch (const pt::SceneError& e) {
            const std::string what = e.what();
            const std::string prefix = path.string() + ": ";
            ASSERT_EQ(what.rfind(prefix, 0), 0u) << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
            EXPECT_NE(what.substr(prefix.size()).find(word), std::string::npos) << what;
        }
    }

    // Success or SceneError; a successful result must be self-consistent.
    void expectNoCrash(const std::string& bytes) const {
        const fs::path path = write("fuzz.ply", bytes);
        try {
            EXPECT_TRUE(consistent(pt::readPly(path)));
        } catch (const pt::SceneError&) {}
    }

    fs::path dir_;
};

// ---------------------------------------------------------------------------------------------
// Well-formed files

TEST_F(PlyReader, AsciiCubeOfQuadsGivesTwelveTriangles) {
    const std::string cube = "ply\nformat ascii 1.0\ncomment a cube of quads\nobj_info made by hand\n"
                             "element vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
                             "element face 6\nproperty list uchar int vertex_index\nend_header\n"
                             "0 0 0\n0 0 1\n0 1 1\n0 1 0\n1 0 0\n1 0 1\n1 1 1\n1 1 0\n"
                             "4 0 1 2 3\n4 7 6 5 4\n4 0 4 5 1\n4 1 5 6 2\n4 2 6 7 3\n4 3 7 4 0\n";
    const pt::PlyMesh m = pt::readPly(write("cube.ply", cube));
    EXPECT_EQ(m.positions.size(), 8u);
    EXPECT_EQ(m.triangles.size(), 12u);
    EXPECT_TRUE(m.normals.empty());
    EXPECT_TRUE(m.uvs.empty());
    EXPECT_EQ(m.positions[6], glm::vec3(1, 1, 1));
    // Quads are fans around their first vertex.
    EXPECT_EQ(m.triangles[0], glm::uvec3(0, 1, 2));
    EXPECT_EQ(m.triangles[1], glm::uvec3(0, 2, 3));
    EXPECT_EQ(m.triangles[11], glm::uvec3(3, 4, 0));
    EXPECT_TRUE(consistent(m));
}

TEST_F(PlyReader, AllThreeFormatsGiveIdenticalMeshes) {
    const pt::PlyMesh ascii = pt::readPly(write("ascii.ply", fullMeshAscii()));
    const pt::PlyMesh little = pt::readPly(write("little.ply", fullMeshBinary(false)));
    const pt::PlyMesh big = pt::readPly(write("big.ply", fullMeshBinary(true)));

    ASSERT_EQ(little.positions.size(), kVertices.size());
    ASSERT_EQ(little.normals.size(), kVertices.size());
    ASSERT_EQ(little.uvs.size(), kVertices.size());
    for (size_t i = 0; i < kVertices.size(); ++i) {
        const Vertex& v = kVertices[i];
        EXPECT_EQ(little.positions[i], glm::vec3(v.p[0], v.p[1], v.p[2])) << i;
        EXPECT_EQ(little.normals[i], glm::vec3(v.n[0], v.n[1], v.n[2])) << i;
        EXPECT_EQ(little.uvs[i], glm::vec2(v.uv[0], v.uv[1])) << i;
    }
    EXPECT_EQ(little.triangles, kTriangles);
    EXPECT_TRUE(sameMesh(ascii, little));
    EXPECT_TRUE(sameMesh(big, little));
}

TEST_F(PlyReader, ListCountAndIndexTypes) {
    const std::vector<glm::uvec3> expected = {{0, 1, 2}, {0, 2, 3}};
    const std::pair<const char*, const char*> kTypes[] = {
        {"uchar", "int"},
        {"int", "int"},
        {"uint8", "uint32"},
        {"ushort", "uint"},
        {"char", "short"},
        {"uint", "ushort"},
        {"int16", "uint8"},
        {"int32", "int8"},
    };
    for (const auto& [count, index] : kTypes) {
        const std::string name = std::string(count) + "_" + index + ".ply";
        const pt::PlyMesh m = pt::readPly(write(name, squareBinary(count, index)));
        EXPECT_EQ(m.triangles, expected) << name;
    }
}

TEST_F(PlyReader, PositionTypeAliasesAndDoubles) {
    // x as double, y as int16, z as uchar, plus skipped properties of every other alias.
    const char* const kSkipped[] = {"char", "int8", "uint8", "short", "ushort", "uint16", "int", "int32", "uint",
        "uint32", "float", "float32", "float64"};
    std::string header = "ply\nformat binary_big_endian 1.0\nelement vertex 3\n"
                         "property double x\nproperty int16 y\nproperty uchar z\n";
    for (const char* type : kSkipped) header += std::string("property ") + type + " extra_" + type + "\n";
    header += "element face 1\nproperty list uchar uint vertex_indices\nend_header\n";
    std::string body;
    const double kPositions[3][3] = {{0.125, -7, 200}, {1e10, 32767, 0}, {-3.5, -32768, 255}};
    for (const auto& p : kPositions) {
        putBinary(body, "double", p[0], true);
        putBinary(body, "int16", p[1], true);
        putBinary(body, "uchar", p[2], true);
        for (const char* type : kSkipped) putBinary(body, type, 42, true);
    }
    putBinary(body, "uchar", 3, true);
    for (int i : {2, 1, 0}) putBinary(body, "uint", i, true);

    const pt::PlyMesh m = pt::readPly(write("types.ply", header + body));
    ASSERT_EQ(m.positions.size(), 3u);
    for (int i = 0; i < 3; ++i)
        EXPECT_EQ(m.positions[i], glm::vec3(static_cast<float>(kPositions[i][0]), static_cast<float>(kPositions[i][1]),
                                      static_cast<float>(kPositions[i][2])));
    EXPECT_EQ(m.triangles, std::vector<glm::uvec3>{glm::uvec3(2, 1, 0)});
}

// Unknown elements (with list properties, some even named vertex_indices) before, between and
// after the mesh elements, and unknown properties inside them, are skipped in both encodings.
std::string meshWithExtras(bool binary) {
    std::string out = "ply\n" + formatLine(binary ? "binary_little_endian" : "ascii") +
                      "element edge 2\nproperty list uchar int vertex_indices\nproperty uchar flag\n"
                      "element vertex 4\nproperty uchar red\nproperty float x\nproperty list ushort double extra\n"
                      "property float y\nproperty float z\n"
                      "element material 5\n" // no properties: occupies nothing
                      "element face 2\nproperty int flags\nproperty list uchar int vertex_indices\n"
                      "property list uchar float texcoord\n"
                      "element edge2 1\nproperty list int uint ids\nend_header\n";
    auto value = [&](const std::string& type, double v) {
        if (binary)
            putBinary(out, type, v, false);
        else
            out += asciiValue(v) + " ";
    };
    auto newline = [&] {
        if (!binary) out += "\n";
    };
    for (int e = 0; e < 2; ++e) { // edges
        value("uchar", 3);
        value("int", 9);
        value("int", 9);
        value("int", 9);
        value("uchar", 1);
        newline();
    }
    const float kSquare[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    for (const auto& p : kSquare) {
        value("uchar", 255);
        value("float", p[0]);
        value("ushort", 2);
        value("double", 1.5);
        value("double", -1);
        value("float", p[1]);
        value("float", p[2]);
        newline();
    }
    value("int", 7);
    value("uchar", 3);
    value("int", 0);
    value("int", 1);
    value("int", 2);
    value("uchar", 6);
    for (int i = 0; i < 6; ++i) value("float", 0.5);
    newline();
    value("int", -7);
    value("uchar", 3);
    value("int", 0);
    value("int", 2);
    value("int", 3);
    value("uchar", 0);
    newline();
    value("int", 3);
    value("uint", 1);
    value("uint", 2);
    value("uint", 3);
    newline();
    return out;
}

TEST_F(PlyReader, SkipsUnknownElementsAndProperties) {
    const std::vector<glm::uvec3> expected = {{0, 1, 2}, {0, 2, 3}};
    for (bool binary : {false, true}) {
        const pt::PlyMesh m =
            pt::readPly(write(binary ? "extras_bin.ply" : "extras_ascii.ply", meshWithExtras(binary)));
        ASSERT_EQ(m.positions.size(), 4u) << binary;
        EXPECT_EQ(m.positions[2], glm::vec3(1, 1, 0)) << binary;
        EXPECT_EQ(m.triangles, expected) << binary;
    }
}

TEST_F(PlyReader, TextureCoordinateNames) {
    const char* const kPairs[][2] = {{"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
    for (const auto& pair : kPairs) {
        const std::string ply = std::string("ply\nformat ascii 1.0\nelement vertex 3\n") + "property float " + pair[1] +
                                "\nproperty float x\nproperty float y\nproperty float z\nproperty float " + pair[0] +
                                "\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                "0.5 0 0 0 0.25\n0.75 1 0 0 1\n1 0 1 0 0\n3 0 1 2\n";
        const pt::PlyMesh m = pt::readPly(write(std::string(pair[0]) + ".ply", ply));
        ASSERT_EQ(m.uvs.size(), 3u) << pair[0];
        EXPECT_EQ(m.uvs[0], glm::vec2(0.25f, 0.5f)) << pair[0];
        EXPECT_EQ(m.uvs[1], glm::vec2(1.0f, 0.75f)) << pair[0];
        EXPECT_TRUE(m.normals.empty());
    }
    // With two complete pairs, u/v wins over s/t.
    const std::string both =
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "property float z\nproperty float s\nproperty float t\nproperty float u\nproperty float v\n"
        "end_header\n0 0 0 9 9 0.5 0.25\n";
    const pt::PlyMesh m = pt::readPly(write("both.ply", both));
    ASSERT_EQ(m.uvs.size(), 1u);
    EXPECT_EQ(m.uvs[0], glm::vec2(0.5f, 0.25f));
    EXPECT_TRUE(m.triangles.empty()); // no face element: a point cloud
}

TEST_F(PlyReader, PolygonsAreFannedAndShortFacesSkipped) {
    const std::string ply = "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
                            "property float z\nelement face 5\nproperty list uchar int vertex_indices\nend_header\n"
                            "0 0 0\n1 0 0\n2 1 0\n1 2 0\n0 1 0\n"
                            "5 0 1 2 3 4\n2 0 1\n1 3\n0\n3 4 3 2\n";
    const pt::PlyMesh m = pt::readPly(write("fan.ply", ply));
    const std::vector<glm::uvec3> expected = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {4, 3, 2}};
    EXPECT_EQ(m.triangles, expected);
    EXPECT_EQ(m.shortFaces, 3u); // counted, for the course loader's note
}

TEST_F(PlyReader, CrlfCommentsAndSpacing) {
    const std::string ply = "ply\r\nformat  ascii   1.0\r\ncomment hello: element vertex 99\r\nobj_info x\r\n"
                            "element vertex 3\r\nproperty float x\r\nproperty\tfloat y\r\nproperty float z\r\n"
                            "\r\nelement face 1\r\nproperty list uchar int vertex_indices\r\nend_header\r\n"
                            "0 0 0\r\n+1 0 0\r\n0 1e0 -0\r\n3 0 1 +2\r\n";
    const pt::PlyMesh m = pt::readPly(write("crlf.ply", ply));
    ASSERT_EQ(m.positions.size(), 3u);
    EXPECT_EQ(m.positions[1], glm::vec3(1, 0, 0));
    EXPECT_EQ(m.triangles, std::vector<glm::uvec3>{glm::uvec3(0, 1, 2)});

    // A binary body right after a CRLF end_header starts after the "\n".
    std::string binary = "ply\r\nformat binary_little_endian 1.0\r\nelement vertex 1\r\nproperty float x\r\n"
                         "property float y\r\nproperty float z\r\nend_header\r\n";
    for (float x : {13.0f, 10.0f, 32.0f}) putBinary(binary, "float", x, false);
    const pt::PlyMesh b = pt::readPly(write("crlf_binary.ply", binary));
    ASSERT_EQ(b.positions.size(), 1u);
    EXPECT_EQ(b.positions[0], glm::vec3(13, 10, 32));
}

TEST_F(PlyReader, EmptyAndPropertylessElementsDoNotLoop) {
    // An element without properties takes no bytes, so even a count of 2^64-1 is legal and cheap.
    const std::string ply = "ply\nformat binary_little_endian 1.0\nelement nothing 18446744073709551615\n"
                            "element vertex 0\nproperty float x\nproperty float y\nproperty float z\n"
                            "element face 0\nproperty list uchar int vertex_indices\nend_header\n";
    const auto start = std::chrono::steady_clock::now();
    const pt::PlyMesh m = pt::readPly(write("empty.ply", ply));
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
    EXPECT_TRUE(m.positions.empty());
    EXPECT_TRUE(m.triangles.empty());
}

// ---------------------------------------------------------------------------------------------
// Real samples (copies; see tests/data/ply/README.md)

const fs::path kCubeSample = PT_TEST_DATA_DIR "/data/ply/cube.ply";
const fs::path kBerserkerSample = PT_TEST_DATA_DIR "/data/ply/berserker_mesh_1.ply";

TEST_F(PlyReader, RealAsciiCube) {
    const pt::PlyMesh m = pt::readPly(kCubeSample);
    ASSERT_EQ(m.positions.size(), 8u);
    EXPECT_EQ(m.triangles.size(), 12u);
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (const glm::vec3& p : m.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    EXPECT_EQ(lo, glm::vec3(0));
    EXPECT_EQ(hi, glm::vec3(1));
    EXPECT_TRUE(consistent(m));
}

TEST_F(PlyReader, RealBinaryLittleEndianMesh) {
    const pt::PlyMesh m = pt::readPly(kBerserkerSample);
    ASSERT_EQ(m.positions.size(), 645u);
    ASSERT_EQ(m.triangles.size(), 1232u);
    EXPECT_TRUE(m.normals.empty());
    EXPECT_TRUE(m.uvs.empty());
    EXPECT_EQ(m.triangles[0], glm::uvec3(0, 1, 2));
    // Values checked independently with Python's struct module.
    EXPECT_FLOAT_EQ(m.positions[0].x, 0.038837432861328125f);
    EXPECT_FLOAT_EQ(m.positions[0].y, 1.0778825283050537f);
    EXPECT_FLOAT_EQ(m.positions[0].z, 3.0095338821411133f);
    EXPECT_TRUE(consistent(m));
}

// ---------------------------------------------------------------------------------------------
// Hostile and malformed input

TEST_F(PlyReader, FileLevelProblems) {
    expectErrorAt(dir_ / "missing.ply", "not found");
    fs::create_directory(dir_ / "adir.ply");
    expectErrorAt(dir_ / "adir.ply", "directory");
    expectError("empty.ply", "", "not a PLY file");
    expectError("stl.ply", "solid cube\nfacet normal 0 0 1\n", "not a PLY file");
    expectError("plyx.ply", "plyx\nformat ascii 1.0\nend_header\n", "not a PLY file");
    expectError("binary_junk.ply", std::string("\x00\x01\x02ply\n", 7), "not a PLY file");
}

TEST_F(PlyReader, HeaderProblems) {
    const std::string v = "element vertex 1\nproperty float x\nproperty float y\nproperty float z\n";
    expectError("no_end.ply", "ply\nformat ascii 1.0\n" + v, "end_header");
    expectError("no_end_body.ply", "ply\nformat ascii 1.0\n" + v + "0 0 0\n", "end_header");
    expectError("no_format.ply", "ply\n" + v + "end_header\n0 0 0\n", "format");
    expectError("two_formats.ply", "ply\nformat ascii 1.0\nformat ascii 1.0\n" + v + "end_header\n0 0 0\n", "format");
    expectError("bad_format.ply", "ply\nformat binary_middle_endian 1.0\n" + v + "end_header\n", "format");
    expectError("bad_version.ply", "ply\nformat ascii 2.0\n" + v + "end_header\n0 0 0\n", "version");
    expectError("keyword.ply", "ply\nformat ascii 1.0\nelemnt vertex 1\nend_header\n", "keyword");
    expectError("orphan.ply", "ply\nformat ascii 1.0\nproperty float x\n" + v + "end_header\n", "before any element");
    expectError("bad_type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n", "type");
    expectError("neg_count.ply", "ply\nformat ascii 1.0\nelement vertex -1\nend_header\n", "count");
    expectError("text_count.ply", "ply\nformat ascii 1.0\nelement vertex many\nend_header\n", "count");
    expectError(
        "huge_count_text.ply", "ply\nformat ascii 1.0\nelement vertex 99999999999999999999999\nend_header\n", "count");
    expectError(
        "short_property.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float\nend_header\n", "property");
    expectError("float_list_count.ply",
        "ply\nformat ascii 1.0\n" + v + "element edge 0\nproperty list float int ids\nend_header\n0 0 0\n",
        "count type");
}

TEST_F(PlyReader, MeshDescriptionProblems) {
    const std::string start = "ply\nformat ascii 1.0\n";
    const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
    const std::string face = "element face 0\nproperty list uchar int vertex_indices\n";
    expectError("no_vertex.ply", start + face + "end_header\n", "no vertex element");
    expectError("no_z.ply", start + "element vertex 0\nproperty float x\nproperty float y\nend_header\n", "'z'");
    expectError("list_x.ply",
        start + "element vertex 0\nproperty list uchar float x\nproperty float y\nproperty float z\nend_header\n",
        "scalar");
    expectError("dup_x.ply", start + "element vertex 0\n" + xyz + "property double x\nend_header\n", "duplicate");
    expectError("two_vertex.ply", start + "element vertex 0\n" + xyz + "element vertex 0\n" + xyz + "end_header\n",
        "more than one vertex");
    expectError("half_normal.ply",
        start + "element vertex 0\n" + xyz + "property float nx\nproperty float ny\nend_header\n", "normal");
    expectError(
        "half_uv.ply", start + "element vertex 0\n" + xyz + "property float u\nend_header\n", "texture coordinate");
    expectError("no_indices.ply",
        start + "element vertex 0\n" + xyz + "element face 0\nproperty list uchar int verts\nend_header\n",
        "vertex_indices");
    expectError("scalar_indices.ply",
        start + "element vertex 0\n" + xyz + "element face 0\nproperty int vertex_indices\nend_header\n",
        "must be a list");
    expectError("float_indices.ply",
        start + "element vertex 0\n" + xyz + "element face 0\nproperty list uchar float vertex_indices\nend_header\n",
        "non-integer index type");
    expectError("both_index_names.ply",
        start + "element vertex 0\n" + xyz +
            "element face 0\nproperty list uchar int vertex_indices\nproperty list uchar int "
            "vertex_index\nend_header\n",
        "more than one");
}

TEST_F(PlyReader, HugeCountsInTinyFilesFailBeforeAllocating) {
    const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
    const std::string face = "element face 1\nproperty list uchar int vertex_indices\n";
    for (const std::string format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
        const std::string start = "ply\n" + formatLine(format);
        expectError(
            format + "_vertex.ply", start + "element vertex 4000000000\n" + xyz + "end_header\n0 0 0\n", "truncated");
        expectError(format + "_vertex_max.ply",
            start + "element vertex 18446744073709551615\n" + xyz + "end_header\n0 0 0\n", "too many vertices");
        expectError(format + "_face.ply",
            start + "element vertex 1\n" + xyz + "element face 4000000000\n" +
                "property list uchar int vertex_indices\nend_header\n0 0 0 3 0 0 0\n",
            "truncated");
        expectError(format + "_other.ply",
            start + "element vertex 0\n" + xyz + "element junk 18446744073709551615\nproperty char a\n" +
                "property char b\nend_header\n0 0 0\n",
            "truncated");
    }
}

TEST_F(PlyReader, HugeListLengthsFail) {
    const std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                               "property float y\nproperty float z\nelement face 1\n"
                               "property list uint int vertex_indices\nend_header\n";
    std::string body;
    for (int i = 0; i < 9; ++i) putBinary(body, "float", 0, false);
    std::string huge = body;
    putBinary(huge, "uint", 4000000000.0, false);
    for (int i = 0; i < 3; ++i) putBinary(huge, "int", i, false);
    expectError("huge_list.ply", header + huge, "truncated");

    std::string negative = body;
    putBinary(negative, "int", -1, false);
    std::string signedHeader = header;
    signedHeader.replace(signedHeader.find("list uint"), 9, "list int");
    expectError("negative_list.ply", signedHeader + negative, "negative");

    // The same in an unknown element, which is skipped without reading the items.
    const std::string edgeHeader = "ply\nformat binary_little_endian 1.0\nelement edge 1\n"
                                   "property list uint int ids\nelement vertex 0\nproperty float x\n"
                                   "property float y\nproperty float z\nend_header\n";
    std::string edge;
    putBinary(edge, "uint", 4000000000.0, false);
    putBinary(edge, "int", 0, false);
    expectError("huge_edge_list.ply", edgeHeader + edge, "truncated");

    expectError("huge_ascii_list.ply", squareAscii("4000000000 0 1 2\n"), "out of range");
    expectError("huge_ascii_list_int.ply",
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list int int vertex_indices\nend_header\n0 0 0\n2000000000 0 0 0\n",
        "truncated");
}

TEST_F(PlyReader, TruncatedFilesFail) {
    // Every proper prefix of a binary file is broken somewhere: header, counts or data.
    const std::string binary = fullMeshBinary(false);
    const std::string big = fullMeshBinary(true);
    for (size_t n = 0; n < binary.size(); ++n) expectError("little_prefix.ply", binary.substr(0, n), "");
    for (size_t n = 0; n < big.size(); ++n) expectError("big_prefix.ply", big.substr(0, n), "");
    expectError("little_cut.ply", binary.substr(0, binary.size() - 3), "face 1: unexpected end of file");

    // An ascii prefix may still be a valid file (a cut inside the last number); it must never crash.
    const std::string ascii = fullMeshAscii();
    for (size_t n = 0; n < ascii.size(); ++n) expectNoCrash(ascii.substr(0, n));
    expectError("ascii_cut.ply", ascii.substr(0, ascii.size() - 4), "face 1: unexpected end of file");
    expectError("ascii_cut_vertex.ply", ascii.substr(0, ascii.find("end_header\n") + 11 + 20), "truncated");
}

TEST_F(PlyReader, IndicesOutOfRangeNameTheFace) {
    expectError("index_high.ply", squareAscii("4 0 1 2 4\n"), "face 0: vertex index 4 is out of range");
    expectError("index_negative.ply", squareAscii("3 0 -1 2\n"), "face 0: vertex index -1 is out of range");
    // In binary with unsigned indices, and in a later face.
    std::string ply = fullMeshBinary(false);
    ply.replace(ply.size() - 4, 4, std::string("\xff\xff\xff\x7f", 4)); // last index of face 1 := INT32_MAX
    expectError("index_high_binary.ply", ply, "face 1: vertex index 2147483647 is out of range");
    // Short faces are skipped, but their indices still have to be valid.
    expectError("index_short_face.ply", squareAscii("2 0 9\n"), "out of range");
}

TEST_F(PlyReader, NonFiniteVerticesFail) {
    const std::string header = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                               "property float z\nend_header\n0 0 0\n";
    expectError("inf.ply", header + "0 inf 0\n", "vertex 1: non-finite vertex");
    expectError("nan.ply", header + "nan 0 0\n", "non-finite vertex");
    expectError("neg_inf.ply", header + "0 0 -Infinity\n", "non-finite vertex");
    expectError("float_overflow.ply", header + "0 0 1e39\n", "non-finite vertex"); // finite double, not float
    expectError("double_overflow.ply", header + "0 0 1e999\n", "out of range");

    std::string binary = fullMeshBinary(false);
    const size_t firstY = binary.find("end_header\n") + 11 + 4;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::memcpy(&binary[firstY], &nan, 4);
    expectError("nan_binary.ply", binary, "vertex 0: non-finite vertex position");

    std::string normal = fullMeshBinary(false);
    const float inf = std::numeric_limits<float>::infinity();
    std::memcpy(&normal[firstY + 8], &inf, 4); // vertex 0's nx
    expectError("inf_normal.ply", normal, "non-finite vertex normal");
}

TEST_F(PlyReader, NonNumericAsciiFails) {
    const std::string header = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                               "property float z\nproperty uchar red\nend_header\n";
    expectError("word.ply", header + "0 abc 0 1\n", "expected a number, found 'abc'");
    expectError("suffix.ply", header + "0 1.0f 0 1\n", "expected a number");
    expectError("comma.ply", header + "0,0 0 0 1\n", "expected a number");
    expectError("nul.ply", header + std::string("0 0 0 \0\n", 8), "expected an integer");
    expectError("float_in_int.ply", header + "0 0 0 1.5\n", "expected an integer");
    expectError("uchar_range.ply", header + "0 0 0 256\n", "out of range for type uchar");
    expectError("index_word.ply", squareAscii("4 0 1 two 3\n"), "face 0: expected an integer, found 'two'");
    expectError("trailing.ply", squareAscii("4 0 1 2 3\n3 0 1 2\n"), "after the last element");
}

// Random byte damage to small valid files must give a mesh or a SceneError, nothing else.
TEST_F(PlyReader, FuzzedFilesNeverCrash) {
    std::mt19937 rng(795);
    const std::string seeds[] = {fullMeshAscii(), fullMeshBinary(false), fullMeshBinary(true), meshWithExtras(true)};
    const char kInteresting[] = {'\0', '\n', ' ', '-', '9', 'e', '\x7f', '\x80', '\xff'};
    for (const std::string& seed : seeds) {
        for (int iteration = 0; iteration < 400; ++iteration) {
            std::string bytes = seed;
            const int edits = 1 + static_cast<int>(rng() % 4);
            for (int e = 0; e < edits; ++e) {
                const size_t at = rng() % bytes.size();
                switch (rng() % 4) {
                case 0: bytes[at] = static_cast<char>(rng()); break;
                case 1: bytes[at] = kInteresting[rng() % sizeof(kInteresting)]; break;
                case 2: bytes.erase(at, 1 + rng() % 8); break;
                default: bytes.insert(at, 1, kInteresting[rng() % sizeof(kInteresting)]); break;
                }
                if (bytes.empty()) bytes = "p";
            }
            expectNoCrash(bytes);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Speed: a million triangles in binary must read in well under a second (Release build).

TEST_F(PlyReader, MillionTriangleBinaryIsFast) {
    constexpr uint32_t kSide = 709; // a grid of 709 x 709 vertices: 1,002,528 triangles
    std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(kSide * kSide) +
                      "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                      std::to_string(2 * (kSide - 1) * (kSide - 1)) +
                      "\nproperty list uchar int vertex_indices\nend_header\n";
    static_assert(std::endian::native == std::endian::little, "the fast writer below assumes a little-endian host");
    auto raw = [&](auto v) { ply.append(reinterpret_cast<const char*>(&v), sizeof(v)); };
    for (uint32_t y = 0; y < kSide; ++y)
        for (uint32_t x = 0; x < kSide; ++x) {
            raw(static_cast<float>(x));
            raw(static_cast<float>(y));
            raw(0.0f);
        }
    for (uint32_t y = 0; y + 1 < kSide; ++y)
        for (uint32_t x = 0; x + 1 < kSide; ++x) {
            const int32_t v = static_cast<int32_t>(y * kSide + x);
            const int32_t up = v + static_cast<int32_t>(kSide);
            for (const glm::ivec3 t : {glm::ivec3(v, v + 1, up + 1), glm::ivec3(v, up + 1, up)}) {
                raw(uint8_t{3});
                raw(t.x);
                raw(t.y);
                raw(t.z);
            }
        }
    const fs::path path = write("million.ply", ply);

    const auto start = std::chrono::steady_clock::now();
    const pt::PlyMesh m = pt::readPly(path);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("[ timing   ] %zu triangles, %zu bytes read in %.3f s\n", m.triangles.size(), ply.size(), seconds);

    ASSERT_EQ(m.triangles.size(), 2u * (kSide - 1) * (kSide - 1));
    ASSERT_GE(m.triangles.size(), 1000000u);
    EXPECT_EQ(m.positions.back(), glm::vec3(kSide - 1, kSide - 1, 0));
    EXPECT_EQ(m.triangles.back(), glm::uvec3(kSide * kSide - kSide - 2, kSide * kSide - 1, kSide * kSide - 2));
    // Generous, so that slow CI machines and debug builds pass; a hang or quadratic behaviour won't.
    EXPECT_LT(seconds, 5.0);
}

} // namespace
