#include "app/bench/bench_command.h"

#include "app/context_options.h"
#include "app/scene_setup.h"
#include "gpu/vulkan_context.h"
#include "app/bench/bench_config.h"
#include "app/bench/budget_run.h"
#include "flatten/feature_set.h"
#include "image/image_io.h"
#include "film/metrics.h"
#include "render/renderer.h"
#include "film/tonemap.h"

#include <fcntl.h>
#include <spawn.h>
#include <unistd.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

extern char** environ;

namespace pt {
extern const char* const kBenchPlotScript; // tools/bench_plot.py, embedded by CMake

namespace {

namespace fs = std::filesystem;

std::string number(double v) {
    std::ostringstream s;
    s.precision(6);
    s << v;
    return s.str();
}

// The configuration that makes a missing reference: the renderer's default techniques with the
// sampler that converges fastest on every scene measured (bench/RESULTS.md).
constexpr const char* kReferenceConfig = "nee+is+rr+sobol";
constexpr uint32_t kReferenceSeedOffset = 0x9E3779B9u;

Image renderReference(VulkanContext& context, const FlatScene& flat, const Job& job, const Scene& scene, uint32_t spp,
    const fs::path& path) {
    IntegratorSettings settings = parseBenchConfig(kReferenceConfig).apply(job.settings);
    // Samples of its own: with the seed of the measured renders, a configuration equal to this
    // one would repeat the reference's first samples, and at 256 spp be the reference (relMSE 0).
    settings.seed += kReferenceSeedOffset;
    Renderer renderer(context, flat, computeFeatures(flat, settings), settings, job.camera,
        FilmSettings{job.width, job.height, scene.background});
    std::fprintf(stderr, "pt: bench: no --reference given: rendering one with %s at %u spp to %s\n", kReferenceConfig,
        spp, path.string().c_str());
    for (uint32_t done = 0; done < spp;) {
        const uint32_t pass = std::min<uint32_t>(16, spp - done);
        renderer.addSamples(pass);
        done += pass;
    }
    Image reference = renderer.read().mean;
    writeExr(path, reference, {{"spp", std::to_string(spp)}, {"config", kReferenceConfig}, {"scene", scene.source}});
    return reference;
}

// Runs `python` with `args`; true when it exits 0. Its output goes where pt's goes unless quiet.
bool runPython(const std::string& python, const std::vector<std::string>& args, bool quiet) {
    std::vector<char*> argv{const_cast<char*>(python.c_str())};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (quiet) {
        posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
        posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
    }
    pid_t pid = 0;
    const int spawned = posix_spawnp(&pid, python.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) return false;
    int status = 0;
    if (waitpid(pid, &status, 0) != pid) return false;
    return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

// The interpreter for the plots: $PT_PYTHON when set; otherwise the first of python3 on PATH and
// Debian's /usr/bin/python3 (whose python3-matplotlib scripts/setup.sh installs) that can import
// matplotlib, since a python3 earlier on PATH (pyenv, a venv) often cannot.
std::string plotInterpreter() {
    const char* chosen = std::getenv("PT_PYTHON");
    if (chosen && *chosen) return chosen;
    for (const char* candidate : {"python3", "/usr/bin/python3"})
        if (runPython(candidate, {"-c", "import matplotlib"}, true)) return candidate;
    return "python3"; // fails below with the message that says what to install
}

// Runs the plot interpreter on DIR/plot.py DIR; false when it cannot run or fails.
bool runPlotScript(const fs::path& dir) {
    const fs::path script = dir / "plot.py";
    {
        std::ofstream out(script);
        out << kBenchPlotScript;
        if (!out) throw std::runtime_error(script.string() + ": cannot write");
    }
    return runPython(plotInterpreter(), {script.string(), dir.string()}, false);
}

} // namespace

int runBench(const BenchOptions& b) {
    const RenderOptions& o = b.render;
    if (b.budgets.empty()) throw std::runtime_error("--budgets: no budget given");
    for (double budget : b.budgets)
        if (!(budget > 0) || !std::isfinite(budget))
            throw std::runtime_error("--budgets: " + number(budget) + " is not a positive time");
    const std::vector<BenchConfig> configs = b.configs.empty() ? defaultBenchConfigs() : parseBenchConfigs(b.configs);

    Scene scene = loadSceneWithOptions(o);
    const bool course = isCourseScene(o.scene);
    const std::vector<Camera> cameras = chooseCameras(scene, o, course);
    if (cameras.size() > 1)
        std::fprintf(stderr, "pt: bench: the scene has %zu cameras; using the first (%s); pick one with --camera\n",
            cameras.size(), cameras[0].name.c_str());
    Job job = makeJob(scene, cameras[0], o, false, course);

    const fs::path dir = b.outputDir;
    std::error_code ec;
    fs::create_directories(dir / "images", ec);
    if (ec) throw std::runtime_error(dir.string() + ": cannot create the output folder: " + ec.message());

    std::optional<Image> given;
    if (!b.reference.empty()) {
        given = referenceAtSize(readExr(b.reference), job.width, job.height, b.reference);
    }

    FlatScene flat = flattenWithNotes(scene, o);
    VulkanContext context(contextOptionsFor(o));
    const std::string device = context.info().name + " (" + context.info().driver + ")";
    const std::string loadsNote = chooseGeometryLoads(context, o, job.settings);
    if (!loadsNote.empty()) std::fprintf(stderr, "pt: bench: %s\n", loadsNote.c_str());
    const Image reference =
        given ? *given : renderReference(context, flat, job, scene, b.referenceSpp, dir / "reference.exr");

    {
        std::ofstream info(dir / "bench_info.txt");
        info << "scene: " << scene.source << "\ncamera: " << job.camera.name << "\nsize: " << job.width << "x"
             << job.height << "\ndevice: " << device << "\nreference: "
             << (given ? b.reference
                       : (dir / "reference.exr").string() + " (made here: " + kReferenceConfig + ", " +
                             std::to_string(b.referenceSpp) + " spp)")
             << "\nsettings: " << job.settings.describe() << "\n";
    }
    const fs::path csvPath = dir / "bench.csv";
    std::ofstream csv(csvPath);
    if (!csv) throw std::runtime_error(csvPath.string() + ": cannot open for writing");
    csv << "config,budget_s,spp,seconds,mpaths_per_s,mrays_per_s,mrays_camera_per_s,mrays_shadow_per_s,"
           "mrays_continuation_per_s,relmse,mse,efficiency,estimated_relmse,dropped_samples,image\n";
    std::fprintf(stderr, "pt: bench: %s, %dx%d, %zu configurations x %zu budgets on %s\n", scene.source.c_str(),
        job.width, job.height, configs.size(), b.budgets.size(), device.c_str());

    const double pixels = double(job.width) * job.height;
    for (const BenchConfig& config : configs) {
        const IntegratorSettings settings = config.apply(job.settings);
        FeatureSet features = computeFeatures(flat, settings);
        features.countRays = true;
        Renderer renderer(
            context, flat, features, settings, job.camera, FilmSettings{job.width, job.height, scene.background});
        // Warm up: the first dispatch of a pipeline pays one-off costs (lavapipe finishes
        // compiling there); like Mitsuba's timings, the budgets measure rendering only.
        renderer.addSamples(1);
        renderer.reset();
        renderToBudgets(renderer, b.budgets, [&](const BudgetPoint& p) {
            const Renderer::Readback result = renderer.read();
            const Renderer::RayCounts rays = renderer.rayCounts();
            const double relmse = relMse(result.mean, reference);
            const double seconds = std::max(p.seconds, 1e-9);
            const double perSecond = 1e-6 / seconds;
            const std::string image = "images/" + config.label + "_" + number(p.budget) + "s.png";
            writeTonemappedPng(dir / image, result.mean, job.tonemap, o.exposure);
            csv << config.label << ',' << number(p.budget) << ',' << p.spp << ',' << number(p.seconds) << ','
                << number(pixels * p.spp * perSecond) << ','
                << number(double(rays.camera + rays.shadow + rays.continuation) * perSecond) << ','
                << number(double(rays.camera) * perSecond) << ',' << number(double(rays.shadow) * perSecond) << ','
                << number(double(rays.continuation) * perSecond) << ',' << number(relmse) << ','
                << number(mse(result.mean, reference)) << ',' << number(1.0 / (relmse * seconds)) << ','
                << number(estimatedRelMse(result.mean, result.varianceOfMean)) << ',' << result.droppedSamples << ','
                << image << '\n'
                << std::flush;
            std::fprintf(stderr, "pt: bench: %-18s %6s s: %6u spp in %7.3f s, %6.3f M paths/s, relMSE %.4g\n",
                config.label.c_str(), number(p.budget).c_str(), p.spp, p.seconds, pixels * p.spp * perSecond, relmse);
        });
    }
    std::fprintf(stderr, "pt: bench: wrote %s\n", csvPath.string().c_str());
    if (!b.plot) return 0;
    if (!runPlotScript(dir)) {
        std::fprintf(stderr,
            "pt: error: %s: plotting failed: it needs python3 with matplotlib (Debian: apt install "
            "python3-matplotlib; another interpreter: PT_PYTHON=/path/to/python); the CSV and "
            "images are written\n",
            (dir / "plot.py").string().c_str());
        return 1;
    }
    std::fprintf(stderr, "pt: bench: wrote %s and %s\n", (dir / "relmse_vs_time.png").string().c_str(),
        (dir / "contact_<budget>s.png").string().c_str());
    return 0;
}

} // namespace pt
