// Emissive spheres and ellipsoids (shaders/lights/sphere_light.glsl): round ones by the cone of
// directions they subtend, ellipsoids (and double-sided spheres) by area.
#include "lights/light_entry.h"

#include <cmath>

namespace pt {
namespace {

// How far from a multiple of the identity A^T A may be (relative to its mean diagonal) for the
// sphere to count as round: a rotation times a uniform scale, composed in float, stays orders
// of magnitude below this; an ellipsoid whose axes differ by less is sampled as the sphere of
// their mean radius, which is what it is to float precision in its pdf.
constexpr double kRoundTolerance = 1e-5;

// Rows of the GpuSphere maps back into a matrix (the linear part is all we need).
glm::dmat3 linearPart(const glm::vec4 rows[3]) {
    glm::dmat3 m;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) m[c][r] = rows[r][c];
    return m;
}

// A sphere is "round" when its linear map is a rotation times a uniform scale: then it is
// sampled by the cone of directions it subtends. Ellipsoids are sampled by area.
bool roundRadius(const glm::dmat3& a, double& radius) {
    const glm::dmat3 ata = glm::transpose(a) * a;
    const double s2 = (ata[0][0] + ata[1][1] + ata[2][2]) / 3.0;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            if (std::abs(ata[c][r] - (r == c ? s2 : 0.0)) > kRoundTolerance * s2) return false;
    radius = std::sqrt(s2);
    return true;
}

} // namespace

std::optional<LightEntry> sphereLight(const gpu::GpuSphere& sphere, uint32_t index, const Material& m) {
    if (!m.emissive()) return std::nullopt;
    const glm::dmat3 a = linearPart(sphere.objectToWorld);
    const double det = std::abs(glm::determinant(a));
    if (!(det > 0.0)) return std::nullopt;
    // Area estimate for the power only: 4 pi times the squared geometric-mean radius.
    const double area = 4.0 * std::numbers::pi * std::pow(det, 2.0 / 3.0);
    std::optional<LightEntry> e =
        areaEmitter(LIGHT_SPHERE, index, static_cast<float>(det), lambertianEmitterPower(m, area));
    if (!e) return std::nullopt;
    e->light.position = glm::vec3(sphere.objectToWorld[0].w, sphere.objectToWorld[1].w, sphere.objectToWorld[2].w);
    double radius = 0.0;
    // Double-sided spheres are lit from inside too: area sampling covers both cases.
    if (!m.doubleSided && roundRadius(a, radius)) e->light.radius = static_cast<float>(radius);
    return e;
}

} // namespace pt
