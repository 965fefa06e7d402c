#include "app/render_command.h"

#include "app/context_options.h"
#include "app/render_session.h"
#include "app/scene_setup.h"
#include "base/memory_usage.h"

#include "gpu/vulkan_context.h"
#include "flatten/feature_set.h"
#include "flatten/flat_scene.h"
#include "image/image_io.h"
#include "film/metrics.h"
#include "render/progressive_render.h"
#include "render/light_visibility_probe.h"
#include "render/renderer.h"
#include "film/state_file.h"
#include "film/tonemap.h"
#include "scene/scene_loader.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace pt {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::string formatDouble(double v) {
    std::ostringstream s;
    s.precision(9);
    s << v;
    return s.str();
}

// --variance: the variance of each pixel's mean as channels variance.R, .G, .B.
std::vector<ExrChannel> varianceChannels(const Image& varianceOfMean) {
    std::vector<ExrChannel> channels{{"variance.R", {}}, {"variance.G", {}}, {"variance.B", {}}};
    const size_t pixels = size_t(varianceOfMean.width) * varianceOfMean.height;
    for (int c = 0; c < 3; ++c) {
        channels[c].values.resize(pixels);
        for (size_t i = 0; i < pixels; ++i) channels[c].values[i] = varianceOfMean.rgba[4 * i + c];
    }
    return channels;
}

// `lastUse`: no job after this one needs `flat`, so its big arrays are freed as they are uploaded.
int renderJob(VulkanContext& context, const Scene& scene, FlatScene& flat, bool lastUse, const Job& planned,
    const RenderOptions& o, const std::optional<Image>& reference, std::ostream* errorLog) {
    Job job = planned;
    // --integrator auto: measure how often light sampling finds the light, where BDPT could
    // render the scene (the rule is computeFeatures').
    const std::string autoNote =
        measureForAutoIntegrator(context, flat, job.settings, job.camera, job.width, job.height);
    if (!o.quiet && !autoNote.empty()) std::fprintf(stderr, "pt: %s: %s\n", job.camera.name.c_str(), autoNote.c_str());
    // --all-features: the unspecialised kernel, for measuring what specialisation saves. Light
    // tracing and BDPT are estimators, not features: the scene decides them either way (each is
    // only correct where computeFeatures allows it), so both kernels render the same image.
    FeatureSet features = computeFeatures(flat, job.settings);
    const std::optional<float> flatHitDistance = flat.cameraHitDistance; // flat may be released below
    if (features.merging && job.settings.estimator == Estimator::Auto) {
        const VkDeviceSize bytes = mergingBufferSizes(job.width, job.height, job.settings.maxDepth).bytes;
        if (bytes > kAutoMergingMaxBytes) {
            features.merging = false;
            if (!o.quiet)
                std::fprintf(stderr,
                    "pt: %s: BDPT without vertex merging: its light vertices would need %s at %dx%d, depth %u "
                    "(--integrator vcm renders with them)\n",
                    job.camera.name.c_str(), formatBytes(bytes).c_str(), job.width, job.height, job.settings.maxDepth);
        }
    }
    // Vertex merging renders in rounds that every pixel takes alike (a round's light subpaths
    // serve every pixel's merges): no adaptive sampling.
    if (features.merging && job.target.adaptive) {
        if (o.adaptive.value_or(false))
            throw std::runtime_error("--adaptive on cannot be used with vertex merging (--integrator vcm): its rounds "
                                     "give every pixel the same samples");
        job.target.adaptive = false;
    }
    if (o.allFeatures) {
        const bool lightTracing = features.lightTracing, bdpt = features.bdpt, merging = features.merging;
        features = FeatureSet::all(job.settings);
        features.lightTracing = lightTracing;
        features.bdpt = bdpt;
        features.merging = merging;
    }
    const FilmSettings film{job.width, job.height, scene.background};
    std::optional<Renderer> made;
    if (lastUse)
        made.emplace(context, std::move(flat), features, job.settings, job.camera, film);
    else
        made.emplace(context, flat, features, job.settings, job.camera, film);
    Renderer& renderer = *made;
    if (!o.quiet) {
        std::fprintf(stderr, "pt: %s: %dx%d, kernel features: %s; pipeline %.3f s (%s kernel)\n",
            job.camera.name.c_str(), job.width, job.height, features.describe().c_str(), renderer.pipelineSeconds(),
            renderer.pipelineSource());
        std::fprintf(stderr, "pt: %s\n", describeIntegrator(job).c_str());
        if (renderer.mergeRadius() > 0)
            std::fprintf(stderr, "pt: vertex merging: radius %g in the first round (%g pixel footprints at %s)\n",
                renderer.mergeRadius(), job.settings.mergeRadius,
                flatHitDistance ? ("the camera's median hit distance " + formatDouble(*flatHitDistance)).c_str()
                                : "the scene's radius");
    }
    ImageMetadata meta;
    meta["seed"] = std::to_string(job.settings.seed);
    meta["device"] = context.info().name;
    meta["driver"] = context.info().driver;
    meta["integrator"] = job.settings.describe();
    meta["features"] = features.describe();
    meta["scene"] = scene.source;
    if (!scene.variant.empty()) meta["variant"] = scene.variant;
    meta["camera"] = job.camera.name;
    // --samples, --resume, --checkpoint, signals, device faults: app/render_session.h.
    RenderSession session(o, scene, job, renderer, meta);
    const ProgressiveResult progress = session.run([&](const ProgressiveTarget& target) {
        return renderProgressively(renderer, target, reference ? &*reference : nullptr, errorLog, !o.quiet);
    });
    session.finish(progress.seconds);

    const AccumulationState state = renderer.readState();
    const Renderer::Readback result = resolve(state);
    const uint32_t spp = renderer.samplesPerPixel();
    const uint32_t sppThisRun = spp - std::min(spp, session.resumedSpp());
    // Adaptive epochs add about spp x pixels samples; the paths are counted exactly.
    const double pathsThisRun = state.adaptive() && session.resumedSpp() == 0
                                    ? state.totalSamples()
                                    : double(job.width) * job.height * sppThisRun;
    const double mpaths = pathsThisRun / std::max(progress.seconds, 1e-9) * 1e-6;
    meta["spp"] = std::to_string(spp);
    if (job.target.adaptive) {
        meta["adaptive_sampling"] = std::to_string(progress.adaptiveEpochs) + " of " + std::to_string(progress.epochs) +
                                    " epochs adaptive, last predicted gain " + formatDouble(progress.predictedGain);
        if (!o.quiet) std::fprintf(stderr, "pt: adaptive sampling: %s\n", meta["adaptive_sampling"].c_str());
    }
    session.addMetadata(meta, progress.seconds);
    meta["dropped_samples"] = std::to_string(result.droppedSamples);
    meta["mpaths_per_second"] = formatDouble(mpaths);
    const double estimate = estimatedRelMse(result.mean, result.varianceOfMean);
    meta["estimated_relmse"] = formatDouble(estimate);
    if (job.target.targetError > 0) meta["target_error"] = formatDouble(job.target.targetError);
    prepareOutputDirectory(job.output);
    if (session.outputIsState())
        writeStateExr(job.output, state, result.mean, meta);
    else if (o.varianceAov)
        writeExr(job.output, result.mean, meta, varianceChannels(result.varianceOfMean));
    else
        writeExr(job.output, result.mean, meta);
    fs::path png = job.output;
    png.replace_extension(".png");
    writeTonemappedPng(png, result.mean, job.tonemap, o.exposure);

    std::string summary = "pt: wrote " + job.output.string() + " and " + png.string() + ": " + std::to_string(spp) +
                          " spp in " + formatDouble(std::round(progress.seconds * 1000) / 1000) + " s, " +
                          formatDouble(std::round(mpaths * 1000) / 1000) + " M paths/s, " +
                          std::to_string(result.droppedSamples) + " non-finite samples dropped, estimated relMSE " +
                          formatDouble(estimate);
    if (job.target.targetError > 0)
        summary += progress.targetReached
                       ? " (target " + formatDouble(job.target.targetError) + " reached)"
                       : " (target " + formatDouble(job.target.targetError) + " not reached: stopped at the cap)";
    if (reference) summary += ", relMSE " + formatDouble(relMse(result.mean, *reference));
    summary += ", peak memory " + formatBytes(peakResidentBytes());
    std::fprintf(stderr, "%s\n", summary.c_str());
    if (session.interrupted())
        std::fprintf(stderr, "pt: interrupted by signal %d after %u spp; continue with --resume %s\n",
            session.interrupted(), spp,
            (o.checkpoint.empty() ? (o.resume.empty() ? job.output.string() : o.resume) : o.checkpoint).c_str());
    return session.exitStatus();
}

} // namespace

int runRender(const RenderOptions& o) {
    const auto loadStart = Clock::now();
    if (o.listVariants) {
        const Scene scene = loadScene(o.scene, o.variant);
        for (const std::string& name : scene.materialVariants) std::printf("%s\n", name.c_str());
        if (scene.materialVariants.empty())
            std::fprintf(stderr, "pt: %s: no material variants\n", scene.source.c_str());
        return 0;
    }
    Scene scene = loadSceneWithOptions(o);
    const bool course = isCourseScene(o.scene);
    const std::vector<Camera> cameras = chooseCameras(scene, o, course);
    std::vector<Job> jobs;
    for (const Camera& c : cameras) jobs.push_back(makeJob(scene, c, o, cameras.size() > 1, course));

    // Fail on a bad reference or output before spending time on rendering.
    std::optional<Image> reference;
    if (!o.reference.empty()) {
        if (jobs.size() != 1)
            throw std::runtime_error(o.reference + ": --reference needs a single image (use --camera)");
        reference = referenceAtSize(readExr(o.reference), jobs[0].width, jobs[0].height, o.reference);
    }
    if (jobs.size() != 1 && (!o.samples.empty() || !o.checkpoint.empty() || !o.resume.empty()))
        throw std::runtime_error((o.scene.empty() ? std::string("built-in scene") : o.scene) +
                                 ": --samples, --checkpoint and --resume need a single image (use --camera)");
    for (const Job& job : jobs) prepareOutputDirectory(job.output);
    std::ofstream errorLog;
    if (!o.errorLog.empty()) {
        errorLog.open(o.errorLog);
        if (!errorLog) throw std::runtime_error(o.errorLog + ": cannot open for writing");
        errorLog << "spp,seconds,relmse\n";
    }

    const uint64_t loadedBytes = residentBytes();
    FlatScene flat = flattenWithNotes(scene, o);
    const uint64_t flattenedBytes = residentBytes();
    // The kernel reads the flattened copies only: the scene model's geometry and texture images
    // need not live on beside them.
    releaseFlattenedParts(scene);
    const uint64_t releasedBytes = residentBytes();
    const double loadSeconds = secondsSince(loadStart);

    VulkanContext context(contextOptionsFor(o));
    if (context.isSlowLavapipe() && !o.quiet)
        std::fprintf(stderr, "pt: note: lavapipe from Mesa older than 24 runs about 3.5x slower; install Mesa 25 "
                             "from bookworm-backports (scripts/setup.sh does)\n");
    if (!o.quiet) {
        std::fprintf(stderr,
            "pt: %s: %zu triangles, %zu spheres, %zu lights, BVH %.3f s (SAH %.1f, depth %d, 4-wide %d), load %.2f s\n",
            scene.source.c_str(), flat.triangles.size(), flat.spheres.size(), flat.lights.lights.size(),
            flat.bvhSeconds, flat.sahCost, flat.bvhDepth, flat.wideBvhDepth, loadSeconds);
        std::fprintf(stderr, "pt: memory: resident %s once loaded, %s once flattened (peak %s), %s without the model\n",
            formatBytes(loadedBytes).c_str(), formatBytes(flattenedBytes).c_str(),
            formatBytes(peakResidentBytes()).c_str(), formatBytes(releasedBytes).c_str());
        const std::string chosen = VulkanContext::lavapipeSettingsChosen();
        const bool cpuDevice = context.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
        std::fprintf(stderr, "pt: device %s (%s)%s%s\n", context.info().name.c_str(), context.info().driver.c_str(),
            cpuDevice && !chosen.empty() ? "; lavapipe settings pt chose (set them to choose yours): " : "",
            cpuDevice ? chosen.c_str() : "");
    }
    // One measurement serves every job: the answer is the machine's, not the scene's.
    IntegratorSettings loads = jobs.front().settings;
    const std::string loadsNote = chooseGeometryLoads(context, o, loads);
    if (!o.quiet && !loadsNote.empty()) std::fprintf(stderr, "pt: %s\n", loadsNote.c_str());
    for (Job& job : jobs) job.settings.texelLoads = job.settings.texelLoads && loads.texelLoads;
    for (size_t i = 0; i < jobs.size(); ++i)
        if (const int status = renderJob(context, scene, flat, i + 1 == jobs.size(), jobs[i], o, reference,
                errorLog.is_open() ? &errorLog : nullptr))
            return status; // interrupted: the checkpoint and partial image are saved

    if (o.validation && context.validationMessageCount() > 0) {
        std::fprintf(stderr, "pt: error: Vulkan validation reported %u message(s); first: %s\n",
            context.validationMessageCount(), context.firstValidationMessage().c_str());
        return 3;
    }
    return 0;
}

} // namespace pt
