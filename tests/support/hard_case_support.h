#pragma once
// Helpers for the hard-case suite (hard_cases_*test.cpp in tests/shaders/geometry/ and
// tests/shaders/integrator/): the scene files of scenes/hard/, renders with the kernel's random
// numbers pinned to the ends of their range, image statistics with their Monte Carlo error, and
// scenes moved to another scale or place.
#include "support/gpu_test_support.h"

#include <functional>

namespace pt::test {

// The fixture of every hard-case test, whichever folder it is in.
class HardCases : public GpuTest {};

// Every hard-case render runs three times: with the normal sampler, and with every random
// number forced to 0 and to 1 - 2^-24 (FORCED_RANDOM_*, shaders/common/rng.glsl).
constexpr uint32_t kForcedModes[] = {FORCED_RANDOM_ZERO, FORCED_RANDOM_ONE};

// renderScene with the kernel's random numbers forced (FORCED_RANDOM_OFF: the normal sampler).
Renderer::Readback renderForced(const Scene& scene, const IntegratorSettings& settings, const Camera& camera, int width,
    int height, uint32_t spp, uint32_t forcedRandom);

// renderForced in both forced modes (1 spp each; by BDPT as well where it can render the scene)
// and with the normal sampler (`spp`), every render expected to keep all its samples; returns
// the normal render. `what` names the case.
Renderer::Readback renderAllModes(const Scene& scene, const IntegratorSettings& settings, const Camera& camera,
    int size, uint32_t spp, const char* what);

// Mean of channel `channel` over the pixels `use` accepts (all when empty) and its standard
// error from the per-pixel variance of the mean.
struct ImageStats {
    double mean = 0;
    double standardError = 0;
    double lowest = 0, highest = 0;
    size_t pixels = 0;
};
ImageStats imageStats(const Renderer::Readback& r, int channel = 0, const std::function<bool(int x, int y)>& use = {});

// The scene and its cameras mapped by x -> scale * x + offset (radiance is unchanged by it).
Scene scaledScene(Scene scene, float scale, glm::vec3 offset);

// The scene with every mesh kept once, where it is, and placed by `map` (an instance each), so
// that the world holds map(scene): spheres, lights and cameras are mapped too. `map` is a
// rotation, a uniform scale (mirrored or not) and a translation.
Scene placedAsInstances(Scene scene, const glm::mat4& map);

// Flattening that keeps every instance an instance (never copied into world space).
BvhBuildOptions keepInstances();

// A camera at `from` looking at `to`.
Camera lookAt(glm::vec3 from, glm::vec3 to, float yfov, glm::vec3 up = glm::vec3(0, 1, 0));

// The world-space direction of the ray through image point (x, y) (pixel units, (0, 0) the
// top-left corner), as the kernel's pinhole camera makes it.
glm::vec3 pixelDirection(const gpu::GpuCamera& c, int width, int height, double x, double y);

// A scene file of scenes/hard/.
std::filesystem::path hardScenePath(const char* fileName);

// Loads scenes/hard/FILE and checks that what the file says about rendering agrees with the
// test's settings `s` (a course camera's RendererParams, a depth from MaxRecursionDepth or glTF
// extras.max_depth), so that `pt render scenes/hard/FILE` renders what the test checks.
Scene loadHardScene(const char* file, const IntegratorSettings& s);

} // namespace pt::test
