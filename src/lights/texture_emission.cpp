#include "lights/texture_emission.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace pt {
namespace {

float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

glm::vec4 fetchTexel(const gpu::GpuTexture& tex, std::span<const uint32_t> texels, int x, int y) {
    const size_t index = size_t(y) * tex.width + size_t(x);
    if (tex.flags & TEXTURE_FLAG_FLOAT) {
        const size_t base = tex.texelOffset + 4 * index;
        if (base + 3 >= texels.size()) return glm::vec4(0.0f);
        glm::vec4 c;
        std::memcpy(&c, &texels[base], sizeof c);
        return c;
    }
    if (tex.texelOffset + index >= texels.size()) return glm::vec4(0.0f);
    const uint32_t packed = texels[tex.texelOffset + index];
    glm::vec4 c(float(packed & 255u), float((packed >> 8) & 255u), float((packed >> 16) & 255u), float(packed >> 24));
    c /= 255.0f;
    if (tex.flags & TEXTURE_FLAG_SRGB)
        c = glm::vec4(srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b), c.a);
    else if (tex.flags & TEXTURE_FLAG_GAMMA_22)
        c = glm::vec4(std::pow(c.r, 2.2f), std::pow(c.g, 2.2f), std::pow(c.b, 2.2f), c.a);
    return c;
}

int positiveRemainder(int i, int n) {
    if (i < 0) i += n * ((n - 1 - i) / n);
    return i % n;
}

int wrapTexel(int i, int size, uint32_t mode) {
    if (mode == TEXTURE_WRAP_CLAMP) return std::clamp(i, 0, size - 1);
    if (mode == TEXTURE_WRAP_MIRROR) {
        const int period = 2 * size;
        const int m = positiveRemainder(i, period);
        return m < size ? m : period - 1 - m;
    }
    return positiveRemainder(i, size);
}

} // namespace

glm::vec4 sampleImageTexture(const gpu::GpuTexture& tex, std::span<const uint32_t> texels, glm::vec2 uv) {
    if (tex.type != TEXTURE_IMAGE || tex.width == 0 || tex.height == 0) return glm::vec4(1.0f);
    const glm::vec2 t(
        glm::dot(glm::vec2(tex.uvRow0), uv) + tex.uvRow0.z, glm::dot(glm::vec2(tex.uvRow1), uv) + tex.uvRow1.z);
    const uint32_t wrapU = (tex.flags >> TEXTURE_WRAP_U_SHIFT) & 3u, wrapV = (tex.flags >> TEXTURE_WRAP_V_SHIFT) & 3u;
    const glm::ivec2 size(int(tex.width), int(tex.height));
    const glm::vec2 st = glm::clamp(t * glm::vec2(size), glm::vec2(-16777216.0f), glm::vec2(16777216.0f));
    glm::vec4 value;
    if (!(tex.flags & TEXTURE_FLAG_BILINEAR)) {
        const glm::ivec2 i(glm::floor(st));
        value = fetchTexel(tex, texels, wrapTexel(i.x, size.x, wrapU), wrapTexel(i.y, size.y, wrapV));
    } else {
        const glm::vec2 f = st - 0.5f;
        const glm::ivec2 i0(glm::floor(f));
        const glm::vec2 w = f - glm::vec2(i0);
        const int x0 = wrapTexel(i0.x, size.x, wrapU), x1 = wrapTexel(i0.x + 1, size.x, wrapU);
        const int y0 = wrapTexel(i0.y, size.y, wrapV), y1 = wrapTexel(i0.y + 1, size.y, wrapV);
        value = glm::mix(glm::mix(fetchTexel(tex, texels, x0, y0), fetchTexel(tex, texels, x1, y0), w.x),
            glm::mix(fetchTexel(tex, texels, x0, y1), fetchTexel(tex, texels, x1, y1), w.x), w.y);
    }
    return glm::vec4(glm::vec3(value) * tex.valueScale, value.a);
}

glm::vec3 averageOverTriangle(const gpu::GpuTexture& tex, std::span<const uint32_t> texels, const glm::vec2 uv[3]) {
    // The footprint in texels sets the density: a triangle over many texels must not miss the
    // bright ones, one inside a texel needs few points.
    const glm::vec2 e1 = uv[1] - uv[0], e2 = uv[2] - uv[0];
    const glm::vec2 scale(glm::length(glm::vec2(tex.uvRow0)), glm::length(glm::vec2(tex.uvRow1)));
    const double footprint =
        0.5 * std::abs(double(e1.x) * e2.y - double(e1.y) * e2.x) * scale.x * scale.y * tex.width * tex.height;
    const int n = int(std::clamp(std::ceil(std::sqrt(std::isfinite(footprint) ? footprint : 1024.0)), 4.0, 32.0));
    // n x n stratified points of the unit square, folded onto the triangle (u + v <= 1).
    glm::dvec3 sum(0.0);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            float a = (i + 0.5f) / n, b = (j + 0.5f) / n;
            if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
            const glm::vec2 p = uv[0] + a * e1 + b * e2;
            sum += glm::dvec3(glm::vec3(sampleImageTexture(tex, texels, p)));
        }
    return glm::vec3(sum / double(n * n));
}

} // namespace pt
