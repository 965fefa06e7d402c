#pragma once
// How much a triangle emits through its material's emission texture: the texture averaged over
// the triangle, so light selection weighs a textured emitter by the light it gives, and a
// triangle whose texels are all black leaves the light table. (Leaving it out costs no
// correctness: emission that BSDF samples find on a triangle outside the table counts fully.)
// The texture is read as the kernel reads it: image_texture.glsl's wrap, filter and decoding,
// mirrored here on the CPU (TextureEmission.CpuSamplingMatchesTheKernel holds them equal).
#include "shared/layout.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <span>

namespace pt {

// RGBA of image texture `tex` at (untransformed) texture coordinates uv, with texels from the
// flattened texel buffer; procedural textures (course patterns) give 1.
glm::vec4 sampleImageTexture(const gpu::GpuTexture& tex, std::span<const uint32_t> texels, glm::vec2 uv);

// The mean RGB of texture `tex` over a triangle with texture coordinates uv[3]: stratified
// barycentric points, about one per texel of the triangle's footprint, at least 16 and at most
// 1024.
glm::vec3 averageOverTriangle(const gpu::GpuTexture& tex, std::span<const uint32_t> texels, const glm::vec2 uv[3]);

} // namespace pt
