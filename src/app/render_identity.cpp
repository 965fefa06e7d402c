#include "app/render_identity.h"

#include "base/hash.h"

#include <cstdio>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace pt {
namespace {

uint64_t hashFile(const std::string& path, uint64_t hash) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error(path + ": cannot read to hash it");
    std::vector<char> buffer(1 << 16);
    while (in) {
        in.read(buffer.data(), std::streamsize(buffer.size()));
        hash = fnv1a64(buffer.data(), size_t(in.gcount()), hash);
    }
    return hash;
}

// Exact text for floats: 9 significant digits round-trip a float32.
std::string exact(float v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", double(v));
    return text;
}
std::string exact(glm::vec3 v) { return exact(v.x) + "," + exact(v.y) + "," + exact(v.z); }

} // namespace

RenderIdentity renderIdentity(const RenderOptions& o, const Scene& scene, const Job& job) {
    std::ostringstream s;
    const Camera& c = job.camera;
    s << "size=" << job.width << "x" << job.height << " camera=" << c.name << " position=" << exact(c.position)
      << " forward=" << exact(c.forward) << " up=" << exact(c.up) << " yfov=" << exact(c.yfov);
    if (c.window) s << " window=" << exact(glm::vec3(*c.window)) << "," << exact(c.window->w);
    s << " aperture=" << exact(c.apertureSize) << " focus=" << exact(c.focusDistance) << " " << job.settings.describe()
      << " background=" << exact(scene.background);
    if (job.target.adaptive) s << " adaptive=on";
    // The same file renders other materials under another KHR_materials_variants variant.
    if (!scene.variant.empty()) s << " variant=" << scene.variant;
    if (scene.environment) {
        const Environment& e = *scene.environment;
        s << " env=" << (e.image.rgba.empty() ? exact(e.colour) : "map") << " env-scale=" << exact(e.scale)
          << " env-rotate=" << exact(e.rotationDegrees);
    }
    RenderIdentity id;
    id.settings = s.str();
    uint64_t hash = o.scene.empty() ? fnv1a64("built-in", 8) : hashFile(o.scene, fnv1a64("file", 4));
    if (!o.environment.empty()) hash = hashFile(o.environment, hash);
    hash = fnv1a64(id.settings.data(), id.settings.size(), hash);
    id.sceneHash = hexDigits(hash);
    return id;
}

void RenderIdentity::addTo(ImageMetadata& metadata) const {
    metadata["render_settings"] = settings;
    metadata["scene_hash"] = sceneHash;
}

std::string identityMismatch(const RenderIdentity& expected, const ImageMetadata& metadata) {
    const auto hash = metadata.find("scene_hash");
    const auto settings = metadata.find("render_settings");
    if (hash == metadata.end() || settings == metadata.end()) return "it carries no scene hash";
    if (settings->second != expected.settings)
        return "its settings differ (it has '" + settings->second + "', this render '" + expected.settings + "')";
    if (hash->second != expected.sceneHash)
        return "its scene hash " + hash->second + " differs from " + expected.sceneHash +
               " (the scene or environment file changed)";
    return {};
}

} // namespace pt
