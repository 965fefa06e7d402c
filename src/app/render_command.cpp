#include "app/render_command.h"

#include "gpu/vulkan_context.h"
#include "render/feature_set.h"
#include "render/flat_scene.h"
#include "render/image_io.h"
#include "render/metrics.h"
#include "render/progress.h"
#include "render/renderer.h"
#include "scene/scene_loader.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace pt {
namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::string joinNotes(const std::vector<std::string>& notes) {
    std::string s;
    for (const auto& n : notes) s += (s.empty() ? "" : "; ") + n;
    return s;
}

std::string formatDouble(double v) {
    std::ostringstream s;
    s.precision(9);
    s << v;
    return s.str();
}

std::filesystem::path defaultOutput(const std::string& scene) {
    std::string stem = scene.empty() ? "cornell-box" : std::filesystem::path(scene).stem().string();
    if (stem == "scene") stem = std::filesystem::path(scene).parent_path().filename().string(); // refs/<name>/scene.gltf
    if (stem.empty()) stem = "render";
    return std::filesystem::path("out") / (stem + ".exr");
}

// Image size: command line, then the scene's own hints, then 512 wide with the camera's aspect.
void chooseResolution(const RenderOptions& o, const Scene& scene, const Camera& camera, int& width, int& height) {
    width = o.width.value_or(scene.hints.width.value_or(512));
    if (o.height) height = *o.height;
    else if (scene.hints.height && !o.width) height = *scene.hints.height;
    else if (camera.aspectRatio > 0) height = std::max(1, static_cast<int>(std::lround(width / camera.aspectRatio)));
    else height = width;
}

Camera chooseCamera(const Scene& scene, int index) {
    if (scene.cameras.empty()) {
        if (index != 0) throw std::runtime_error(scene.source + ": --camera " + std::to_string(index) + ": the scene has no cameras");
        // No camera in the file: look at the scene's bounding box from +z.
        glm::vec3 lo(INFINITY), hi(-INFINITY);
        for (const auto& m : scene.meshes)
            for (const auto& p : m.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
        Camera c;
        c.yfov = 0.8f;
        const glm::vec3 centre = 0.5f * (lo + hi);
        const float radius = 0.5f * glm::length(hi - lo);
        c.position = centre + glm::vec3(0, 0, radius / std::tan(0.5f * c.yfov) + radius);
        std::fprintf(stderr, "pt: note: %s has no camera; using one that frames the scene\n", scene.source.c_str());
        return c;
    }
    if (index < 0 || index >= static_cast<int>(scene.cameras.size()))
        throw std::runtime_error(scene.source + ": --camera " + std::to_string(index) + " is out of range (the scene has " +
                                 std::to_string(scene.cameras.size()) + " camera(s))");
    return scene.cameras[index];
}

} // namespace

int runRender(const RenderOptions& o) {
    const auto loadStart = Clock::now();
    Scene scene = loadScene(o.scene);
    if (!scene.unsupported.empty())
        std::fprintf(stderr, "pt: warning: %s: not supported yet, rendered approximately: %s\n", scene.source.c_str(),
            joinNotes(scene.unsupported).c_str());
    const Camera camera = chooseCamera(scene, o.camera);
    int width, height;
    chooseResolution(o, scene, camera, width, height);
    validateImageSize(width, height);

    IntegratorSettings settings = o.integrator;
    settings.maxDepth = o.maxDepth.value_or(scene.hints.maxDepth ? static_cast<uint32_t>(*scene.hints.maxDepth) : settings.maxDepth);
    if (settings.maxDepth < 1) throw std::runtime_error("--max-depth must be at least 1");

    // Fail on a bad reference or output path before spending time on rendering.
    std::optional<Image> reference;
    if (!o.reference.empty()) {
        reference = readExr(o.reference);
        if (reference->width != width || reference->height != height)
            throw std::runtime_error(o.reference + ": reference is " + std::to_string(reference->width) + "x" +
                                     std::to_string(reference->height) + " but the render is " + std::to_string(width) +
                                     "x" + std::to_string(height));
    }
    const std::filesystem::path output = o.output.empty() ? defaultOutput(o.scene) : std::filesystem::path(o.output);
    if (output.extension() != ".exr") throw std::runtime_error(output.string() + ": output must end in .exr");
    if (!output.parent_path().empty()) {
        std::error_code ec;
        std::filesystem::create_directories(output.parent_path(), ec);
        if (ec) throw std::runtime_error(output.parent_path().string() + ": cannot create directory (" + ec.message() + ")");
    }
    std::ofstream errorLog;
    if (!o.errorLog.empty()) {
        errorLog.open(o.errorLog);
        if (!errorLog) throw std::runtime_error(o.errorLog + ": cannot open for writing");
        errorLog << "spp,seconds,relmse\n";
    }

    FlatScene flat = flattenScene(scene);
    if (flat.degenerateTriangles > 0)
        std::fprintf(stderr, "pt: note: %s: dropped %zu degenerate (zero-area) triangles\n", scene.source.c_str(),
            flat.degenerateTriangles);
    const double loadSeconds = secondsSince(loadStart);
    if (flat.lights.lights.empty() && scene.background == glm::vec3(0.0f))
        std::fprintf(stderr, "pt: warning: %s: nothing emits light (no emissive triangles, black background): the image "
                             "will be black\n", scene.source.c_str());

    ContextOptions contextOptions;
    contextOptions.validation = o.validation;
    contextOptions.deviceSubstring = o.device;
    VulkanContext context(contextOptions);
    if (context.isSlowLavapipe() && !o.quiet)
        std::fprintf(stderr, "pt: note: lavapipe from Mesa older than 24 runs about 3.5x slower; install Mesa 25 "
                             "from bookworm-backports (scripts/setup.sh does)\n");

    const FeatureSet features = computeFeatures(flat, settings);
    FilmSettings film{width, height, scene.background};
    Renderer renderer(context, flat, features, settings, camera, film);
    if (!o.quiet) {
        std::fprintf(stderr, "pt: %s: %zu triangles, %zu lights, BVH %.3f s (SAH %.1f, depth %d), load %.2f s\n",
            scene.source.c_str(), flat.triangles.size(), flat.lights.lights.size(), flat.bvhSeconds, flat.sahCost,
            flat.bvhDepth, loadSeconds);
        std::fprintf(stderr, "pt: device %s (%s); kernel features: %s; pipeline %.3f s\n", context.info().name.c_str(),
            context.info().driver.c_str(), features.describe().c_str(), renderer.pipelineSeconds());
        std::fprintf(stderr, "pt: %dx%d, %s\n", width, height, settings.describe().c_str());
    }

    // Progressive passes: about half a second each (or --pass-spp), until the spp or time target.
    const uint32_t targetSpp = o.spp.value_or(o.seconds ? 0u : 64u);
    const double targetSeconds = o.seconds.value_or(0.0);
    Progress progress(targetSpp, targetSeconds, !o.quiet);
    double renderSeconds = 0;
    double lastRelMse = NAN;
    const double pixels = double(width) * height;
    while (true) {
        const uint32_t done = renderer.samplesPerPixel();
        if (targetSpp > 0 && done >= targetSpp) break;
        const double secondsPerSpp = done > 0 ? renderSeconds / done : 0.0;
        uint32_t pass;
        if (o.passSpp > 0) pass = o.passSpp;
        else if (done == 0) pass = 1;
        else pass = static_cast<uint32_t>(std::clamp(0.5 / std::max(secondsPerSpp, 1e-9), 1.0, 4096.0));
        if (targetSpp > 0) pass = std::min(pass, targetSpp - done);
        if (targetSeconds > 0 && done > 0) {
            const double remaining = targetSeconds - renderSeconds;
            const double fits = std::floor(remaining / std::max(secondsPerSpp, 1e-9));
            if (fits < 1.0) break;
            pass = static_cast<uint32_t>(std::min<double>(pass, fits));
        }
        const auto passStart = Clock::now();
        renderer.addSamples(pass, o.tileSize);
        renderSeconds += secondsSince(passStart);
        const uint32_t spp = renderer.samplesPerPixel();
        if (reference) {
            lastRelMse = relMse(renderer.read().mean, *reference);
            if (errorLog) errorLog << spp << "," << formatDouble(renderSeconds) << "," << formatDouble(lastRelMse) << "\n";
        }
        progress.update(spp, renderSeconds, pixels * spp / std::max(renderSeconds, 1e-9) * 1e-6, lastRelMse);
        if (targetSeconds > 0 && renderSeconds >= targetSeconds) break;
    }
    progress.finish();

    const Renderer::Readback result = renderer.read();
    const uint32_t spp = renderer.samplesPerPixel();
    const double mpaths = pixels * spp / std::max(renderSeconds, 1e-9) * 1e-6;
    ImageMetadata meta;
    meta["spp"] = std::to_string(spp);
    meta["seconds"] = formatDouble(renderSeconds);
    meta["seed"] = std::to_string(settings.seed);
    meta["device"] = context.info().name;
    meta["driver"] = context.info().driver;
    meta["integrator"] = settings.describe();
    meta["features"] = features.describe();
    meta["scene"] = scene.source;
    meta["camera"] = camera.name;
    meta["dropped_samples"] = std::to_string(result.droppedSamples);
    meta["mpaths_per_second"] = formatDouble(mpaths);
    writeExr(output, result.mean, meta);
    std::filesystem::path png = output;
    png.replace_extension(".png");
    writePng(png, result.mean, o.exposure);

    std::string summary = "pt: wrote " + output.string() + " and " + png.string() + ": " + std::to_string(spp) + " spp in " +
                          formatDouble(std::round(renderSeconds * 1000) / 1000) + " s, " +
                          formatDouble(std::round(mpaths * 1000) / 1000) + " M paths/s, " +
                          std::to_string(result.droppedSamples) + " non-finite samples dropped";
    if (reference) summary += ", relMSE " + formatDouble(relMse(result.mean, *reference));
    std::fprintf(stderr, "%s\n", summary.c_str());

    if (o.validation && context.validationMessageCount() > 0) {
        std::fprintf(stderr, "pt: error: Vulkan validation reported %u message(s); first: %s\n",
            context.validationMessageCount(), context.firstValidationMessage().c_str());
        return 3;
    }
    return 0;
}

} // namespace pt
