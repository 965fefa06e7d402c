#include "app/scene_setup.h"

#include "image/image_io.h"
#include "render/renderer.h"
#include "render/texel_load_choice.h"
#include "scene/scene_loader.h"
#include "image/texture_image.h"

#include <algorithm>
#include <limits>
#include <cmath>
#include <cstdio>

namespace pt {
namespace {

namespace fs = std::filesystem;

std::string joinNotes(const std::vector<std::string>& notes) {
    std::string s;
    for (const auto& n : notes) s += (s.empty() ? "" : "; ") + n;
    return s;
}

// One warning line per value the scene file lacks and pt filled in.
void warnAssumed(const Scene& scene, const Camera& camera, const std::string& what) {
    std::fprintf(stderr, "pt: warning: %s: %s: %s\n", scene.source.c_str(), camera.name.c_str(), what.c_str());
}

} // namespace

Scene loadSceneWithOptions(const RenderOptions& o) {
    Scene scene = loadScene(o.scene, o.variant);
    if (!o.environment.empty()) {
        Environment env;
        env.image = loadRadianceImage(o.environment);
        env.source = o.environment;
        scene.environment = env;
    } else if (o.environmentColour) {
        Environment env;
        env.colour = *o.environmentColour;
        env.source = "--env-colour";
        scene.environment = env;
    }
    if (scene.environment) {
        scene.environment->scale *= o.environmentScale;
        scene.environment->rotationDegrees += o.environmentRotation;
    }
    // The loaders' notes: features not modelled yet, and values the file lacks (or gives out of
    // range) that the loader filled in, which say "... assumed)"; one warning line each.
    std::vector<std::string> approximated, assumed;
    for (const std::string& n : scene.unsupported)
        (n.find(" assumed)") != std::string::npos ? assumed : approximated).push_back(n);
    if (!approximated.empty())
        std::fprintf(stderr, "pt: warning: %s: not supported yet, rendered approximately: %s\n", scene.source.c_str(),
            joinNotes(approximated).c_str());
    if (!assumed.empty())
        std::fprintf(stderr, "pt: warning: %s: values assumed: %s\n", scene.source.c_str(), joinNotes(assumed).c_str());
    // Without MaxRecursionDepth the course parser's default of 0 would stop at the camera ray.
    const bool capped = std::any_of(scene.cameras.begin(), scene.cameras.end(),
        [](const Camera& c) { return !c.settings.russianRoulette.value_or(false); });
    if (isCourseScene(o.scene) && !scene.hints.maxDepth && !o.maxDepth && capped)
        std::fprintf(stderr,
            "pt: warning: %s: no MaxRecursionDepth: max depth 16, pt's default (the course parser's 0 would trace "
            "camera rays only; --max-depth to choose)\n",
            scene.source.c_str());
    return scene;
}

FlatScene flattenWithNotes(const Scene& scene, const RenderOptions& o) {
    BvhBuildOptions bvh;
    bvh.instancing = o.instancing;
    FlatScene flat = flattenScene(scene, bvh);
    if (!flat.instancing.empty() && !o.quiet)
        std::fprintf(stderr, "pt: %s: %s\n", scene.source.c_str(), flat.instancing.c_str());
    if (flat.degenerateTriangles > 0)
        std::fprintf(stderr, "pt: note: %s: dropped %zu degenerate (zero-area) triangles\n", scene.source.c_str(),
            flat.degenerateTriangles);
    if (flat.degenerateSpheres > 0)
        std::fprintf(stderr, "pt: note: %s: dropped %zu spheres with a singular transform\n", scene.source.c_str(),
            flat.degenerateSpheres);
    if (flat.degenerateInstances > 0)
        std::fprintf(stderr, "pt: note: %s: dropped %zu instances with a singular or non-finite transform\n",
            scene.source.c_str(), flat.degenerateInstances);
    // Unlit surfaces (glTF KHR_materials_unlit, the course's replace_all) show their colour
    // without light, outside the light table.
    const bool anyUnlit =
        std::any_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) { return m.unlit; });
    if (flat.lights.lights.empty() && scene.background == glm::vec3(0.0f) && flat.environment.width == 0 && !anyUnlit)
        std::fprintf(stderr,
            "pt: warning: %s: nothing emits light (no emissive surfaces or lights, black background): "
            "the image will be black\n",
            scene.source.c_str());
    return flat;
}

void releaseFlattenedParts(Scene& scene) {
    std::vector<Mesh>().swap(scene.meshes);
    std::vector<SharedMesh>().swap(scene.sharedMeshes);
    std::vector<TextureImage>().swap(scene.textureImages);
}

std::string sceneStem(const std::string& scene) {
    std::string stem = scene.empty() ? "cornell-box" : fs::path(scene).stem().string();
    if (stem == "scene") stem = fs::path(scene).parent_path().filename().string(); // refs/<name>/scene.gltf
    return stem.empty() ? "render" : stem;
}

bool isCourseScene(const std::string& scene) {
    std::string ext = fs::path(scene).extension().string();
    for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".xml";
}

namespace {

// Calls f(p) for every point the framing camera must see: each vertex (at both ends of its motion)
// and 26 points on each ellipsoid (the directions of a cube's faces, edges and corners), which bound
// its silhouette within 5%.
template <typename F>
void forEachFramingPoint(const Scene& scene, F&& f) {
    for (const Mesh& m : scene.meshes)
        for (const glm::vec3& p : m.positions) {
            f(p);
            if (m.motion != glm::vec3(0.0f)) f(p + m.motion);
        }
    // An instance: the corners of its mesh's box, placed (a box around the placed mesh).
    for (const MeshInstance& instance : scene.instances) {
        if (instance.mesh >= scene.sharedMeshes.size()) continue;
        glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
        for (const Mesh& part : scene.sharedMeshes[instance.mesh].parts)
            for (const glm::vec3& p : part.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
        if (!(lo.x <= hi.x)) continue;
        for (int corner = 0; corner < 8; ++corner) {
            const glm::vec3 c((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z);
            const glm::vec3 p(instance.objectToWorld * glm::vec4(c, 1.0f));
            f(p);
            if (instance.motion != glm::vec3(0.0f)) f(p + instance.motion);
        }
    }
    for (const Sphere& s : scene.spheres)
        for (int x = -1; x <= 1; ++x)
            for (int y = -1; y <= 1; ++y)
                for (int z = -1; z <= 1; ++z) {
                    if (x == 0 && y == 0 && z == 0) continue;
                    const glm::vec3 p(s.objectToWorld * glm::vec4(glm::normalize(glm::vec3(x, y, z)), 1.0f));
                    f(p);
                    if (s.motion != glm::vec3(0.0f)) f(p + s.motion);
                }
}

// The image aspect of a camera without settings, sized as makeJob sizes it: the command line, then
// the scene's hints, then 512 wide; square unless a height is given.
float framingAspect(const Scene& scene, const RenderOptions& o) {
    const int width = o.width.value_or(scene.hints.width.value_or(512));
    int height = width;
    if (o.height)
        height = *o.height;
    else if (!o.width && scene.hints.height)
        height = *scene.hints.height;
    return width > 0 && height > 0 ? static_cast<float>(width) / static_cast<float>(height) : 1.0f;
}

} // namespace

Camera framingCamera(const Scene& scene, float aspect) {
    Camera c;
    c.name = "framing camera";
    c.yfov = 0.8f;
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    forEachFramingPoint(scene, [&](const glm::vec3& p) { lo = glm::min(lo, p), hi = glm::max(hi, p); });
    if (!(lo.x <= hi.x)) return c; // nothing to frame
    const glm::vec3 extent = hi - lo;
    const float largest = std::max({extent.x, extent.y, extent.z});
    // glTF's front is +z: look down -z, unless that sees a flat scene edge-on: a floor (flat in y)
    // is seen from 45 degrees above the front, a wall facing x from +x.
    if (extent.y <= 0.1f * largest && extent.y <= extent.x && extent.y <= extent.z) {
        c.forward = glm::normalize(glm::vec3(0, -1, -1));
        c.up = glm::normalize(glm::vec3(0, 1, -1));
    } else if (extent.x <= 0.1f * largest && extent.x <= extent.z) {
        c.forward = glm::vec3(-1, 0, 0);
    }
    // The renderer's frame (toGpuCamera); a point p - centre = u right + v up + w forward, seen from
    // centre + s right + q up - t forward, is at x = (u - s) / ((t + w) tan(xfov / 2)) of the
    // half-width. Every point lies within kFramingFill of the half-width and half-height when
    // t >= |u - s| / tx - w and t >= |v - q| / ty - w, with tx, ty kFramingFill times the tangents.
    const glm::vec3 right = glm::normalize(glm::cross(c.forward, c.up));
    const glm::vec3 up = glm::cross(right, c.forward);
    const float ty = kFramingFill * std::tan(0.5f * c.yfov), tx = ty * aspect;
    const glm::vec3 centre = 0.5f * (lo + hi);
    const float margin = 1e-2f * 0.5f * glm::length(extent); // never closer to a point than this
    float s = 0.0f, q = 0.0f;
    const auto distance = [&] {
        float t = -INFINITY;
        forEachFramingPoint(scene, [&](const glm::vec3& p) {
            const glm::vec3 d = p - centre;
            const float w = glm::dot(d, c.forward);
            t = std::max(
                {t, std::abs(glm::dot(d, right) - s) / tx - w, std::abs(glm::dot(d, up) - q) / ty - w, margin - w});
        });
        return t;
    };
    // Centred: shifted sideways until the outermost points on either side project symmetrically
    // (perspective makes a near edge look larger than a far one), then moved back to fit.
    for (int iteration = 0; iteration < 4; ++iteration) {
        const float t = distance();
        struct Extreme {
            float ndc, offset, depth;
        };
        Extreme xlo{INFINITY, 0, 1}, xhi{-INFINITY, 0, 1}, ylo{INFINITY, 0, 1}, yhi{-INFINITY, 0, 1};
        forEachFramingPoint(scene, [&](const glm::vec3& p) {
            const glm::vec3 d = p - centre;
            const float depth = t + glm::dot(d, c.forward), u = glm::dot(d, right), v = glm::dot(d, up);
            const float x = (u - s) / depth, y = (v - q) / depth;
            if (x < xlo.ndc) xlo = {x, u, depth};
            if (x > xhi.ndc) xhi = {x, u, depth};
            if (y < ylo.ndc) ylo = {y, v, depth};
            if (y > yhi.ndc) yhi = {y, v, depth};
        });
        // (hi.offset - s') / hi.depth = (s' - lo.offset) / lo.depth
        s = (xhi.offset * xlo.depth + xlo.offset * xhi.depth) / (xlo.depth + xhi.depth);
        q = (yhi.offset * ylo.depth + ylo.offset * yhi.depth) / (ylo.depth + yhi.depth);
    }
    const float t = distance();
    c.position = centre + s * right + q * up - (std::isfinite(t) && t > 0.0f ? t : 1.0f) * c.forward;
    return c;
}

std::vector<Camera> chooseCameras(const Scene& scene, const RenderOptions& o, bool course) {
    if (scene.cameras.empty()) {
        if (o.camera && *o.camera != 0)
            throw std::runtime_error(
                scene.source + ": --camera " + std::to_string(*o.camera) + ": the scene has no cameras");
        std::fprintf(stderr, "pt: note: %s has no camera; using one that frames the scene\n", scene.source.c_str());
        return {framingCamera(scene, framingAspect(scene, o))};
    }
    if (course) {
        if (!o.camera) return scene.cameras;
        for (const auto& c : scene.cameras)
            if (c.id == *o.camera) return {c};
        std::string ids;
        for (const auto& c : scene.cameras) ids += (ids.empty() ? "" : " ") + std::to_string(c.id);
        throw std::runtime_error(
            scene.source + ": --camera " + std::to_string(*o.camera) + ": no camera with that id (ids: " + ids + ")");
    }
    const int index = o.camera.value_or(0);
    if (index < 0 || index >= static_cast<int>(scene.cameras.size()))
        throw std::runtime_error(scene.source + ": --camera " + std::to_string(index) +
                                 " is out of range (the scene has " + std::to_string(scene.cameras.size()) +
                                 " camera(s))");
    return {scene.cameras[index]};
}

namespace {
// A render resumed from a state whose pixels all have the same samples (a --samples part, or a
// checkpoint of --adaptive off) continues that way unless --adaptive says otherwise. A file that
// cannot be read is left to the resume's own error.
bool resumesUniformState(const std::string& resume) {
    if (resume.empty()) return false;
    try {
        ImageMetadata metadata;
        readExrChannels(resume, {}, &metadata);
        return metadata["adaptive"] != "1";
    } catch (const std::exception&) {
        return false;
    }
}
} // namespace

Job makeJob(const Scene& scene, const Camera& camera, const RenderOptions& o, bool severalImages, bool course) {
    Job job;
    job.camera = camera;
    const CameraRenderSettings& cs = camera.settings;
    // Size: command line, then the camera's, then the scene's hints, then 512 wide.
    job.width = o.width.value_or(cs.width.value_or(scene.hints.width.value_or(512)));
    if (o.height)
        job.height = *o.height;
    else if (!o.width && cs.height)
        job.height = *cs.height;
    else if (!o.width && scene.hints.height)
        job.height = *scene.hints.height;
    else if (camera.aspectRatio > 0)
        job.height = std::max(1, static_cast<int>(std::lround(job.width / camera.aspectRatio)));
    else
        job.height = job.width;
    // A size that came from the scene file (its camera, extras or aspect ratio) is the file's problem.
    try {
        validateImageSize(job.width, job.height);
    } catch (const std::exception& e) {
        if (o.width && o.height) throw;
        throw std::runtime_error(scene.source + ": " + e.what());
    }
    // A course camera names its image size, samples and file; where one lacks a value that the
    // command line does not give either, say what pt assumed.
    if (course && !cs.width && !(o.width && o.height))
        warnAssumed(scene, camera,
            "no ImageResolution: rendered at " + std::to_string(job.width) + "x" + std::to_string(job.height));

    IntegratorSettings& s = job.settings;
    s = o.integrator;
    s.classic = o.classic.value_or(cs.classic.value_or(false));
    s.nee = o.nee.value_or(cs.nee.value_or(true));
    s.mis = o.mis.value_or(true);
    s.rr = o.rr.value_or(cs.russianRoulette.value_or(true));
    s.sampling = o.sampling.value_or(
        cs.importanceSampling.value_or(true) ? DirectionSampling::Cosine : DirectionSampling::Uniform);
    const DepthChoice depth = chooseMaxDepth(scene, camera, o, course);
    if (depth.depth < 1) throw std::runtime_error("max depth must be at least 1");
    s.maxDepth = static_cast<uint32_t>(depth.depth);
    job.maxDepthReason = depth.reason;

    job.target.spp = o.spp.value_or(o.seconds || o.targetError ? 0u : cs.spp.value_or(64u));
    if (course && !o.spp && !o.seconds && !o.targetError && !cs.spp)
        warnAssumed(scene, camera,
            "no NumSamples: " + std::to_string(job.target.spp) +
                " samples per pixel (the course's default of 1 suits only its deterministic ray tracer; --spp to "
                "choose)");
    job.target.seconds = o.seconds.value_or(0.0);
    job.target.targetError = o.targetError.value_or(0.0);
    job.target.passSpp = o.passSpp;
    job.target.tileSize = o.tileSize;
    if (o.adaptive.value_or(false) && !o.samples.empty())
        throw std::runtime_error("--adaptive on cannot render a --samples part: parts merge only when every pixel "
                                 "has the same samples");
    job.target.adaptive = o.adaptive.value_or(o.samples.empty() && !resumesUniformState(o.resume));
    job.tonemap = cs.tonemap.value_or(TonemapSettings{});

    // Output: -o FILE.exr names the file (one image only); any other -o is a folder for the
    // images, named by their ImageName (course scenes) or the scene; the default folder is out/.
    fs::path name = cs.imageName.empty() ? fs::path(sceneStem(o.scene) + ".exr") : fs::path(cs.imageName).filename();
    name.replace_extension(".exr");
    const fs::path requested(o.output);
    if (requested.extension() == ".exr") {
        if (severalImages)
            throw std::runtime_error(
                o.output + ": several cameras render several images: give a folder, or pick one with --camera");
        job.output = requested;
    } else if (!o.output.empty() && (course || fs::is_directory(requested))) {
        job.output = requested / name;
    } else if (!o.output.empty()) {
        throw std::runtime_error(o.output + ": output must end in .exr (or be a folder)");
    } else {
        job.output = fs::path("out") / name;
    }
    if (course && cs.imageName.empty() && requested.extension() != ".exr")
        warnAssumed(scene, camera, "no ImageName: written to " + job.output.string());
    return job;
}

DepthChoice chooseMaxDepth(const Scene& scene, const Camera& camera, const RenderOptions& o, bool course) {
    const CameraRenderSettings& cs = camera.settings;
    if (o.maxDepth) return {static_cast<int>(*o.maxDepth), ""};
    // The course's official path-tracing images apply Russian roulette without a depth cap
    // (docs/ceng795-format.md section 8): such cameras get a cap so high that only roulette ends paths.
    if (course && cs.russianRoulette.value_or(false) && !cs.maxDepth)
        return {kUncappedDepth, "course: Russian roulette without a depth cap"};
    if (course && cs.maxDepth) {
        // The loader gives MaxRecursionDepth + 1: the camera ray plus MaxRecursionDepth bounces,
        // which is how the course's renderer counts without NEE (and in its classic ray tracer).
        // With NEE it also adds the light sampled at the last vertex, one segment deeper: its NEE
        // images match pt at MaxRecursionDepth + 2 (bench/RESULTS.md, the HW6 boxes). The camera's
        // own NEE decides, not --nee: a switch changes the estimator, never the image.
        const int recursion = *cs.maxDepth - 1;
        const std::string base = "course: MaxRecursionDepth " + std::to_string(recursion);
        if (cs.classic.value_or(false)) return {recursion + 1, base + " + 1"};
        if (cs.nee.value_or(false)) return {recursion + 2, base + " + 2 with NEE"};
        return {recursion + 1, base + " + 1 without NEE"};
    }
    if (cs.maxDepth) return {*cs.maxDepth, "the camera's"};
    if (scene.hints.maxDepth) return {*scene.hints.maxDepth, "the scene's"};
    return {16, course ? "pt's default: the file has no MaxRecursionDepth" : "pt's default"};
}

std::string describeIntegrator(const Job& job) {
    std::string text = job.settings.describe();
    const std::string key = "max-depth=" + std::to_string(job.settings.maxDepth);
    const size_t at = text.find(key);
    if (!job.maxDepthReason.empty() && at != std::string::npos)
        text.insert(at + key.size(), " (" + job.maxDepthReason + ")");
    return text;
}

std::string chooseGeometryLoads(VulkanContext& context, const RenderOptions& o, IntegratorSettings& settings) {
    if (!o.measureTexelLoads || !settings.texelLoads) return {};
    const std::optional<TexelLoadChoice> choice = chooseTexelLoads(context);
    if (!choice) return {};
    settings.texelLoads = choice->texelLoads;
    return describeTexelLoadChoice(*choice);
}

} // namespace pt
