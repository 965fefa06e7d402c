// glTF cameras (perspective; orthographic ones are skipped) and KHR_lights_punctual lights into
// the scene model (gltf_importer.h), each placed by its node's world transform.
#include "scene/gltf/gltf_importer.h"

namespace pt::gltf {

// ---- cameras ----
void GltfImporter::addCamera(int cameraIndex, const glm::mat4& world) {
    if (cameraIndex >= static_cast<int>(model_.cameras.size()))
        fail("camera index " + std::to_string(cameraIndex) + " out of range");
    const tinygltf::Camera& cam = model_.cameras[cameraIndex];
    if (cam.type != "perspective") {
        unsupported("orthographic cameras (skipped)");
        return;
    }
    const double yfov = cam.perspective.yfov;
    if (!(yfov > 0.0 && yfov < M_PI))
        fail("camera " + std::to_string(cameraIndex) + ": yfov " + std::to_string(yfov) + " must be in (0, pi)");
    Camera c;
    c.name = cam.name.empty() ? "camera " + std::to_string(cameraIndex) : cam.name;
    c.position = glm::vec3(world * glm::vec4(0, 0, 0, 1));
    glm::vec3 forward = glm::mat3(world) * glm::vec3(0, 0, -1);
    glm::vec3 up = glm::mat3(world) * glm::vec3(0, 1, 0);
    if (glm::length(forward) == 0.0f || glm::length(glm::cross(forward, up)) == 0.0f)
        fail("camera " + std::to_string(cameraIndex) + ": degenerate camera transform");
    c.forward = glm::normalize(forward);
    c.up = glm::normalize(up - glm::dot(up, c.forward) * c.forward);
    // Lengths that overflow (or vanish) leave no usable frame.
    if (!finite(c.forward) || !finite(c.up) || !(glm::length(c.forward) > 0.5f) || !(glm::length(c.up) > 0.5f))
        fail("camera " + std::to_string(cameraIndex) + ": degenerate camera transform");
    c.yfov = static_cast<float>(yfov);
    // Absent (0) means "the image's"; beyond 1:16384 no image of an allowed size has that shape,
    // and the height derived from it would overflow.
    const double aspect = cam.perspective.aspectRatio;
    if (aspect != 0.0 && !(aspect >= 1.0 / 16384 && aspect <= 16384))
        fail("camera " + std::to_string(cameraIndex) + ": aspectRatio " + std::to_string(aspect) +
             " must be in [1/16384, 16384]");
    c.aspectRatio = static_cast<float>(aspect);
    scene_.cameras.push_back(c);
}

// ---- lights (KHR_lights_punctual) ----
// Photometric units read as radiometric ones: point and spot intensity (candela) is radiant
// intensity (W/sr), directional intensity (lux) is irradiance (W/m^2); times the colour.
// Lights sit at the node's origin and shine along its -z. `range` is a rasteriser's cut-off
// and is ignored (inverse-square falloff to infinity, as the extension recommends for
// physically based renderers).
void GltfImporter::addLight(const tinygltf::Value& ref, int nodeIndex, const glm::mat4& world) {
    const std::string where = "node " + std::to_string(nodeIndex) + ": KHR_lights_punctual";
    const int index =
        ref.IsObject() && ref.Has("light") && ref.Get("light").IsInt() ? ref.Get("light").GetNumberAsInt() : -1;
    if (index < 0 || index >= static_cast<int>(model_.lights.size())) fail(where + " light index out of range");
    const tinygltf::Light& src = model_.lights[index];
    const std::string label = "light " + std::to_string(index) + (src.name.empty() ? "" : " '" + src.name + "'");
    glm::vec3 colour(1.0f); // the extension's default, when absent
    if (src.color.size() == 3)
        colour = glm::vec3(src.color[0], src.color[1], src.color[2]);
    else if (!src.color.empty())
        unsupported(label + ": color is not 3 numbers (1 1 1 assumed)");
    if (!finite(colour) || glm::any(glm::lessThan(colour, glm::vec3(0))) || !(src.intensity >= 0.0) ||
        !std::isfinite(src.intensity))
        fail(label + ": colour and intensity must be finite and non-negative");
    PunctualLight light;
    light.intensity = colour * static_cast<float>(src.intensity);
    light.position = glm::vec3(world * glm::vec4(0, 0, 0, 1));
    const glm::vec3 axis = glm::mat3(world) * glm::vec3(0, 0, -1);
    if (!(glm::length(axis) > 0.0f)) fail(where + ": degenerate light transform");
    light.direction = glm::normalize(axis);
    if (!finite(light.direction) || !(glm::length(light.direction) > 0.5f))
        fail(where + ": degenerate light transform");
    // A finite double intensity can still overflow a float.
    if (!finite(light.intensity)) fail(label + ": intensity times colour overflows");
    if (src.type == "point") {
        light.type = PunctualLight::Type::Point;
    } else if (src.type == "directional") {
        light.type = PunctualLight::Type::Directional;
    } else if (src.type == "spot") {
        const double inner = src.spot.innerConeAngle, outer = src.spot.outerConeAngle;
        if (!(inner >= 0.0 && inner <= outer && outer > 0.0 && outer <= M_PI / 2 + 1e-6))
            fail(label + ": spot cone angles need 0 <= innerConeAngle <= outerConeAngle <= pi/2");
        light.type = PunctualLight::Type::Spot;
        // glTF's smooth edge: t^2 with t = (cos a - cos outer) / (cos inner - cos outer).
        light.cosCoverage = static_cast<float>(std::cos(outer));
        light.cosFalloff = static_cast<float>(std::cos(inner));
        light.falloffExponent = 2.0f;
    } else {
        unsupported("KHR_lights_punctual light type '" + src.type + "' (skipped)");
        return;
    }
    if (src.range > 0.0)
        unsupported("KHR_lights_punctual range (ignored: lights fall off with the inverse square to infinity)");
    scene_.punctualLights.push_back(light);
}

} // namespace pt::gltf
