#include "app/view_command.h"

#include "app/context_options.h"
#include "app/scene_setup.h"
#include "gpu/vulkan_context.h"
#include "render/light_visibility_probe.h"
#include "viewer/script.h"
#include "viewer/viewer.h"
#include "viewer/window.h"

#include <cstdio>
#include <memory>

namespace pt {
namespace {

int noDisplay(const std::string& why) {
    std::fprintf(stderr, "pt: error: pt view: %s; render to a file with 'pt render' instead\n", why.c_str());
    return 1;
}

} // namespace

int runView(const ViewOptions& v) {
    const RenderOptions& o = v.render;
    // Cheap checks first: no display, or a bad script, fail before the scene loads.
    if (std::string why = viewer::missingDisplayReason(); !why.empty()) return noDisplay(why);
    viewer::ViewerConfig config;
    if (!v.script.empty()) {
        config.script = viewer::loadScript(v.script);
        config.scripted = true;
    }

    Scene scene = loadSceneWithOptions(o);
    const bool course = isCourseScene(o.scene);
    // One camera: --camera's, else the first (course scenes too).
    RenderOptions pick = o;
    if (course && !pick.camera && !scene.cameras.empty()) pick.camera = scene.cameras.front().id;
    const Camera camera = chooseCameras(scene, pick, course).front();
    config.job = makeJob(scene, camera, o, false, course);
    config.job.target.adaptive = false; // the viewer's passes sample every pixel alike
    FlatScene flat = flattenWithNotes(scene, o);

    config.sceneSource = scene.source;
    config.sceneStem = sceneStem(o.scene);
    config.background = scene.background;
    config.sppCap = o.spp.value_or(1024u);
    config.tileSize = o.tileSize ? o.tileSize : 64u;
    config.frameBudgetMs = v.frameBudgetMs;
    config.exposure = o.exposure;
    config.outputDir = v.outputDir;

    try {
        viewer::Window window(config.job.width, config.job.height, "pt view: " + config.sceneStem);
        ContextOptions contextOptions = contextOptionsFor(o);
        contextOptions.instanceExtensions = viewer::Window::requiredInstanceExtensions();
        contextOptions.createSurface = [&](VkInstance instance) { return window.createSurface(instance); };
        std::unique_ptr<VulkanContext> context;
        try {
            context = std::make_unique<VulkanContext>(contextOptions);
        } catch (const viewer::NoDisplayError&) {
            throw;
        } catch (const std::exception& e) {
            throw viewer::NoDisplayError(std::string("no Vulkan device can present to the window: ") + e.what());
        }
        std::fprintf(stderr, "pt: view: %s: %zu triangles, %zu spheres, %zu lights; device %s (%s)\n",
            scene.source.c_str(), flat.triangles.size(), flat.spheres.size(), flat.lights.lights.size(),
            context->info().name.c_str(), context->info().driver.c_str());
        const std::string loadsNote = chooseGeometryLoads(*context, o, config.job.settings);
        if (!loadsNote.empty()) std::fprintf(stderr, "pt: view: %s\n", loadsNote.c_str());
        // --integrator auto decides as pt render does (the probe needs the device).
        const std::string autoNote = measureForAutoIntegrator(
            *context, flat, config.job.settings, config.job.camera, config.job.width, config.job.height);
        if (!autoNote.empty()) std::fprintf(stderr, "pt: view: %s\n", autoNote.c_str());
        int status = viewer::runViewer(window, *context, flat, config);
        if (o.validation && context->validationMessageCount() > 0) {
            std::fprintf(stderr, "pt: error: Vulkan validation reported %u message(s); first: %s\n",
                context->validationMessageCount(), context->firstValidationMessage().c_str());
            return 3;
        }
        return status;
    } catch (const viewer::NoDisplayError& e) {
        return noDisplay(e.what());
    }
}

} // namespace pt
