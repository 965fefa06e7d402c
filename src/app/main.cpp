// pt: a path tracer on Vulkan compute. Subcommands: render, view, devices.
#include "app/bench/bench_command.h"
#include "app/options.h"
#include "app/merge_command.h"
#include "app/render_command.h"
#include "app/view_command.h"
#include "base/memory_usage.h"
#include "gpu/vulkan_context.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string>

namespace {

int listDevices() {
    auto devices = pt::VulkanContext::listDevices();
    if (devices.empty()) {
        std::fprintf(
            stderr, "pt: error: no Vulkan device found (install mesa-vulkan-drivers for lavapipe, or a GPU driver)\n");
        return 1;
    }
    for (const auto& d : devices)
        std::printf("%u: %s (%s, %s, Vulkan %u.%u)%s%s\n", d.index, d.name.c_str(), d.type.c_str(), d.driver.c_str(),
            VK_API_VERSION_MAJOR(d.apiVersion), VK_API_VERSION_MINOR(d.apiVersion),
            d.usable ? "" : " unusable: ", d.whyNotUsable.c_str());
    return 0;
}

bool onOff(const std::string& v) { return v == "on"; }

// Switches given as words on the command line, converted after parsing.
struct SwitchWords {
    std::string nee, mis, rr, sampling, integrator, sampler, lightTracing, instances, lightTree, bvh, sharedSamples,
        texelLoads;
    std::vector<float> envColour;
};

// Options `pt render` and `pt view` share: what to render and how.
void addSceneOptions(CLI::App* cmd, pt::RenderOptions& o, SwitchWords& w) {
    cmd->add_option("scene", o.scene, "Scene file");
    cmd->add_option("--width", o.width, "Image width (default: the scene's, else 512)")->check(CLI::Range(1, 1 << 30));
    cmd->add_option("--height", o.height, "Image height (default: the scene's, else from the camera aspect)")
        ->check(CLI::Range(1, 1 << 30));
    cmd->add_option("--max-depth", o.maxDepth,
           "Ray segments per path including the camera ray (1: emitters only, 2: direct light); default 16")
        ->check(CLI::Range(1u, 65536u));
    cmd->add_option(
        "--rr-start", o.integrator.rrStartDepth, "Russian roulette starts after this many segments (default 3)");
    cmd->add_option("--rr-threshold", o.integrator.rrThreshold,
           "Russian roulette: paths with throughput at least this always continue, others survive with probability "
           "throughput / threshold (default 0.5; pbrt and Mitsuba use 1)")
        ->check(CLI::Range(1e-3, 1e3));
    cmd->add_option("--merge-radius", o.integrator.mergeRadius,
           "Vertex merging (--integrator vcm): the first round's merge radius in pixel footprints at the median "
           "distance of the surfaces the camera sees (default 8)")
        ->check(CLI::Range(0.01, 1000.0));
    cmd->add_option("--merge-alpha", o.integrator.mergeAlpha,
           "Vertex merging: the radius shrinks as round^((alpha - 1) / 2) (default 0.65; 1 keeps it)")
        ->check(CLI::Range(0.01, 1.0));
    cmd->add_option("--seed", o.integrator.seed, "Random seed (default 0)");
    cmd->add_option("--nee", w.nee, "Next event estimation (light sampling): on|off (default on)")
        ->check(CLI::IsMember({"on", "off"}));
    cmd->add_option("--mis", w.mis, "Multiple importance sampling of light and BSDF samples: on|off (default on)")
        ->check(CLI::IsMember({"on", "off"}));
    cmd->add_option("--rr", w.rr, "Russian roulette: on|off (default on)")->check(CLI::IsMember({"on", "off"}));
    cmd->add_option("--integrator", w.integrator,
           "path: path tracing; bdpt: bidirectional path tracing (light and camera subpaths joined by every "
           "strategy with MIS: for light that arrives through gaps, shades and caustics); vcm: bdpt whose camera "
           "vertices also merge with every light subpath's vertices near them (vertex connection and merging); "
           "auto: the one the scene calls for; classic: the CENG795 course's classic ray tracer (ambient + direct "
           "light with its Blinn-Phong, specular chains); default: course cameras without <Renderer> classic, else "
           "auto")
        ->check(CLI::IsMember({"path", "bdpt", "vcm", "auto", "classic"}));
    cmd->add_option("--sampling", w.sampling,
           "BSDF direction sampling: bsdf (importance sampling of every lobe, cosine-weighted for Lambert; "
           "'cosine' is the same) or uniform (uniform hemisphere / sphere); default bsdf")
        ->check(CLI::IsMember({"bsdf", "cosine", "uniform"}));
    cmd->add_option("--sampler", w.sampler,
           "What fills each sample's random dimensions: independent (hashed random numbers) or sobol "
           "(Owen-scrambled Sobol' points shuffled per pixel; lower error for the same samples); default sobol")
        ->check(CLI::IsMember({"independent", "sobol"}));
    cmd->add_option("--light-tracing", w.lightTracing,
           "Caustics seen directly (camera, diffuse surface, mirrors or glass, area light) by light tracing, "
           "splatted, where the scene has them: on|off (default on; off leaves them to BSDF sampling)")
        ->check(CLI::IsMember({"on", "off"}));
    cmd->add_option("--light-tree", w.lightTree,
           "How light sampling chooses among lights with a place (emissive triangles and spheres, point, spot and "
           "square lights): on (a tree over their bounds, power and orientation: near lights that face the point "
           "first), off (by power alone) or auto (the tree where two or more lights spread over a quarter of the "
           "scene or face more ways than a 30-degree cone); default auto")
        ->check(CLI::IsMember({"auto", "on", "off"}));
    cmd->add_option("--bvh", w.bvh,
           "Triangles: always (the four-wide tree; the default) or auto (a scene of at most 48 triangles and no "
           "instances tests every triangle against each ray from a uniform buffer instead: faster on lavapipe "
           "before the tree read its nodes as texels, slower since); the same image either way")
        ->check(CLI::IsMember({"auto", "always"}));
    cmd->add_option("--texel-loads", w.texelLoads,
           "Triangles and tree nodes on a CPU device such as lavapipe: on (read through texel buffers: one 16-byte "
           "load per lane instead of a gather per word), off (through buffer addresses, as on GPUs) or auto (the one "
           "this machine renders the built-in Cornell box faster with, measured once and remembered in the pipeline "
           "cache's folder; on without the folder); default auto; the same image either way")
        ->check(CLI::IsMember({"auto", "on", "off"}));
    cmd->add_option("--shared-samples", w.sharedSamples,
           "Path tracing: the 8 pixels the CPU driver runs as one SIMD vector (spread over an 8x8 block) share "
           "their random numbers, so their paths stay together: 1.2-1.3x the paths per second on lavapipe with "
           "each pixel's expected error unchanged, but their noise is correlated (faint mottling at the block's "
           "scale): on|off (default off)")
        ->check(CLI::IsMember({"on", "off"}));
    cmd->add_option("--instances", w.instances,
           "Meshes placed several times (glTF nodes sharing a mesh, the course's MeshInstances): keep (one copy "
           "each, under a tree over their placements), expand (copied into world space into one tree: more memory, "
           "faster for small meshes) or auto (expand when the copies add at most 32768 triangles); default auto")
        ->check(CLI::IsMember({"auto", "keep", "expand"}));
    cmd->add_option("--variant", o.variant,
        "glTF KHR_materials_variants: render this variant's materials (default: the default materials; see "
        "--list-variants)");
    cmd->add_option("--camera", o.camera,
        "Camera to render: glTF: its index (default 0); course XML: its id (default: every camera)");
    cmd->add_option("--device", o.device, "Use the first Vulkan device whose name contains this (see 'pt devices')");
    cmd->add_option("--exposure", o.exposure, "Exposure in stops for the PNG");
    cmd->add_option("--env", o.environment, "Environment: an equirectangular (lat-long) radiance map, .exr");
    auto* envColourOpt =
        cmd->add_option("--env-colour", w.envColour, "Environment: a constant radiance R G B")->expected(3);
    envColourOpt->excludes(cmd->get_option("--env"));
    cmd->add_option("--env-scale", o.environmentScale, "Multiply the environment's radiance")
        ->check(CLI::Range(0.0f, 1e30f));
    cmd->add_option("--env-rotate", o.environmentRotation, "Rotate the environment about +y, in degrees");
    cmd->add_flag("--validation", o.validation, "Enable the Vulkan validation layer; fail if it reports anything");
    cmd->add_flag("--no-pipeline-cache", o.noPipelineCache,
        "Neither read nor write the pipeline cache ($XDG_CACHE_HOME/pt, else ~/.cache/pt: specialised kernels "
        "and the driver's cache, which make a kernel's second start-up fast)");
    cmd->add_flag("--all-features", o.allFeatures,
        "Use the kernel with every feature compiled in instead of one specialised "
        "to the scene (to measure what specialisation saves; same image)");
}

void applySwitchWords(const SwitchWords& w, pt::RenderOptions& o) {
    if (const char* v = std::getenv("PT_VALIDATION"); v && std::string(v) == "1") o.validation = true;
    if (w.envColour.size() == 3) o.environmentColour = glm::vec3(w.envColour[0], w.envColour[1], w.envColour[2]);
    if (!w.integrator.empty()) o.classic = w.integrator == "classic";
    if (w.integrator == "path") o.integrator.estimator = pt::Estimator::Path;
    if (w.integrator == "bdpt") o.integrator.estimator = pt::Estimator::Bidirectional;
    if (w.integrator == "vcm") o.integrator.estimator = pt::Estimator::VertexMerging;
    if (!w.nee.empty()) o.nee = onOff(w.nee);
    if (!w.mis.empty()) o.mis = onOff(w.mis);
    if (!w.rr.empty()) o.rr = onOff(w.rr);
    if (!w.lightTracing.empty()) o.integrator.lightTracing = onOff(w.lightTracing);
    if (!w.lightTree.empty())
        o.integrator.lightSelection = w.lightTree == "on"    ? pt::LightSelection::Tree
                                      : w.lightTree == "off" ? pt::LightSelection::Power
                                                             : pt::LightSelection::Auto;
    if (!w.bvh.empty()) o.integrator.alwaysTree = w.bvh == "always";
    if (!w.sharedSamples.empty()) o.integrator.sharedSamples = onOff(w.sharedSamples);
    if (!w.texelLoads.empty()) {
        o.integrator.texelLoads = w.texelLoads != "off";
        o.measureTexelLoads = w.texelLoads == "auto";
    }
    if (!w.sampler.empty())
        o.integrator.sampler = w.sampler == "sobol" ? pt::SamplerKind::Sobol : pt::SamplerKind::Independent;
    if (!w.instances.empty())
        o.instancing = w.instances == "keep"     ? pt::Instancing::Keep
                       : w.instances == "expand" ? pt::Instancing::Expand
                                                 : pt::Instancing::Auto;
    if (!w.sampling.empty())
        o.sampling = w.sampling == "uniform" ? pt::DirectionSampling::Uniform : pt::DirectionSampling::Cosine;
}

} // namespace

int main(int argc, char** argv) {
    CLI::App app{"pt: a physically based path tracer on Vulkan compute shaders"};
    app.require_subcommand(1);
    pt::RenderOptions o;
    SwitchWords words;

    CLI::App* render =
        app.add_subcommand("render", "Render a scene (glTF .gltf/.glb; none: the built-in Cornell box) to EXR and PNG");
    addSceneOptions(render, o, words);
    render->add_option(
        "-o,--output", o.output, "Output EXR (default out/<scene>.exr); a tonemapped PNG is written beside it");
    auto* sppOpt =
        render->add_option("--spp", o.spp, "Samples per pixel (default 64)")->check(CLI::Range(1u, 1u << 30));
    auto* timeOpt = render->add_option("--time", o.seconds, "Render for this many seconds instead of a fixed spp")
                        ->check(CLI::Range(0.001, 1e7));
    sppOpt->excludes(timeOpt);
    render
        ->add_option("--target-error", o.targetError,
            "Add samples until the estimated relMSE (from the image's own variance, no reference) is at most "
            "this; --spp or --time then cap the render")
        ->check(CLI::Range(1e-12, 1e6));
    render->add_option("--reference", o.reference, "Reference EXR: log relMSE after every pass");
    render->add_option("--error-log", o.errorLog, "CSV of spp, seconds, relMSE after every pass (needs --reference)");
    render->add_option("--tile", o.tileSize, "Split each pass into tiles of this many pixels square (same image)");
    render->add_option("--pass-spp", o.passSpp, "Samples per pass (default: passes of about two seconds; same image)");
    render
        ->add_option_function<std::string>(
            "--adaptive", [&o](const std::string& v) { o.adaptive = v == "on"; },
            "Adaptive sampling: more samples where the relative error is (spp and --pass-spp then count the mean "
            "per pixel): on|off (default on; off for --samples parts, which merge only when every pixel has the "
            "same samples)")
        ->check(CLI::IsMember({"on", "off"}));
    render->add_flag("-q,--quiet", o.quiet, "Only print the summary line and errors");
    render->add_flag("--list-variants", o.listVariants,
        "Print the scene's glTF material variants (KHR_materials_variants), one per line, and stop");
    render->add_flag(
        "--variance", o.varianceAov, "Add the variance of each pixel's mean to the EXR (channels variance.R/G/B)");
    auto* samplesOpt = render->add_option("--samples", o.samples,
        "Render sample indices A (inclusive) to B (exclusive) of the global sequence, for pt merge");
    samplesOpt->excludes(sppOpt)->excludes(timeOpt);
    render->add_option(
        "--checkpoint", o.checkpoint, "Save the accumulation state to this EXR periodically and on SIGINT/SIGTERM");
    render->add_option("--checkpoint-every", o.checkpointEvery, "Seconds of rendering between checkpoints (default 60)")
        ->check(CLI::Range(0.0, 1e9));
    render->add_option("--resume", o.resume, "Continue from a checkpoint (or a --samples part) of the same render");

    pt::ViewOptions v;
    v.render.tileSize = 64;
    SwitchWords viewWords;
    CLI::App* view =
        app.add_subcommand("view", "Interactive progressive preview in a window (keys: see README or press H)");
    addSceneOptions(view, v.render, viewWords);
    view->add_option("--spp", v.render.spp, "Stop refining at this many samples per pixel (default 1024)")
        ->check(CLI::Range(1u, 1u << 30));
    view->add_option("--tile", v.render.tileSize, "Tile side of a full-resolution pass spread over frames (default 64)")
        ->check(CLI::Range(8u, 4096u));
    view->add_option("--frame-ms", v.frameBudgetMs, "Rendering work per frame in ms, bounds input latency (default 20)")
        ->check(CLI::Range(1.0, 10000.0));
    view->add_option("-o,--output-dir", v.outputDir, "Folder for saved images and screenshots (default out)");
    view->add_option("--script", v.script, "Run timed inputs from FILE (tests, benchmarks; format in README)");

    pt::BenchOptions bench;
    SwitchWords benchWords;
    std::string budgetList;
    CLI::App* benchCmd = app.add_subcommand("bench",
        "Speed against error: render a scene under several integrator configurations to equal time budgets; "
        "writes a CSV, the images, a log-log plot and contact sheets");
    addSceneOptions(benchCmd, bench.render, benchWords);
    benchCmd->add_option("--reference", bench.reference, "Reference EXR (default: render one, see --reference-spp)");
    benchCmd
        ->add_option(
            "--reference-spp", bench.referenceSpp, "Samples of the reference made without --reference (default 4096)")
        ->check(CLI::Range(1u, 1u << 24));
    benchCmd->add_option("--budgets", budgetList, "Comma-separated time budgets in seconds (default 2,5,10,30,60)");
    benchCmd->add_option("--configs", bench.configs,
        "Comma-separated configurations, each words joined by '+': nee, is, rr, nomis, sobol, nolt, or none "
        "(default: the eight nee/is/rr combinations, nee+is+rr+nomis, nee+is+rr+sobol, nee+is+rr+nolt)");
    benchCmd->add_option("-o,--output-dir", bench.outputDir, "Output folder (default out/bench)");
    benchCmd->add_flag("!--no-plot", bench.plot, "Skip the plot and contact sheets (no python3 needed)");

    CLI::App* devices = app.add_subcommand("devices", "List Vulkan devices");

    pt::MergeOptions mergeOptions;
    CLI::App* merge = app.add_subcommand("merge", "Merge partial renders (pt render --samples A:B) into one image");
    pt::addMergeOptions(merge, mergeOptions);

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        // CLI11 prints the message; its own exit codes vary, ours are 0 (help) or 2 (usage).
        return app.exit(e) == 0 ? 0 : 2;
    }
    applySwitchWords(words, o);
    applySwitchWords(viewWords, v.render);
    if (!o.errorLog.empty() && o.reference.empty()) {
        std::fprintf(stderr, "pt: error: --error-log needs --reference\n");
        return 2;
    }
    try {
        if (*devices) return listDevices();
        if (*merge) return pt::runMerge(mergeOptions);
        if (*view) return pt::runView(v);
        if (*benchCmd) {
            applySwitchWords(benchWords, bench.render);
            if (!budgetList.empty()) {
                bench.budgets.clear();
                std::istringstream items(budgetList);
                for (std::string item; std::getline(items, item, ',');) {
                    size_t used = 0;
                    double value = 0;
                    try {
                        value = std::stod(item, &used);
                    } catch (const std::exception&) {
                        used = 0;
                    }
                    if (used == 0 || used != item.size())
                        throw std::runtime_error("--budgets: '" + item + "' is not a number of seconds");
                    bench.budgets.push_back(value);
                }
            }
            return pt::runBench(bench);
        }
        return pt::runRender(o);
    } catch (const std::bad_alloc&) {
        // What a scene's estimate (scene/memory_estimate.h) did not foresee: still one line.
        const pt::MemoryHeadroom headroom = pt::hostMemoryHeadroom();
        std::string limit;
        if (!headroom.limit.empty()) limit = "; " + headroom.limit + " leaves " + pt::formatBytes(headroom.bytes);
        std::fprintf(stderr, "pt: error: out of host memory (peak resident %s%s)\n",
            pt::formatBytes(pt::peakResidentBytes()).c_str(), limit.c_str());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "pt: error: %s\n", e.what());
        return 1;
    }
}
