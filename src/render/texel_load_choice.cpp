#include "render/texel_load_choice.h"

#include "base/hash.h"
#include "flatten/feature_set.h"
#include "flatten/flat_scene.h"
#include "gpu/shader_cache_directory.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <string>
#include <thread>

namespace pt {

namespace {
// Passes of 96x96 pixels at 8 samples: 40-100 ms each on two cores, long enough for the clock's
// resolution and short enough that five rounds of both take about a second once compiled.
constexpr int kSide = 96;
constexpr uint32_t kPassSpp = 8;
constexpr int kRounds = 5;
constexpr const char* kEntry = "texel-loads";
// Bump when the measurement changes, so that older answers are measured again.
constexpr uint32_t kChoiceVersion = 1;

// What the CPU is, as the kernel's speed could depend on it: the first processor's identity and
// feature flags in /proc/cpuinfo (empty elsewhere) and how many threads the machine runs.
std::string cpuIdentity() {
    std::ifstream in("/proc/cpuinfo");
    std::string line, identity;
    while (std::getline(in, line)) {
        if (line.empty()) break; // the first processor's block ends here
        for (const char* field : {"vendor_id", "cpu family", "model", "stepping", "flags"})
            if (line.rfind(field, 0) == 0) identity += line + "\n";
    }
    return identity + std::to_string(std::thread::hardware_concurrency());
}

// Everything the answer depends on: the CPU, the driver (its version and build), the lavapipe
// settings in force (thread count, instruction set) and the kernels' code.
uint64_t choiceKey(const VulkanContext& context) {
    const VkPhysicalDeviceProperties& p = context.properties();
    uint64_t key = fnv1a64(&kChoiceVersion, sizeof kChoiceVersion);
    key = fnv1a64(&p.driverVersion, sizeof p.driverVersion, key);
    key = fnv1a64(p.pipelineCacheUUID, VK_UUID_SIZE, key);
    std::string text = cpuIdentity() + "\n" + context.info().name + "\n" + context.info().driver + "\n";
    for (const char* variable :
        {"LP_NUM_THREADS", "GALLIUM_OVERRIDE_CPU_CAPS", "LP_NATIVE_VECTOR_WIDTH", "GALLIVM_PERF"})
        if (const char* value = std::getenv(variable)) text += std::string(variable) + "=" + value + "\n";
    key = fnv1a64(text.data(), text.size(), key);
    const uint64_t kernels = renderKernelFingerprint();
    return fnv1a64(&kernels, sizeof kernels, key);
}

double secondsOfPass(Renderer& renderer) {
    const auto start = std::chrono::steady_clock::now();
    renderer.addSamples(kPassSpp);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The built-in Cornell box both ways, alternating (the order swapped each round, as the machine's
// speed drifts); the fastest pass of each. Nothing when the device gives the kernel no texel views.
std::optional<TexelLoadChoice> measure(VulkanContext& context) {
    const Scene scene = loadScene("");
    const FlatScene flat = flattenScene(scene);
    IntegratorSettings settings;
    settings.estimator = Estimator::Path;
    FeatureSet texelFeatures = computeFeatures(flat, settings);
    texelFeatures.lightTracing = texelFeatures.bdpt = texelFeatures.merging = false;
    FeatureSet addressFeatures = texelFeatures;
    addressFeatures.texelLoads = false;
    const FilmSettings film{kSide, kSide, glm::vec3(0.0f)};
    Renderer texel(context, flat, texelFeatures, settings, scene.cameras.at(0), film);
    if (!texel.features().texelLoads) return std::nullopt;
    Renderer address(context, flat, addressFeatures, settings, scene.cameras.at(0), film);
    // The first dispatch of each pays the driver's compile.
    texel.addSamples(1);
    address.addSamples(1);
    TexelLoadChoice choice;
    choice.texelSeconds = choice.addressSeconds = std::numeric_limits<double>::max();
    for (int round = 0; round < kRounds; ++round) {
        const bool texelFirst = round % 2 == 0;
        const double first = secondsOfPass(texelFirst ? texel : address);
        const double second = secondsOfPass(texelFirst ? address : texel);
        choice.texelSeconds = std::min(choice.texelSeconds, texelFirst ? first : second);
        choice.addressSeconds = std::min(choice.addressSeconds, texelFirst ? second : first);
    }
    choice.texelLoads = choice.texelSeconds <= choice.addressSeconds;
    choice.measuredNow = true;
    return choice;
}

// The remembered answer: a version, the choice and both times, as text.
std::string encode(const TexelLoadChoice& c) {
    char text[96];
    std::snprintf(
        text, sizeof text, "%u %d %.9g %.9g", kChoiceVersion, c.texelLoads ? 1 : 0, c.texelSeconds, c.addressSeconds);
    return text;
}

std::optional<TexelLoadChoice> decode(const std::vector<uint8_t>& payload) {
    const std::string text(payload.begin(), payload.end());
    unsigned version = 0;
    int texelLoads = 0;
    TexelLoadChoice c;
    if (std::sscanf(text.c_str(), "%u %d %lg %lg", &version, &texelLoads, &c.texelSeconds, &c.addressSeconds) != 4 ||
        version != kChoiceVersion || (texelLoads != 0 && texelLoads != 1))
        return std::nullopt;
    c.texelLoads = texelLoads == 1;
    return c;
}
} // namespace

std::optional<TexelLoadChoice> chooseTexelLoads(VulkanContext& context) {
    if (context.properties().deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU) return std::nullopt;
    // No folder, or one that cannot be made (the pipeline cache warns about that): measuring on
    // every run would cost more than it saves.
    const std::filesystem::path folder = context.pipelineCache().directory();
    if (folder.empty()) return std::nullopt;
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    if (!std::filesystem::is_directory(folder, ec)) return std::nullopt;
    ShaderCacheDirectory cache(folder);
    const uint64_t key = choiceKey(context);
    if (auto payload = cache.read(kEntry, key))
        if (auto remembered = decode(*payload)) return remembered;
    std::optional<TexelLoadChoice> measured = measure(context);
    if (measured) {
        const std::string text = encode(*measured);
        cache.write(kEntry, key, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()));
    }
    return measured;
}

std::string describeTexelLoadChoice(const TexelLoadChoice& c) {
    char text[256];
    std::snprintf(text, sizeof text,
        "geometry loads: %s (%s on this machine: a pass of the built-in Cornell box %.1f ms through texel buffers, "
        "%.1f ms through buffer addresses; --texel-loads on|off chooses)",
        c.texelLoads ? "texel buffers" : "buffer addresses", c.measuredNow ? "measured now" : "measured earlier",
        1e3 * c.texelSeconds, 1e3 * c.addressSeconds);
    return text;
}

} // namespace pt
