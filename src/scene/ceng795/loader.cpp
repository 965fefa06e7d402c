#include "scene/ceng795/loader.h"

#include "image/file_read.h"
#include "image/image_io.h"
#include "image/texture_image.h"

#include "scene/ceng795/camera.h"
#include "scene/ceng795/document.h"
#include "scene/ceng795/geometry.h"
#include "scene/ceng795/materials.h"
#include "scene/ceng795/objects.h"
#include "scene/ceng795/transforms.h"
#include "scene/scene_error.h"

#include <algorithm>
#include <cmath>
#include <new>
#include <set>

namespace pt {
namespace {

using namespace ceng795;

// MaxRecursionDepth counts bounces after the camera ray (primary rays have depth 0); the
// renderer's depth counts ray segments including the camera ray.
constexpr long long kMaxRecursionDepth = (1 << 16) - 2;

void noteUnknownElements(Context& ctx, pugi::xml_node root) {
    static const std::set<std::string> known = {"MaxRecursionDepth", "BackgroundColor", "ShadowRayEpsilon",
        "IntersectionTestEpsilon", "ZeroBasedIndexing", "Cameras", "Lights", "Materials", "BRDFs", "Textures",
        "Transformations", "VertexData", "TexCoordData", "Objects"};
    // The epsilons are deliberately ignored: the renderer offsets rays robustly by itself.
    for (pugi::xml_node e : root.children())
        if (e.type() == pugi::node_element && !known.count(e.name()))
            ctx.note("element <" + printable(e.name()) + "> (ignored)");
}

void readSceneSettings(Context& ctx, pugi::xml_node root, Scene& s) {
    if (pugi::xml_node d = root.child("MaxRecursionDepth"))
        s.hints.maxDepth = static_cast<int>(integer(ctx, d, 0, kMaxRecursionDepth) + 1);
    // Absent, the course parser's default of 0 would mean camera rays only; better to leave
    // the depth to the renderer.
    if (pugi::xml_node b = root.child("BackgroundColor")) {
        s.background = vec3(ctx, b);
        if (s.background.x < 0.0f || s.background.y < 0.0f || s.background.z < 0.0f)
            ctx.fail(b, "must not be negative");
        // The course shows it to primary rays only; the renderer lights the scene with it too.
        if (s.background != glm::vec3(0.0f)) ctx.note("background seen only by primary rays");
    }
}

PunctualLight readPointLight(const Context& ctx, pugi::xml_node e) {
    PunctualLight l;
    l.type = PunctualLight::Type::Point;
    l.position = vec3(ctx, required(ctx, e, "Position"));
    // The course's Intensity is radiant intensity (E = I / d^2), as is the scene model's.
    pugi::xml_node i = required(ctx, e, "Intensity");
    l.intensity = vec3(ctx, i);
    if (l.intensity.x < 0.0f || l.intensity.y < 0.0f || l.intensity.z < 0.0f) ctx.fail(i, "must not be negative");
    return l;
}

PunctualLight readDirectionalLight(const Context& ctx, pugi::xml_node e) {
    PunctualLight l;
    l.type = PunctualLight::Type::Directional;
    // Direction is the way the light travels; its "Radiance" arrives undiminished with distance,
    // i.e. it is the irradiance on a surface facing the light, which is what the model stores.
    pugi::xml_node d = required(ctx, e, "Direction");
    const glm::vec3 direction = vec3(ctx, d);
    const float length = glm::length(direction);
    if (!(length > 0.0f) || !std::isfinite(length)) ctx.fail(d, "must be non-zero");
    l.direction = direction / length;
    pugi::xml_node r = required(ctx, e, "Radiance");
    l.intensity = vec3(ctx, r);
    if (l.intensity.x < 0.0f || l.intensity.y < 0.0f || l.intensity.z < 0.0f) ctx.fail(r, "must not be negative");
    return l;
}

glm::vec3 unitDirection(const Context& ctx, pugi::xml_node e, const char* child) {
    pugi::xml_node d = required(ctx, e, child);
    const glm::vec3 v = vec3(ctx, d);
    const float length = glm::length(v);
    if (!(length > 0.0f) || !std::isfinite(length)) ctx.fail(d, "must be non-zero");
    return v / length;
}

glm::vec3 nonNegativeColour(const Context& ctx, pugi::xml_node e, const char* child) {
    pugi::xml_node c = required(ctx, e, child);
    const glm::vec3 v = vec3(ctx, c);
    if (v.x < 0.0f || v.y < 0.0f || v.z < 0.0f) ctx.fail(c, "must not be negative");
    return v;
}

float angleDegrees(const Context& ctx, pugi::xml_node e, const char* child) {
    pugi::xml_node a = required(ctx, e, child);
    const float v = scalar(ctx, a);
    if (!(v > 0.0f && v <= 360.0f)) ctx.fail(a, "must be an angle in (0, 360] degrees");
    return v;
}

// SpotLight: CoverageAngle and FalloffAngle are full cone angles in degrees.
PunctualLight readSpotLight(Context& ctx, pugi::xml_node e) {
    PunctualLight l;
    l.type = PunctualLight::Type::Spot;
    l.position = vec3(ctx, required(ctx, e, "Position"));
    l.direction = unitDirection(ctx, e, "Direction");
    l.intensity = nonNegativeColour(ctx, e, "Intensity");
    const float coverage = angleDegrees(ctx, e, "CoverageAngle");
    float falloff = angleDegrees(ctx, e, "FalloffAngle");
    // The falloff cone lies inside the coverage cone; a wider one is cut to it.
    if (falloff > coverage) {
        ctx.note(label(e) + ": FalloffAngle " + formatNumber(falloff) + " wider than CoverageAngle (" +
                 formatNumber(coverage) + " assumed)");
        falloff = coverage;
    }
    l.cosCoverage = std::cos(glm::radians(0.5f * coverage));
    l.cosFalloff = std::cos(glm::radians(0.5f * falloff));
    return l;
}

// AreaLight: an invisible square (edge Size) emitting Radiance on the side Normal faces.
PunctualLight readAreaLight(const Context& ctx, pugi::xml_node e) {
    PunctualLight l;
    l.type = PunctualLight::Type::Square;
    l.position = vec3(ctx, required(ctx, e, "Position"));
    l.direction = unitDirection(ctx, e, "Normal");
    l.intensity = nonNegativeColour(ctx, e, "Radiance");
    pugi::xml_node size = required(ctx, e, "Size");
    l.size = scalar(ctx, size);
    if (!(l.size > 0.0f) || !std::isfinite(l.size)) ctx.fail(size, "must be positive");
    return l;
}

// SphericalDirectionalLight: a lat-long radiance map from <Textures><Images> (OpenEXR or Radiance .hdr).
void readEnvironmentLight(Context& ctx, pugi::xml_node root, pugi::xml_node e, Scene& s) {
    if (s.environment) ctx.fail(e, "only one environment light is supported");
    pugi::xml_node idNode = required(ctx, e, "ImageId");
    const std::string id = std::string(idNode.child_value());
    for (pugi::xml_node images : root.child("Textures").children("Images"))
        for (pugi::xml_node image : images.children("Image")) {
            if (std::string(image.attribute("id").value()) != id) continue;
            const std::string text = textOf(image);
            const std::vector<std::string_view> name = tokens(text);
            if (name.size() != 1) ctx.fail(image, "is not one file name");
            const std::filesystem::path file = ctx.resolve(name[0]);
            Environment env;
            try {
                env.image = loadRadianceImage(file);
            } catch (const std::exception& err) {
                ctx.fail(e, err.what());
            }
            env.source = file.string();
            s.environment = std::move(env);
            return;
        }
    ctx.fail(idNode, "unknown image " + quote(id));
}

// Point and directional lights map onto the model's punctual lights; the others are named once
// and skipped (object lights are objects, read with the geometry).
void readLights(Context& ctx, pugi::xml_node root, Scene& s) {
    for (pugi::xml_node lights : root.children("Lights"))
        for (pugi::xml_node l : lights.children()) {
            if (l.type() != pugi::node_element) continue;
            const std::string type = l.name();
            if (type == "AmbientLight") {
                // The course adds ka * Ia: the classic integrator does, path tracing has no such term.
                s.ambientLight = vec3(ctx, l);
                if (glm::any(glm::lessThan(s.ambientLight, glm::vec3(0.0f)))) ctx.fail(l, "must not be negative");
            } else if (type == "PointLight")
                s.punctualLights.push_back(readPointLight(ctx, l));
            else if (type == "DirectionalLight")
                s.punctualLights.push_back(readDirectionalLight(ctx, l));
            else if (type == "AreaLight")
                s.punctualLights.push_back(readAreaLight(ctx, l));
            else if (type == "SpotLight")
                s.punctualLights.push_back(readSpotLight(ctx, l));
            else if (type == "SphericalDirectionalLight")
                readEnvironmentLight(ctx, root, l, s);
            else
                ctx.note(printable(type) + " lights (ignored)");
        }
}

Scene importScene(Context& ctx, pugi::xml_node root) {
    Scene s;
    s.source = ctx.file();
    noteUnknownElements(ctx, root);
    readSceneSettings(ctx, root, s);
    readLights(ctx, root, s);
    MaterialTable materials = MaterialTable::read(ctx, root, s.materials);
    TextureTable textures = TextureTable::read(ctx, root, s);
    const Transforms transforms = Transforms::read(ctx, root);
    const VertexPool pool = readVertexPool(ctx, root);
    readObjects(ctx, root, pool, transforms, materials, textures, s);
    materials.noteUsed(ctx);
    if (s.meshes.empty() && s.instances.empty() && s.spheres.empty()) ctx.fail("no objects to render");
    s.cameras = readCameras(ctx, root, s.hints.maxDepth);
    s.unsupported = ctx.notes();
    // The classic integrator models the diffuse and specular layers of mirrors, conductors and
    // glass; the notes about them concern path tracing only.
    const bool allClassic = std::all_of(
        s.cameras.begin(), s.cameras.end(), [](const Camera& c) { return c.settings.classic.value_or(false); });
    if (allClassic && !s.cameras.empty())
        std::erase_if(s.unsupported, [](const std::string& n) {
            return n.find("with diffuse layer") != std::string::npos ||
                   n.find("with specular highlights") != std::string::npos;
        });
    return s;
}

// pugixml reports a byte offset; a line number is what an editor can jump to.
size_t lineAt(std::string_view text, ptrdiff_t offset) {
    const size_t end = std::min(text.size(), static_cast<size_t>(std::max<ptrdiff_t>(0, offset)));
    return 1 + static_cast<size_t>(std::count(text.begin(), text.begin() + static_cast<ptrdiff_t>(end), '\n'));
}

} // namespace

Scene loadCeng795Text(std::string_view xml, const std::string& displayName, const std::filesystem::path& baseDir) {
    Context ctx(displayName, baseDir);
    pugi::xml_document doc;
    const pugi::xml_parse_result parsed =
        doc.load_buffer(xml.data(), xml.size(), pugi::parse_default, pugi::encoding_auto);
    if (!parsed)
        ctx.fail("malformed XML at offset " + std::to_string(parsed.offset) + " (line " +
                 std::to_string(lineAt(xml, parsed.offset)) + "): " + parsed.description());
    pugi::xml_node root = doc.document_element();
    if (std::string(root.name()) != "Scene")
        ctx.fail("root element is <" + std::string(root.name()) + ">, expected <Scene>");
    return importScene(ctx, root);
}

// By the input-file policy (image/file_read.h), in its words: this reader's are where they came
// from. Devices and FIFOs are read to their end, as before the policy (a scene can come through a
// pipe); emptiness is checked after the read, so that an unreadable empty file says so.
Scene loadCeng795File(const std::filesystem::path& xml) {
    const std::string name = xml.string();
    const FileRead file = tryReadInputFile(xml, {.streamNonRegular = true});
    if (file.problem == FileProblem::CannotAccess) throw SceneError(name, "file not found");
    if (file.problem == FileProblem::OutOfMemory) throw std::bad_alloc();
    if (!file) throw SceneError(name, describeFileProblem(file, "a scene file"));
    if (file.bytes.empty()) throw SceneError(name, "empty file");
    return loadCeng795Text(
        std::string_view(reinterpret_cast<const char*>(file.bytes.data()), file.bytes.size()), name, xml.parent_path());
}

} // namespace pt
