#include "scene/ceng795/camera.h"

#include <cmath>
#include <limits>

namespace pt::ceng795 {
namespace {

constexpr long long kMaxImageSide = 1 << 16;
constexpr long long kMaxSamples = 1 << 20;

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Position, forward and up. The course builds w = -gaze, v = up, u = v x w and re-orthogonalises
// v = w x u; pt's forward/up/right = forward x up is the same frame for a right-handed camera.
void readView(const Context& ctx, pugi::xml_node e, Camera& c) {
    c.position = vec3(ctx, required(ctx, e, "Position"));
    glm::vec3 gaze;
    // lookAt cameras normally give a GazePoint, but the official HW6 Cornell files give a Gaze
    // direction with type="lookAt", so whichever is present wins, regardless of type.
    if (pugi::xml_node p = e.child("GazePoint"))
        gaze = vec3(ctx, p) - c.position;
    else if (pugi::xml_node g = e.child("Gaze"))
        gaze = vec3(ctx, g);
    else
        ctx.fail(e, "missing <Gaze> or <GazePoint>");
    const float gazeLength = glm::length(gaze);
    if (!(gazeLength > 0.0f) || !std::isfinite(gazeLength)) ctx.fail(e, "gaze direction is zero");
    c.forward = gaze / gazeLength;
    const glm::vec3 up = vec3(ctx, required(ctx, e, "Up"));
    const glm::vec3 orthogonal = up - glm::dot(up, c.forward) * c.forward;
    const float upLength = glm::length(orthogonal);
    if (!(upLength > 1e-6f * glm::length(up)) || !finite(orthogonal)) ctx.fail(e, "Up is zero or parallel to the gaze");
    c.up = orthogonal / upLength;
}

void readResolution(const Context& ctx, pugi::xml_node e, Camera& c) {
    pugi::xml_node r = e.child("ImageResolution");
    if (!r) return;
    const std::vector<long long> wh = integers(ctx, r);
    if (wh.size() != 2) ctx.fail(r, "expected width and height");
    for (long long v : wh)
        if (v < 1 || v > kMaxImageSide)
            ctx.fail(r, std::to_string(v) + " is out of range [1, " + std::to_string(kMaxImageSide) + "]");
    c.settings.width = static_cast<int>(wh[0]);
    c.settings.height = static_cast<int>(wh[1]);
    c.aspectRatio = static_cast<float>(wh[0]) / static_cast<float>(wh[1]);
}

// NearPlane (l, r, b, t) at NearDistance d: the renderer's window is the same frustum at unit
// distance. yfov is set too, for anything that only understands a symmetric field of view.
void readNearPlane(const Context& ctx, pugi::xml_node e, pugi::xml_node plane, Camera& c) {
    const std::vector<double> v = numbers(ctx, plane);
    // The official 2024 HW1 spheres files write "-1 1 -1 1 10" (the near distance repeated);
    // the course parser reads four numbers and ignores the rest, so a fifth is tolerated.
    if (v.size() != 4 && v.size() != 5)
        ctx.fail(plane, "expected left right bottom top, found " + std::to_string(v.size()) + " numbers");
    pugi::xml_node dn = required(ctx, e, "NearDistance");
    const double d = scalar(ctx, dn);
    if (!(d > 0.0)) ctx.fail(dn, "must be positive");
    const double l = v[0] / d, r = v[1] / d, b = v[2] / d, t = v[3] / d;
    if (!(l < r) || !(b < t)) ctx.fail(plane, "needs left < right and bottom < top");
    c.window = glm::vec4(l, r, b, t);
    if (!std::isfinite(c.window->x) || !std::isfinite(c.window->y) || !std::isfinite(c.window->z) ||
        !std::isfinite(c.window->w))
        ctx.fail(plane, "number out of range");
    c.yfov = static_cast<float>(std::atan(t) - std::atan(b));
}

void readFovY(const Context& ctx, pugi::xml_node fov, Camera& c) {
    const float degrees = scalar(ctx, fov);
    if (!(degrees > 0.0f && degrees < 180.0f)) ctx.fail(fov, "must be in (0, 180) degrees");
    c.yfov = glm::radians(degrees);
}

// handedness="left": the course then takes u = w x v, the negative of the right-handed u, so
// image columns run the other way along pt's right = forward x up. The image is the mirror
// image; we express that with the window: left and right negated, i.e. left > right. The
// renderer maps column i to l + (i + 0.5) (r - l) / width, which then runs right to left.
void mirrorForLeftHandedness(Context& ctx, Camera& c) {
    if (!c.window) {
        if (c.aspectRatio <= 0.0f) {
            ctx.note("left-handed camera without ImageResolution (rendered right-handed)");
            return;
        }
        const float t = std::tan(0.5f * c.yfov);
        c.window = glm::vec4(-t * c.aspectRatio, t * c.aspectRatio, -t, t);
    }
    c.window->x = -c.window->x;
    c.window->y = -c.window->y;
}

void readProjection(Context& ctx, pugi::xml_node e, Camera& c) {
    // Whichever is present, regardless of type (2018 files put FovY on type="simple").
    if (pugi::xml_node plane = e.child("NearPlane"))
        readNearPlane(ctx, e, plane, c);
    else if (pugi::xml_node fov = e.child("FovY"))
        readFovY(ctx, fov, c);
    else
        ctx.fail(e, "missing <NearPlane> or <FovY>");
    const std::string handedness = lowercase(e.attribute("handedness").value());
    if (handedness == "left")
        mirrorForLeftHandedness(ctx, c);
    else if (!handedness.empty() && handedness != "right")
        ctx.fail(e, "handedness " + quote(handedness) + " is not left or right");
}

void readLens(const Context& ctx, pugi::xml_node e, Camera& c) {
    pugi::xml_node a = e.child("ApertureSize");
    if (!a) return;
    c.apertureSize = scalar(ctx, a);
    if (c.apertureSize < 0.0f) ctx.fail(a, "must not be negative");
    if (c.apertureSize == 0.0f) return;
    pugi::xml_node f = required(ctx, e, "FocusDistance");
    c.focusDistance = scalar(ctx, f);
    if (!(c.focusDistance > 0.0f)) ctx.fail(f, "must be positive");
}

// "sRGB" selects the transfer curve; anything else must be a positive exponent.
void readGamma(const Context& ctx, pugi::xml_node g, TonemapSettings& tm) {
    const std::string text = textOf(g);
    const std::vector<std::string_view> t = tokens(text);
    if (t.size() == 1 && lowercase(t[0]) == "srgb") {
        tm.srgb = true;
        return;
    }
    tm.srgb = false;
    tm.gamma = scalar(ctx, g);
    if (!(tm.gamma > 0.0f)) ctx.fail(g, "must be positive");
}

// Without <Tonemap> the course clamps to [0, 255] with no gamma (HW1-4).
TonemapSettings clampTonemap() {
    TonemapSettings tm;
    tm.op = TonemapSettings::Operator::Clamp;
    tm.srgb = false;
    tm.gamma = 1.0f;
    return tm;
}

TonemapSettings readTonemap(Context& ctx, pugi::xml_node e) {
    TonemapSettings tm = clampTonemap();
    // 2018 files: <GammaCorrection>sRGB</GammaCorrection> outside the Tonemap.
    if (pugi::xml_node g = e.child("GammaCorrection")) readGamma(ctx, g, tm);
    pugi::xml_node t = e.child("Tonemap");
    if (!t) return tm;
    tm.op = TonemapSettings::Operator::Photographic;
    const std::string op = textOf(required(ctx, t, "TMO"));
    const std::vector<std::string_view> opTokens = tokens(op);
    if (opTokens.size() != 1 || lowercase(opTokens[0]) != "photographic")
        ctx.note("tone mapping operator " + quote(op) + " (Photographic used)");
    if (pugi::xml_node o = t.child("TMOOptions")) {
        const std::vector<double> v = numbers(ctx, o);
        if (v.size() != 2) ctx.fail(o, "expected key and burn percentage");
        if (!(v[0] > 0.0)) ctx.fail(o, "key must be positive");
        if (!(v[1] >= 0.0 && v[1] <= 100.0)) ctx.fail(o, "burn percentage must be in [0, 100]");
        tm.key = static_cast<float>(v[0]);
        tm.burnPercent = static_cast<float>(v[1]);
    } else {
        ctx.note(label(t) + " without TMOOptions (key " + formatNumber(tm.key) + ", burn " +
                 formatNumber(tm.burnPercent) + "% assumed)");
    }
    if (pugi::xml_node s = t.child("Saturation")) {
        tm.saturation = scalar(ctx, s);
        if (tm.saturation < 0.0f) ctx.fail(s, "must not be negative");
    } else {
        ctx.note(label(t) + " without Saturation (" + formatNumber(tm.saturation) + " assumed)");
    }
    if (pugi::xml_node g = t.child("Gamma"))
        readGamma(ctx, g, tm);
    else if (!e.child("GammaCorrection"))
        ctx.note(label(t) + " without Gamma (1, no gamma correction, assumed)");
    return tm;
}

// Renderer/RendererParams (HW6). Without <Renderer> the course used its classic (Whitted /
// direct lighting) ray tracer; the options are left to the command line and its defaults.
void readRenderer(Context& ctx, pugi::xml_node e, CameraRenderSettings& s) {
    pugi::xml_node r = e.child("Renderer");
    if (!r) {
        s.classic = true;
        // Its images are in 0..255 display units, written clamped without gamma.
        if (!e.child("Tonemap") && s.tonemap) s.tonemap->scale = 1.0f / 255.0f;
        return;
    }
    s.classic = false;
    const std::string name = textOf(r);
    const std::vector<std::string_view> nameTokens = tokens(name);
    if (nameTokens.size() != 1 || lowercase(nameTokens[0]) != "pathtracing")
        ctx.note("renderer " + quote(name) + " (rendered by path tracing)");
    // Each option is on exactly when named; an empty or absent list means plain path tracing
    // with uniform hemisphere sampling (docs/ceng795-format.md §2).
    s.nee = s.importanceSampling = s.russianRoulette = false;
    const std::string params = textOf(e.child("RendererParams"));
    for (std::string_view p : tokens(params)) {
        const std::string word = lowercase(p);
        if (word == "nexteventestimation")
            s.nee = true;
        else if (word == "importancesampling")
            s.importanceSampling = true;
        else if (word == "russianroulette")
            s.russianRoulette = true;
        else
            ctx.note("renderer option " + quote(p) + " (ignored)");
    }
}

// Output names are written next to the scene file; refuse anything that would leave it.
void readImageName(const Context& ctx, pugi::xml_node e, CameraRenderSettings& s) {
    pugi::xml_node n = e.child("ImageName");
    if (!n) return;
    const std::string text = textOf(n);
    const std::vector<std::string_view> t = tokens(text);
    if (t.size() != 1) ctx.fail(n, "expected one file name");
    const std::filesystem::path p{std::string(t[0])};
    bool escapes = p.is_absolute() || p.has_root_name();
    for (const auto& part : p) escapes = escapes || part == "..";
    if (escapes) ctx.fail(n, quote(t[0]) + " must be a relative path inside the scene's directory");
    s.imageName = std::string(t[0]);
}

void readSettings(Context& ctx, pugi::xml_node e, std::optional<int> maxDepth, Camera& c) {
    CameraRenderSettings& s = c.settings;
    // The course's default of 1 sample suited its deterministic ray tracer; a path tracer
    // needs more, so an absent NumSamples leaves the choice to the command line.
    if (pugi::xml_node n = e.child("NumSamples")) s.spp = static_cast<uint32_t>(integer(ctx, n, 1, kMaxSamples));
    readImageName(ctx, e, s);
    s.tonemap = readTonemap(ctx, e);
    readRenderer(ctx, e, s);
    // The official path-tracing references apply Russian roulette without the depth cap
    // (docs/ceng795-format.md §8), so those cameras get no cap of their own and the renderer's default applies.
    if (!s.russianRoulette.value_or(false)) s.maxDepth = maxDepth;
}

} // namespace

Camera readCamera(Context& ctx, pugi::xml_node e, size_t index, std::optional<int> maxDepth) {
    Camera c;
    c.name = "camera " + idText(e, std::to_string(index + 1));
    // The id is how a user picks a course camera (--camera); it must fit the model's int.
    if (e.attribute("id")) {
        const long long id = idOf(ctx, e);
        if (id < 0 || id > std::numeric_limits<int>::max()) ctx.fail(e, "id is out of range");
        c.id = static_cast<int>(id);
    } else {
        ctx.note("Camera without an id (the name '" + c.name + "' from its position assumed)");
    }
    readView(ctx, e, c);
    readResolution(ctx, e, c);
    readProjection(ctx, e, c);
    readLens(ctx, e, c);
    readSettings(ctx, e, maxDepth, c);
    return c;
}

std::vector<Camera> readCameras(Context& ctx, pugi::xml_node scene, std::optional<int> maxDepth) {
    std::vector<Camera> cameras;
    for (pugi::xml_node list : scene.children("Cameras"))
        for (pugi::xml_node e : list.children("Camera"))
            cameras.push_back(readCamera(ctx, e, cameras.size(), maxDepth));
    return cameras;
}

} // namespace pt::ceng795
