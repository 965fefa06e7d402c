// `pt view`: keys, mouse, the script, saving and printing.
#include "gpu/vulkan_error.h"
#include "image/atomic_file.h"
#include "image/image_io.h"
#include "film/tonemap.h"
#include "viewer/viewer_session.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

namespace pt::viewer {
namespace {

namespace fs = std::filesystem;

constexpr float kDollyPerPixel = 0.05f; // right drag: wheel clicks per pixel
constexpr float kEvStep = 0.5f;
constexpr uint32_t kMaxDepthLimit = 1024;
// Firefly clamp levels cycled by C (0 = off).
constexpr float kClampLevels[] = {0.0f, 100.0f, 10.0f, 1.0f};
constexpr int kDebugViews = 6; // DEBUG_VIEW_NONE .. DEBUG_VIEW_NAN_MASK

const char* debugViewName(uint32_t v) {
    static const char* names[] = {"none", "albedo", "normal", "depth", "bvh", "nan"};
    return v < 6 ? names[v] : "?";
}

// Script names of keys: letters and digits as themselves, plus these.
const std::map<std::string, int>& namedKeys() {
    static const std::map<std::string, int> m = {
        {"escape", GLFW_KEY_ESCAPE},
        {"space", GLFW_KEY_SPACE},
        {"minus", GLFW_KEY_MINUS},
        {"equal", GLFW_KEY_EQUAL},
        {"comma", GLFW_KEY_COMMA},
        {"period", GLFW_KEY_PERIOD},
        {"left_bracket", GLFW_KEY_LEFT_BRACKET},
        {"right_bracket", GLFW_KEY_RIGHT_BRACKET},
        {"f1", GLFW_KEY_F1},
        {"f5", GLFW_KEY_F5},
        {"f6", GLFW_KEY_F6},
    };
    return m;
}

int keyFromName(const std::string& name, int& mods) {
    std::string n = name;
    mods = 0;
    if (n.rfind("shift+", 0) == 0) mods |= GLFW_MOD_SHIFT, n = n.substr(6);
    if (n.rfind("ctrl+", 0) == 0) mods |= GLFW_MOD_CONTROL, n = n.substr(5);
    if (n.size() == 1 && std::isalpha(static_cast<unsigned char>(n[0]))) return GLFW_KEY_A + (std::tolower(n[0]) - 'a');
    if (n.size() == 1 && std::isdigit(static_cast<unsigned char>(n[0]))) return GLFW_KEY_0 + (n[0] - '0');
    auto it = namedKeys().find(n);
    return it == namedKeys().end() ? GLFW_KEY_UNKNOWN : it->second;
}

std::string fixed(double v, int digits) {
    char b[64];
    std::snprintf(b, sizeof b, "%.*f", digits, v);
    return b;
}

const char* kHelp =
    "pt view keys:\n"
    "  left drag: orbit (fly mode: look)   middle or shift+left drag: pan   wheel or right drag: dolly\n"
    "  F: fly mode (W A S D move, Q E down/up)   [ ]: fly speed /2 x2   R: reset view   P: print the camera\n"
    "  N: NEE   M: MIS   L: Russian roulette   U: cosine/uniform sampling   - =: max depth\n"
    "  B: integrator (auto, path, bidirectional)   G: light selection (auto, light tree, power)\n"
    "  , .: exposure -/+ 0.5 EV   T: tone mapping (srgb, photographic, aces)   C: firefly clamp (biased)\n"
    "  V (shift+V): debug view (albedo, normal, depth, bvh cost, nan mask)   space: pause\n"
    "  F5 or ctrl+S: save EXR + PNG   F6: window screenshot   F1 or H: this help   Esc: quit\n";

} // namespace

std::string Session::settingsText() const {
    // (Vertex merging is rendered by BDPT in the viewer: viewerFeatures.)
    const char* integrator =
        settings_.estimator == Estimator::Path                                                               ? "path "
        : settings_.estimator == Estimator::Bidirectional || settings_.estimator == Estimator::VertexMerging ? "bdpt "
                                                                                                             : "auto ";
    std::string s = std::string(settings_.classic ? "" : integrator) + (settings_.nee ? "nee" : "no-nee") + " " +
                    (settings_.mis ? "mis" : "no-mis") + " " + (settings_.rr ? "rr" : "no-rr") + " " +
                    (settings_.sampling == DirectionSampling::Cosine ? "cosine" : "uniform") + " depth " +
                    std::to_string(settings_.maxDepth) + (settings_.classic ? " classic" : "");
    if (settings_.lightSelection != LightSelection::Auto)
        s += settings_.lightSelection == LightSelection::Tree ? " light-tree" : " power-lights";
    if (clamp_ > 0.0f) s += " | clamp " + fixed(clamp_, 0) + " (BIASED)";
    if (debugView_ != 0) s += " | view " + std::string(debugViewName(debugView_));
    return s;
}

void Session::handleInput(const Input& input, float seconds) {
    for (const KeyPress& k : input.keys) handleKey(k.key, k.mods);
    if (input.leftDrag != glm::vec2(0.0f)) {
        if (fly_)
            controller_.look(input.leftDrag);
        else
            controller_.orbit(input.leftDrag);
        cameraDirty_ = true;
    }
    if (input.panDrag != glm::vec2(0.0f)) controller_.pan(input.panDrag, windowSize_.y), cameraDirty_ = true;
    const float dolly = input.scroll - kDollyPerPixel * input.rightDrag.y;
    if (dolly != 0.0f) controller_.dolly(dolly), cameraDirty_ = true;
    if (fly_) {
        const bool ctrl = window_.keyDown(GLFW_KEY_LEFT_CONTROL) || window_.keyDown(GLFW_KEY_RIGHT_CONTROL);
        glm::vec3 axes(0.0f);
        if (!ctrl) {
            axes.x = float(window_.keyDown(GLFW_KEY_D)) - float(window_.keyDown(GLFW_KEY_A));
            axes.y = float(window_.keyDown(GLFW_KEY_E)) - float(window_.keyDown(GLFW_KEY_Q));
            axes.z = float(window_.keyDown(GLFW_KEY_W)) - float(window_.keyDown(GLFW_KEY_S));
        }
        if (axes != glm::vec3(0.0f)) controller_.fly(axes, seconds), cameraDirty_ = true;
    }
}

void Session::handleKey(int key, int mods) {
    const bool shift = (mods & GLFW_MOD_SHIFT) != 0;
    const bool ctrl = (mods & GLFW_MOD_CONTROL) != 0;
    switch (key) {
    case GLFW_KEY_ESCAPE: quit_ = true; break;
    case GLFW_KEY_R: controller_.reset(), cameraDirty_ = true; break;
    case GLFW_KEY_F:
        fly_ = !fly_;
        std::fprintf(stderr, "pt: view: %s mode\n", fly_ ? "fly" : "orbit");
        displayDirty_ = true;
        break;
    case GLFW_KEY_LEFT_BRACKET: controller_.scaleSpeed(0.5f), displayDirty_ = true; break;
    case GLFW_KEY_RIGHT_BRACKET: controller_.scaleSpeed(2.0f), displayDirty_ = true; break;
    case GLFW_KEY_N: settings_.nee = !settings_.nee, integratorDirty_ = true; break;
    case GLFW_KEY_M: settings_.mis = !settings_.mis, integratorDirty_ = true; break;
    case GLFW_KEY_L: settings_.rr = !settings_.rr, integratorDirty_ = true; break;
    case GLFW_KEY_B: // auto -> path -> bidirectional -> auto (auto decides by the probe's measurement)
        settings_.estimator = settings_.estimator == Estimator::Auto   ? Estimator::Path
                              : settings_.estimator == Estimator::Path ? Estimator::Bidirectional
                                                                       : Estimator::Auto;
        integratorDirty_ = true;
        break;
    case GLFW_KEY_G: // auto -> light tree -> power CDF -> auto
        settings_.lightSelection = settings_.lightSelection == LightSelection::Auto   ? LightSelection::Tree
                                   : settings_.lightSelection == LightSelection::Tree ? LightSelection::Power
                                                                                      : LightSelection::Auto;
        integratorDirty_ = true;
        break;
    case GLFW_KEY_U:
        settings_.sampling =
            settings_.sampling == DirectionSampling::Cosine ? DirectionSampling::Uniform : DirectionSampling::Cosine;
        integratorDirty_ = true;
        break;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT:
        settings_.maxDepth = std::max(1u, settings_.maxDepth - 1), integratorDirty_ = true;
        break;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD:
        settings_.maxDepth = std::min(kMaxDepthLimit, settings_.maxDepth + 1), integratorDirty_ = true;
        break;
    case GLFW_KEY_COMMA: ev_ -= kEvStep, displayDirty_ = true, updatePhotographicTerms(true); break;
    case GLFW_KEY_PERIOD: ev_ += kEvStep, displayDirty_ = true, updatePhotographicTerms(true); break;
    case GLFW_KEY_T:
        op_ = static_cast<DisplayOperator>((static_cast<int>(op_) + (shift ? 2 : 1)) % 3);
        std::fprintf(stderr, "pt: view: tone mapping %s\n", operatorName(op_));
        displayDirty_ = true;
        updatePhotographicTerms(true);
        break;
    case GLFW_KEY_C: {
        size_t i = 0;
        while (i < std::size(kClampLevels) && kClampLevels[i] != clamp_) ++i;
        clamp_ = kClampLevels[(i + 1) % std::size(kClampLevels)];
        if (clamp_ > 0.0f)
            std::fprintf(stderr, "pt: view: firefly clamp at %g: BIASED (energy above it is dropped)\n", clamp_);
        else
            std::fprintf(stderr, "pt: view: firefly clamp off\n");
        clampDirty_ = true;
        break;
    }
    case GLFW_KEY_V:
        debugView_ = (debugView_ + (shift ? kDebugViews - 1 : 1)) % kDebugViews;
        integratorDirty_ = true;
        break;
    case GLFW_KEY_P: printCamera(); break;
    case GLFW_KEY_SPACE: paused_ = !paused_, displayDirty_ = true; break;
    case GLFW_KEY_F5:
        save(config_.outputDir / (config_.sceneStem + "-view-" + std::to_string(++saveCounter_) + ".exr"));
        break;
    case GLFW_KEY_S:
        if (ctrl) save(config_.outputDir / (config_.sceneStem + "-view-" + std::to_string(++saveCounter_) + ".exr"));
        break;
    case GLFW_KEY_F6:
        screenshot(config_.outputDir / (config_.sceneStem + "-window-" + std::to_string(++saveCounter_) + ".png"));
        break;
    case GLFW_KEY_F1:
    case GLFW_KEY_H: std::fputs(kHelp, stdout), std::fflush(stdout); break;
    default: break;
    }
}

// ---- Script ----

void Session::stepScript() {
    if (waitResize_ > 0) {
        if (window_.framebufferSize() == resizeTarget_ && windowSize_ == resizeTarget_)
            waitResize_ = 0;
        else if (--waitResize_ == 0) {
            std::fprintf(stderr, "pt: error: script: the window did not resize to %dx%d (it is %dx%d)\n",
                resizeTarget_.x, resizeTarget_.y, windowSize_.x, windowSize_.y);
            status_ = 1;
            quit_ = true;
        }
        return;
    }
    if (repeatLeft_ > 0) {
        --repeatLeft_;
        runCommand(repeated_);
        return;
    }
    if (waitFrames_ > 0) {
        --waitFrames_;
        return;
    }
    if (waitSpp_ >= 0) {
        const uint32_t target = std::min<uint32_t>(static_cast<uint32_t>(waitSpp_), config_.sppCap);
        if (scale_ > 1 || passActive_ || renderer_->samplesPerPixel() < target || cameraDirty_ || integratorDirty_ ||
            clampDirty_ || sizeDirty_)
            return;
        waitSpp_ = -1;
    }
    while (scriptNext_ < config_.script.size() && !quit_) {
        const ScriptCommand& c = config_.script[scriptNext_++];
        if (c.name == "wait") {
            waitFrames_ = std::max(0, static_cast<int>(c.numbers[0]) - 1);
            return;
        }
        if (c.name == "wait-spp") {
            waitSpp_ = static_cast<int64_t>(c.numbers[0]);
            return;
        }
        if (c.name == "repeat") {
            std::string rest;
            for (size_t i = 1; i < c.args.size(); ++i) rest += c.args[i] + " ";
            repeated_ = parseScript(rest, "repeat")[0];
            repeatLeft_ = static_cast<int>(c.numbers[0]);
            if (repeatLeft_ > 0) --repeatLeft_, runCommand(repeated_);
            return;
        }
        runCommand(c);
        if (c.name == "resize" || c.name == "orbit" || c.name == "pan" || c.name == "dolly" || c.name == "look" ||
            c.name == "move")
            return; // one input per frame, as from a user
    }
}

void Session::runCommand(const ScriptCommand& c) {
    const auto& n = c.numbers;
    if (c.name == "orbit")
        controller_.orbit(glm::vec2(n[0], n[1])), cameraDirty_ = true;
    else if (c.name == "pan")
        controller_.pan(glm::vec2(n[0], n[1]), windowSize_.y), cameraDirty_ = true;
    else if (c.name == "dolly")
        controller_.dolly(static_cast<float>(n[0])), cameraDirty_ = true;
    else if (c.name == "look")
        controller_.look(glm::vec2(n[0], n[1])), cameraDirty_ = true;
    else if (c.name == "move")
        controller_.fly(glm::vec3(n[0], n[1], n[2]), 1.0f), cameraDirty_ = true;
    else if (c.name == "reset-view")
        handleKey(GLFW_KEY_R, 0);
    else if (c.name == "key") {
        int mods = 0;
        const int key = keyFromName(c.args[0], mods);
        if (key == GLFW_KEY_UNKNOWN) {
            std::fprintf(stderr, "pt: error: script %s: unknown key '%s'\n", c.where().c_str(), c.args[0].c_str());
            status_ = 1;
            quit_ = true;
            return;
        }
        handleKey(key, mods);
    } else if (c.name == "toggle") {
        static const std::map<std::string, int> keys = {{"nee", GLFW_KEY_N}, {"mis", GLFW_KEY_M}, {"rr", GLFW_KEY_L},
            {"sampling", GLFW_KEY_U}, {"fly", GLFW_KEY_F}, {"integrator", GLFW_KEY_B}, {"light-tree", GLFW_KEY_G}};
        handleKey(keys.at(c.args[0]), 0);
    } else if (c.name == "view") {
        static const std::vector<std::string> views = {"none", "albedo", "normal", "depth", "bvh", "nan"};
        debugView_ = static_cast<uint32_t>(std::find(views.begin(), views.end(), c.args[0]) - views.begin());
        integratorDirty_ = true;
    } else if (c.name == "tonemap") {
        op_ = c.args[0] == "photographic" ? DisplayOperator::Photographic
              : c.args[0] == "aces"       ? DisplayOperator::Aces
                                          : DisplayOperator::Srgb;
        displayDirty_ = true;
        updatePhotographicTerms(true);
    } else if (c.name == "exposure") {
        ev_ = static_cast<float>(n[0]), displayDirty_ = true;
        updatePhotographicTerms(true);
    } else if (c.name == "max-depth") {
        settings_.maxDepth = static_cast<uint32_t>(std::clamp(n[0], 1.0, double(kMaxDepthLimit)));
        integratorDirty_ = true;
    } else if (c.name == "clamp") {
        clamp_ = static_cast<float>(std::max(0.0, n[0]));
        clampDirty_ = true;
    } else if (c.name == "resize") {
        resizeTarget_ = glm::ivec2(static_cast<int>(n[0]), static_cast<int>(n[1]));
        window_.requestSize(resizeTarget_.x, resizeTarget_.y);
        waitResize_ = 200;
    } else if (c.name == "save")
        save(c.args[0]);
    else if (c.name == "screenshot")
        screenshot(c.args[0]);
    else if (c.name == "print-camera")
        printCamera();
    else if (c.name == "stats")
        printStats();
    else if (c.name == "report")
        printReport();
    else if (c.name == "quit")
        quit_ = true;
}

// ---- Output ----

void Session::save(const fs::path& requested) {
    fs::path exr = requested;
    if (exr.extension() != ".exr") exr += ".exr";
    try {
        finishPass();
        prepareOutputDirectory(exr);
        const Renderer::Readback r = renderer_->read();
        const Camera cam = controller_.camera();
        ImageMetadata meta;
        meta["spp"] = std::to_string(renderer_->samplesPerPixel());
        meta["seconds"] = fixed(renderSeconds_, 3);
        meta["seed"] = std::to_string(settings_.seed);
        meta["device"] = context_.info().name;
        meta["driver"] = context_.info().driver;
        meta["integrator"] = settings_.describe();
        meta["features"] = renderer_->features().describe();
        meta["scene"] = config_.sceneSource;
        meta["camera"] = "position " + fixed(cam.position.x, 6) + " " + fixed(cam.position.y, 6) + " " +
                         fixed(cam.position.z, 6) + " forward " + fixed(cam.forward.x, 6) + " " +
                         fixed(cam.forward.y, 6) + " " + fixed(cam.forward.z, 6) + " up " + fixed(cam.up.x, 6) + " " +
                         fixed(cam.up.y, 6) + " " + fixed(cam.up.z, 6) + " yfov " + fixed(cam.yfov, 6);
        meta["dropped_samples"] = std::to_string(r.droppedSamples);
        meta["viewer"] = "pt view" + std::string(scale_ > 1 ? " (preview resolution)" : "");
        if (clamp_ > 0.0f) meta["sample_clamp"] = fixed(clamp_, 3) + " (biased)";
        if (debugView_ != 0) meta["debug_view"] = debugViewName(debugView_);
        writeExr(exr, r.mean, meta);
        fs::path variance = exr;
        variance.replace_extension(".var.exr");
        writeExr(variance, r.varianceOfMean, meta);
        fs::path png = exr;
        png.replace_extension(".png");
        writeDisplayPng(
            png, r.mean, debugView_ ? DisplayOperator::Srgb : op_, config_.job.tonemap, debugView_ ? 0.0f : ev_);
        std::fprintf(stderr, "pt: view: saved %s (and .var.exr, .png): %u spp, %dx%d\n", exr.string().c_str(),
            renderer_->samplesPerPixel(), r.mean.width, r.mean.height);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "pt: error: saving: %s\n", e.what());
        if (config_.scripted) status_ = 1, quit_ = true;
    }
}

void Session::screenshot(const fs::path& png) {
    try {
        prepareOutputDirectory(png);
        const std::vector<uint8_t> rgb = display_->readRgb(swapchain_->bgra());
        Image image;
        image.width = display_->width();
        image.height = display_->height();
        image.rgba.resize(size_t(image.width) * image.height * 4, 1.0f);
        for (size_t i = 0; i < rgb.size() / 3; ++i)
            for (int c = 0; c < 3; ++c) image.rgba[4 * i + c] = rgb[3 * i + c] / 255.0f;
        // Clamp with gamma 1 writes the bytes back exactly.
        TonemapSettings exact;
        exact.op = TonemapSettings::Operator::Clamp;
        exact.srgb = false;
        exact.gamma = 1.0f;
        writeTonemappedPng(png, image, exact);
        std::fprintf(stderr, "pt: view: screenshot %s (%dx%d)\n", png.string().c_str(), image.width, image.height);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "pt: error: screenshot: %s\n", e.what());
        if (config_.scripted) status_ = 1, quit_ = true;
    }
}

void Session::printCamera() const {
    std::printf("glTF node:\n%s\ncourse XML:\n%s\n", controller_.gltfSnippet().c_str(),
        controller_.courseXmlSnippet(windowSize_.x, windowSize_.y).c_str());
    std::fflush(stdout);
}

void Session::printStats() {
    const double seconds = std::chrono::duration<double>(Clock::now() - stats_.start).count();
    const double mpaths = stats_.renderMs > 0 ? stats_.pathSamples / stats_.renderMs * 1e-3 : 0.0;
    std::printf("pt: view: stats frames=%llu seconds=%.3f fps=%.2f frame_ms_mean=%.2f frame_ms_max=%.2f "
                "mpaths_per_s=%.3f spp=%u\n",
        static_cast<unsigned long long>(stats_.frames), seconds, stats_.frames / std::max(seconds, 1e-9),
        stats_.frames ? stats_.sumMs / stats_.frames : 0.0, stats_.maxMs, mpaths, renderer_->samplesPerPixel());
    std::fflush(stdout);
    stats_ = {};
}

void Session::printReport() const {
    std::printf("pt: view: report spp=%u film=%dx%d window=%dx%d scale=%d since_change=%.3f frames=%llu\n",
        renderer_->samplesPerPixel(), renderer_->width(), renderer_->height(), windowSize_.x, windowSize_.y, scale_,
        std::chrono::duration<double>(Clock::now() - changeTime_).count(), static_cast<unsigned long long>(frames_));
    std::fflush(stdout);
}

void Session::updateTitle(bool force) {
    if (!force && std::chrono::duration<double>(Clock::now() - titleTime_).count() < 0.25) return;
    titleTime_ = Clock::now();
    std::string t = "pt view: " + config_.sceneStem + " | " + std::to_string(renderer_->samplesPerPixel()) + " spp";
    if (scale_ > 1) t += " (preview 1/" + std::to_string(scale_) + ")";
    if (passActive_ && passTiles_ > 1) t += " +" + std::to_string(100 * passTilesDone_ / passTiles_) + "%";
    t += " | " + fixed(lastGpuMs_, 1) + " ms/frame GPU, " + fixed(lastFrameMs_, 1) + " wall | " +
         fixed(1e-3 / costMs_, 2) + " M paths/s | " + settingsText() + " | " +
         (debugView_ ? "srgb" : operatorName(op_)) + " EV " + fixed(ev_, 1);
    if (fly_) t += " | fly x" + fixed(controller_.speed(), 2);
    if (paused_)
        t += " | paused";
    else if (!workLeft())
        t += " | done";
    window_.setTitle(t);
}

} // namespace pt::viewer
