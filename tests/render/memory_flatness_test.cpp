// No leaks on the long-render path: hundreds of passes of a textured scene, each followed by a
// readback and every few by a checkpoint written to disk, leave the resident set where it was
// after warm-up. (The first seed's leak grew to 29 GB over a long render.) The full curve of a
// 10,000-spp render is bench/bench_memory.sh's, recorded in bench/RESULTS.md.
#include "render/checkpoint.h"
#include "scene/gltf/gltf_loader.h"
#include "support/gpu_test_support.h"

#include <unistd.h>

#include <fstream>
#include <string>

namespace pt::test {
namespace {

long residentKiB() {
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
        if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
    return -1;
}

class MemoryFlatness : public GpuTest {};

TEST_F(MemoryFlatness, ResidentSetStaysFlatOverManyPasses) {
    Scene scene = loadGltfFile(
        testDataDir() / "data" / "gltf_samples" / "TextureSettingsTest" / "glTF" / "TextureSettingsTest.gltf");
    Environment sky; // the sample has no light of its own
    sky.colour = glm::vec3(1.0f);
    scene.environment = sky;
    const FlatScene flat = flattenScene(scene);
    IntegratorSettings settings;
    settings.maxDepth = 4;
    Camera camera; // the sample has no camera: look at its panels (around the origin) from +z
    camera.position = glm::vec3(0.0f, 0.0f, 30.0f);
    Renderer renderer(
        sharedContext(), flat, suiteFeatures(flat, settings), settings, camera, FilmSettings{24, 24, scene.background});
    const auto dir = std::filesystem::temp_directory_path() / ("pt_memory_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    Checkpointer checkpointer(dir / "ckpt.exr", 0.0, {}, 0.0);
    long afterWarmUp = 0;
    constexpr int kPasses = 500, kWarmUp = 50;
    for (int pass = 1; pass <= kPasses; ++pass) {
        renderer.addSamples(1);
        (void)renderer.read();
        if (pass % 10 == 0) checkpointer.save(renderer, pass);
        if (pass == kWarmUp) afterWarmUp = residentKiB();
    }
    const long atEnd = residentKiB();
    std::filesystem::remove_all(dir);
    ASSERT_GT(afterWarmUp, 0) << "no VmRSS in /proc/self/status";
    // 450 passes: 1 MiB of growth would be a leak of over 2 KiB per pass.
    EXPECT_LT(atEnd - afterWarmUp, 1024) << "RSS grew from " << afterWarmUp << " KiB after " << kWarmUp << " passes to "
                                         << atEnd << " KiB after " << kPasses;
}

} // namespace
} // namespace pt::test
