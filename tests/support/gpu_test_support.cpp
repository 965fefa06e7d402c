#include "support/gpu_test_support.h"

#include "gpu/compute_pipeline.h"
#include "pt_test_kernels_spv.h"
#include "flatten/feature_set.h"
#include "render/texel_load_choice.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <numeric>
#include <optional>

namespace pt::test {

VulkanContext& sharedContext() {
    static std::unique_ptr<VulkanContext> context = [] {
        ContextOptions options;
        options.validation = true;
#ifdef PT_TEST_PIPELINE_CACHE
        options.pipelineCacheDirectory = PT_TEST_PIPELINE_CACHE;
#endif
        return std::make_unique<VulkanContext>(options);
    }();
    return *context;
}

void GpuTest::SetUp() { messagesBefore_ = sharedContext().validationMessageCount(); }

void GpuTest::TearDown() {
    EXPECT_EQ(sharedContext().validationMessageCount(), messagesBefore_)
        << "Vulkan validation: " << sharedContext().firstValidationMessage();
}

namespace {
bool testKernelTexelLoads = false;
}

void setTestKernelTexelLoads(bool on) { testKernelTexelLoads = on; }

std::vector<glm::vec4> runTestKernel(uint32_t mode, uint32_t count, const GpuScene* scene,
    std::span<const std::byte> inputs, glm::vec3 point, glm::vec3 normal, uint32_t seed, uint32_t materialIndex) {
    VulkanContext& ctx = sharedContext();
    // One pipeline per mode and load path, specialised to them: a process compiles only the code
    // of the modes it runs.
    static std::map<std::pair<uint32_t, bool>, std::unique_ptr<ComputePipeline>> pipelines;
    std::unique_ptr<ComputePipeline>& pipeline = pipelines[{mode, testKernelTexelLoads}];
    if (!pipeline) {
        FeatureSet features = FeatureSet::all(IntegratorSettings{});
        features.texelLoads = testKernelTexelLoads;
        std::vector<SpecializationConstant> constants = features.constants(8, 8);
        constants.push_back({TEST_MODE_CONSTANT_ID, mode});
        pipeline = std::make_unique<ComputePipeline>(ctx, std::span<const uint32_t>(pt_test_kernels_spv),
            static_cast<uint32_t>(sizeof(gpu::GpuTestPush)), constants, "test kernels");
    }
    GpuBuffer input(ctx, std::max<size_t>(inputs.size(), 16), "test input");
    input.upload(inputs.data(), inputs.size());
    // Two vec4 per item: most modes write only the first half (BSDF sampling writes both).
    GpuBuffer output(ctx, sizeof(glm::vec4) * count * 2, "test output");
    gpu::GpuTestPush push{};
    push.sceneParams = scene ? scene->paramsAddress() : 0;
    push.inputs = inputs.empty() ? 0 : input.address(); // 0: the kernel draws its own numbers
    push.outputs = output.address();
    push.mode = mode;
    push.count = count;
    push.point = point;
    push.normal = normal;
    push.materialIndex = materialIndex;
    push.seed = seed;
    // The previous dispatch has finished (submitAndWait), so the set may change.
    pipeline->setTexelBuffers(scene ? scene->texelBuffers() : TexelBuffers{});
    ctx.submitAndWait([&](VkCommandBuffer cmd) {
        pipeline->bindAndPush(cmd, &push, sizeof(push));
        vkCmdDispatch(cmd, (count + 63) / 64, 1, 1);
        VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
        barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0,
            nullptr, 0, nullptr);
    });
    std::vector<glm::vec4> result(mode == TEST_MODE_BSDF_SAMPLE ? 2 * count : count);
    output.download(result.data(), sizeof(glm::vec4) * result.size());
    return result;
}

Mesh makeIcosphere(int subdivisions, glm::vec3 centre, float radius, uint32_t material) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    std::vector<glm::vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t}, {0, -1, -t},
        {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    std::vector<glm::uvec3> f = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
        {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9}, {4, 9, 5},
        {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    for (auto& p : v) p = glm::normalize(p);
    for (int s = 0; s < subdivisions; ++s) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            auto key = std::minmax(a, b);
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            v.push_back(glm::normalize(v[a] + v[b]));
            return mid[key] = static_cast<uint32_t>(v.size() - 1);
        };
        std::vector<glm::uvec3> next;
        for (auto tri : f) {
            uint32_t a = midpoint(tri.x, tri.y), b = midpoint(tri.y, tri.z), c = midpoint(tri.z, tri.x);
            next.push_back({tri.x, a, c});
            next.push_back({tri.y, b, a});
            next.push_back({tri.z, c, b});
            next.push_back({a, b, c});
        }
        f = next;
    }
    Mesh m;
    m.name = "icosphere";
    for (auto& p : v) m.positions.push_back(centre + radius * p);
    m.triangles = f;
    m.material = material;
    return m;
}

Mesh makeQuad(glm::vec3 corner, glm::vec3 edgeU, glm::vec3 edgeV, uint32_t material) {
    Mesh m;
    m.name = "quad";
    m.positions = {corner, corner + edgeU, corner + edgeU + edgeV, corner + edgeV};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    m.material = material;
    return m;
}

bool suiteTexelLoads() {
    // Nothing chosen (no texel views, or not a CPU device): the renderer decides as it would.
    static const bool texel = [] {
        const std::optional<TexelLoadChoice> choice = chooseTexelLoads(sharedContext());
        if (choice) std::printf("%s\n", describeTexelLoadChoice(*choice).c_str());
        return !choice || choice->texelLoads;
    }();
    return texel;
}

namespace {
FeatureSet withSuiteLoads(FeatureSet features) {
    features.texelLoads = features.texelLoads && suiteTexelLoads();
    return features;
}
} // namespace

FeatureSet suiteFeatures(const FlatScene& flat, const IntegratorSettings& settings) {
    return withSuiteLoads(computeFeatures(flat, settings));
}

IntegratorSettings independentSettings() {
    IntegratorSettings s;
    s.sampler = SamplerKind::Independent;
    return s;
}

Renderer::Readback renderScene(const Scene& scene, const IntegratorSettings& settings, const Camera& camera, int width,
    int height, uint32_t spp, uint32_t passSpp, uint32_t tileSize, const BvhBuildOptions& bvh) {
    FlatScene flat = flattenScene(scene, bvh);
    Renderer renderer(sharedContext(), flat, suiteFeatures(flat, settings), settings, camera,
        FilmSettings{width, height, scene.background});
    const uint32_t pass = passSpp ? passSpp : spp;
    while (renderer.samplesPerPixel() < spp)
        renderer.addSamples(std::min(pass, spp - renderer.samplesPerPixel()), tileSize);
    return renderer.read();
}

Renderer::Readback renderSceneWith(const Scene& scene, const IntegratorSettings& settings, const FeatureSet& features,
    const Camera& camera, int width, int height, uint32_t spp) {
    FlatScene flat = flattenScene(scene);
    Renderer renderer(sharedContext(), flat, withSuiteLoads(features), settings, camera,
        FilmSettings{width, height, scene.background});
    renderer.addSamples(spp, 0);
    return renderer.read();
}

void expectTheSameImageHoweverSplit(const Scene& scene, const IntegratorSettings& settings, uint32_t spp) {
    const Camera& camera = scene.cameras.at(0);
    const Renderer::Readback whole = renderScene(scene, settings, camera, 40, 40, spp);
    const Renderer::Readback split = renderScene(scene, settings, camera, 40, 40, spp, 3, 16);
    ASSERT_EQ(whole.mean.rgba.size(), split.mean.rgba.size());
    EXPECT_EQ(0, std::memcmp(whole.mean.rgba.data(), split.mean.rgba.data(), whole.mean.rgba.size() * sizeof(float)));
    IntegratorSettings other = settings;
    other.seed = 7;
    const Renderer::Readback reseeded = renderScene(scene, other, camera, 40, 40, spp);
    EXPECT_NE(0, std::memcmp(whole.mean.rgba.data(), reseeded.mean.rgba.data(), whole.mean.rgba.size() * sizeof(float)))
        << "the comparison can tell images apart";
}

std::filesystem::path testDataDir() { return PT_TEST_DATA_DIR; }

double gammaQ(double a, double x) {
    if (x <= 0) return 1.0;
    const double lga = std::lgamma(a);
    if (x < a + 1) {
        // Series for P(a, x).
        double sum = 1.0 / a, term = sum;
        for (int n = 1; n < 10000; ++n) {
            term *= x / (a + n);
            sum += term;
            if (std::abs(term) < std::abs(sum) * 1e-15) break;
        }
        return 1.0 - sum * std::exp(-x + a * std::log(x) - lga);
    }
    // Continued fraction for Q(a, x) (modified Lentz).
    double b = x + 1 - a, c = 1e300, d = 1 / b, h = d;
    for (int i = 1; i < 10000; ++i) {
        const double an = -i * (i - a);
        b += 2;
        d = an * d + b;
        if (std::abs(d) < 1e-300) d = 1e-300;
        c = b + an / c;
        if (std::abs(c) < 1e-300) c = 1e-300;
        d = 1 / d;
        const double delta = d * c;
        h *= delta;
        if (std::abs(delta - 1) < 1e-15) break;
    }
    return std::exp(-x + a * std::log(x) - lga) * h;
}

double chiSquarePValue(std::span<const double> observed, std::span<const double> expected, int* dofOut) {
    // Sort bins by expected count and pool the small ones until the pool reaches 5.
    std::vector<size_t> order(expected.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return expected[a] < expected[b]; });
    double pooledObs = 0, pooledExp = 0, chi2 = 0;
    int bins = 0;
    for (size_t i : order) {
        if (expected[i] == 0) {
            if (observed[i] > 0) return 0.0; // samples where the pdf says none can be
            continue;
        }
        if (pooledExp > 0 || expected[i] < 5) {
            pooledObs += observed[i];
            pooledExp += expected[i];
            if (pooledExp >= 5) {
                chi2 += (pooledObs - pooledExp) * (pooledObs - pooledExp) / pooledExp;
                pooledObs = pooledExp = 0;
                ++bins;
            }
            continue;
        }
        chi2 += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
        ++bins;
    }
    if (pooledExp > 0) {
        chi2 += (pooledObs - pooledExp) * (pooledObs - pooledExp) / pooledExp;
        ++bins;
    }
    const int dof = std::max(1, bins - 1);
    if (dofOut) *dofOut = dof;
    return gammaQ(dof / 2.0, chi2 / 2.0);
}

} // namespace pt::test
