#pragma once
// What `pt render` and `pt view` share: loading a scene with the command line's environment,
// flattening it with the usual notes, and turning a camera plus options into an image job
// (size, integrator settings, sample target, tone mapping, output file).
#include "app/options.h"
#include "flatten/flat_scene.h"
#include "gpu/vulkan_context.h"
#include "image/atomic_file.h" // prepareOutputDirectory
#include "render/job.h"
#include "scene/scene.h"

#include <filesystem>
#include <string>
#include <vector>

namespace pt {

// "No depth cap": deep enough that Russian roulette, not the cap, ends every path in practice.
constexpr int kUncappedDepth = 256;

// Output file stem for a scene path ("cornell-box" for the built-in scene).
std::string sceneStem(const std::string& scene);
bool isCourseScene(const std::string& scene);

// Loads the scene (none: the built-in Cornell box), applies --env / --env-colour and their
// scale and rotation, and warns once about anything rendered approximately.
Scene loadSceneWithOptions(const RenderOptions& o);
// flattenScene plus the notes about dropped primitives and the warning for a scene without light.
FlatScene flattenWithNotes(const Scene& scene, const RenderOptions& o);
// Frees what flattening copied (meshes, texture images), keeping what the render still reads
// (source, cameras, background, environment, hints).
void releaseFlattenedParts(Scene& scene);

// The camera for a scene without one (most glTF sample models): it looks down -z at the scene
// (glTF's front; a scene flat in y from 45 degrees above, one flat in x from +x) and stands where
// every vertex lies within kFramingFill of the image's half-width and half-height, centred, for an
// image of `aspect` (width / height): the scene fills that fraction of its limiting dimension.
constexpr float kFramingFill = 0.9f;
Camera framingCamera(const Scene& scene, float aspect);

// The cameras to render: --camera picks one (a glTF index, a course camera id); glTF renders
// its first camera by default, a course scene every camera (one image each, as the course does);
// a scene without cameras gets framingCamera for the image size the options give.
std::vector<Camera> chooseCameras(const Scene& scene, const RenderOptions& o, bool course);
// Warns (stderr) about every render setting the camera's file leaves out and pt fills in, unless
// the command line gives it (course cameras: ImageResolution, NumSamples, ImageName).
Job makeJob(const Scene& scene, const Camera& camera, const RenderOptions& o, bool severalImages, bool course);

// The max depth a camera renders at, and why: --max-depth; else a course camera's own convention
// (path tracing: MaxRecursionDepth + 1, the camera ray plus MaxRecursionDepth bounces, or + 2 when
// the camera uses NEE, whose renderer adds direct light at the last vertex, one segment deeper;
// Russian roulette: no cap; classic: MaxRecursionDepth + 1); else the scene's; else 16.
struct DepthChoice {
    int depth = 16;
    std::string reason; // for the log line; empty when the command line chose
};
DepthChoice chooseMaxDepth(const Scene& scene, const Camera& camera, const RenderOptions& o, bool course);
// --texel-loads auto on a CPU device: settings.texelLoads off where this machine was measured to
// render faster through buffer addresses (render/texel_load_choice.h). Returns the log line, empty
// where nothing was chosen.
std::string chooseGeometryLoads(VulkanContext& context, const RenderOptions& o, IntegratorSettings& settings);

// IntegratorSettings::describe() with the depth's reason after max-depth, for the log line.
std::string describeIntegrator(const Job& job);

} // namespace pt
