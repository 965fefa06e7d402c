// pt render and memory: a scene too big for the memory it may use is refused before it is
// allocated, with one line naming the file, the need and the limit (exit 1: never a
// std::bad_alloc text or a killed process), and every render reports its peak resident memory.
// The limit is set with `ulimit -v` (the address-space limit, which pt reads as a headroom like
// a cgroup's), so the tests behave the same on a machine of any size.
#include "cli_fixture.h"

#include <cstdint>
#include <fstream>
#include <regex>
#include <sstream>

namespace pt::test {
namespace {

constexpr uint64_t kLimitKiB = 4u << 20; // 4 GiB of address space

// pt with `args`, under `ulimit -v limitKiB`.
PtRun runLimited(const fs::path& dir, const fs::path& capture, const std::vector<std::string>& args) {
    std::vector<std::string> argv = {
        "bash", "-c", "ulimit -v " + std::to_string(kLimitKiB) + " && exec \"$0\" \"$@\"", PT_BINARY};
    argv.insert(argv.end(), args.begin(), args.end());
    RunOptions options;
    options.dir = dir;
    options.stdoutFile = capture / "stdout";
    options.stderrFile = capture / "stderr";
    options.timeoutSeconds = 60;
    return runProcess(argv, options);
}

// A glTF scene of one mesh of `triangles` triangles (non-indexed) placed by `nodes` nodes.
void writeInstancedGltf(const fs::path& gltf, int triangles, int nodes) {
    std::vector<float> positions;
    for (int t = 0; t < triangles; ++t) {
        const float x = float(t % 100), y = float(t / 100);
        for (float v : {x, y, 0.0f, x + 1, y, 0.0f, x, y + 1, 0.0f}) positions.push_back(v);
    }
    const size_t bytes = positions.size() * sizeof(float);
    std::ofstream(gltf.parent_path() / "mesh.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(positions.data()), std::streamsize(bytes));
    std::ostringstream s;
    s << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [)";
    for (int n = 0; n < nodes; ++n) s << (n ? "," : "") << n;
    s << R"(]}], "nodes": [)";
    for (int n = 0; n < nodes; ++n) s << (n ? "," : "") << R"({"mesh": 0, "translation": [0, 0, )" << -n << "]}";
    s << R"(], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": )"
      << 3 * triangles << R"(, "type": "VEC3", "min": [0, 0, 0], "max": [100, 100, 0]}],
  "bufferViews": [{"buffer": 0, "byteLength": )"
      << bytes << R"(}], "buffers": [{"uri": "mesh.bin", "byteLength": )" << bytes << "}]}";
    std::ofstream(gltf) << s.str();
}

// A course scene of one Mesh of `triangles` triangles and `instances` MeshInstances of it.
void writeInstancedCourseScene(const fs::path& xml, int triangles, int instances) {
    std::ostringstream s;
    s << R"(<Scene><MaxRecursionDepth>4</MaxRecursionDepth><Cameras><Camera id="1"><Position>0 0 5</Position>)"
      << R"(<Gaze>0 0 -1</Gaze><Up>0 1 0</Up><NearPlane>-1 1 -1 1</NearPlane><NearDistance>1</NearDistance>)"
      << R"(<ImageResolution>8 8</ImageResolution><ImageName>x.png</ImageName></Camera></Cameras>)"
      << R"(<Lights><PointLight id="1"><Position>0 4 0</Position><Intensity>100 100 100</Intensity></PointLight>)"
      << R"(</Lights><Materials><Material id="1"><DiffuseReflectance>0.5 0.5 0.5</DiffuseReflectance></Material>)"
      << R"(</Materials><Transformations><Translation id="1">0 0 -1</Translation></Transformations><VertexData>)";
    for (int t = 0; t < triangles; ++t) s << t << " 0 0 " << t + 1 << " 0 0 " << t << " 1 0\n";
    s << R"(</VertexData><Objects><Mesh id="1"><Material>1</Material><Faces>)";
    for (int t = 0; t < triangles; ++t) s << 3 * t + 1 << " " << 3 * t + 2 << " " << 3 * t + 3 << "\n";
    s << "</Faces></Mesh>";
    for (int i = 0; i < instances; ++i)
        s << R"(<MeshInstance id=")" << i + 2 << R"(" baseMeshId="1"><Material>1</Material>)"
          << R"(<Transformations>t1</Transformations></MeshInstance>)";
    s << "</Objects></Scene>";
    std::ofstream(xml) << s.str();
}

// The one error line of a refused scene: the file, "needs about", the triangle count, the limit.
void expectRefusedForMemory(const PtRun& r, const std::string& file, const std::string& triangles) {
    EXPECT_EXIT_STATUS(r, 1);
    const std::string line = r.errorLine();
    EXPECT_NE(line.find(file), std::string::npos) << line;
    EXPECT_NE(line.find("needs about"), std::string::npos) << line;
    EXPECT_NE(line.find(triangles + " triangles"), std::string::npos) << line;
    EXPECT_NE(line.find("ulimit -v"), std::string::npos) << "should name the limit: " << line;
    EXPECT_EQ(line.find("bad_alloc"), std::string::npos) << line;
    EXPECT_LT(r.seconds, 20.0) << "refused before copying the instances: " << r;
    std::printf("[          ] %s\n", line.c_str());
}

// 20,000 triangles placed by 5,000 nodes: 100 M triangles, about 30 GB copied into world space.
// Kept as instances, the mesh is stored once and the scene renders under a 4 GiB limit; asked to
// copy them, pt refuses before copying.
TEST_F(CliTest, HundredMillionTrianglesOfInstancesRenderAndTheirCopiesAreRefused) {
    const fs::path scene = dir_ / "forest.gltf";
    writeInstancedGltf(scene, 20000, 5000);
    const PtRun kept =
        runLimited(dir_, captureDir_, {"render", scene.string(), "--spp", "1", "--width", "64", "-o", "x.exr"});
    EXPECT_EXIT_STATUS(kept, 0);
    EXPECT_NE(kept.err.find("5000 instances of 1 meshes kept as instances"), std::string::npos) << kept.err;
    EXPECT_TRUE(fs::exists(dir_ / "x.exr"));
    const PtRun copied =
        runLimited(dir_, captureDir_, {"render", scene.string(), "--spp", "1", "--instances", "expand", "-o", "y.exr"});
    expectRefusedForMemory(copied, scene.string(), "100000000");
    EXPECT_NE(copied.errorLine().find("instances copied into world space"), std::string::npos) << copied.errorLine();
    EXPECT_FALSE(fs::exists(dir_ / "y.exr"));
}

TEST_F(CliTest, CourseMeshInstancesRenderAsInstancesAndTheirCopiesAreRefused) {
    const fs::path scene = dir_ / "crowd.xml";
    writeInstancedCourseScene(scene, 20000, 5000); // 20,000 x 5,001 triangles
    const PtRun kept =
        runLimited(dir_, captureDir_, {"render", scene.string(), "--spp", "1", "--width", "64", "-o", "x.exr"});
    EXPECT_EXIT_STATUS(kept, 0);
    EXPECT_NE(kept.err.find("5001 instances of 1 meshes kept as instances"), std::string::npos) << kept.err;
    const PtRun copied =
        runLimited(dir_, captureDir_, {"render", scene.string(), "--spp", "1", "--instances", "expand", "-o", "y.exr"});
    expectRefusedForMemory(copied, scene.string(), "100020000");
    EXPECT_NE(copied.errorLine().find("instances copied into world space"), std::string::npos) << copied.errorLine();
}

// The same scene, small enough, renders under the same limit: the estimate does not refuse
// what fits.
TEST_F(CliTest, InstancedGltfThatFitsRendersUnderTheSameLimit) {
    const fs::path scene = dir_ / "grove.gltf";
    writeInstancedGltf(scene, 2000, 20);
    const PtRun r = runLimited(dir_, captureDir_, {"render", scene.string(), "--spp", "1", "-q", "-o", "x.exr"});
    EXPECT_EXIT_STATUS(r, 0);
    EXPECT_TRUE(fs::exists(dir_ / "x.exr"));
}

// The image's accumulation buffer counts too: the built-in scene at 8192 x 8192 needs more than
// 4 GiB of device memory, which on lavapipe is host memory, so the device check refuses it.
TEST_F(CliTest, ImageTooBigForTheDeviceMemoryIsRefusedWithItsNeed) {
    const PtRun r =
        runLimited(dir_, captureDir_, {"render", "--spp", "1", "--width", "8192", "--height", "8192", "-o", "x.exr"});
    EXPECT_EXIT_STATUS(r, 1);
    const std::string line = r.errorLine();
    EXPECT_NE(line.find("of device memory"), std::string::npos) << line;
    EXPECT_NE(line.find("image "), std::string::npos) << "should say what needs it: " << line;
    std::printf("[          ] %s\n", line.c_str());
    EXPECT_EQ(line.find("bad_alloc"), std::string::npos) << line;
    EXPECT_FALSE(fs::exists(dir_ / "x.exr"));
}

TEST_F(CliTest, SummaryLineReportsThePeakResidentMemory) {
    const PtRun r = run({"render", "--spp", "1", "--width", "64", "-q", "-o", (dir_ / "x.exr").string()});
    EXPECT_EXIT_STATUS(r, 0);
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.err, m, std::regex("peak memory ([0-9.]+) (kB|MB|GB)"))) << r.err;
    const double value = std::stod(m[1]) * (m[2] == "GB" ? 1e9 : m[2] == "MB" ? 1e6 : 1e3);
    EXPECT_GT(value, 10e6) << "a Vulkan process holds more than 10 MB: " << m[0];
    EXPECT_LT(value, 4e9) << m[0];
}

} // namespace
} // namespace pt::test
