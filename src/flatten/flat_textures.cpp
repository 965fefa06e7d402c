// Textures as the kernel reads them: one GpuTexture record per texture, and one texel buffer
// holding every image (packed RGBA8 as loaded, or 4 floats per texel for HDR images), so the
// kernel needs no descriptor indexing (Debian 12's own lavapipe lacks it).
#include "flatten/flat_scene.h"
#include "flatten/sheen_tables.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <stdexcept>

namespace pt {
namespace {

uint32_t wrapBits(TextureWrap w) {
    switch (w) {
    case TextureWrap::Repeat: return TEXTURE_WRAP_REPEAT;
    case TextureWrap::Clamp: return TEXTURE_WRAP_CLAMP;
    case TextureWrap::Mirror: return TEXTURE_WRAP_MIRROR;
    }
    return TEXTURE_WRAP_REPEAT;
}

// Appends an image to the texel buffer; returns its first uint.
uint32_t appendImage(const TextureImage& image, std::vector<uint32_t>& texels) {
    const size_t offset = texels.size();
    if (!image.rgbaF.empty()) {
        const size_t words = image.rgbaF.size() * 4;
        texels.resize(offset + words);
        std::memcpy(texels.data() + offset, image.rgbaF.data(), words * sizeof(uint32_t));
    } else {
        texels.insert(texels.end(), image.rgba8.begin(), image.rgba8.end());
    }
    if (texels.size() > 0xffffffffull) throw std::runtime_error("textures exceed 16 GiB of texels");
    return static_cast<uint32_t>(offset);
}

} // namespace

void flattenTextures(const Scene& scene, FlatScene& flat) {
    // Each image is stored once, however many textures read it.
    std::vector<int64_t> imageOffset(scene.textureImages.size(), -1);
    for (const Texture& t : scene.textures) {
        gpu::GpuTexture g{};
        g.valueScale = t.valueScale;
        g.uvRow0 = glm::vec4(t.uvRow0, 0.0f);
        g.uvRow1 = glm::vec4(t.uvRow1, 0.0f);
        g.patternScale = t.scale;
        g.patternOffset = t.offset;
        g.colorA = t.black;
        g.colorB = t.white;
        switch (t.type) {
        case Texture::Type::Image: {
            if (t.image >= scene.textureImages.size())
                throw std::runtime_error(scene.source + ": texture refers to a missing image");
            const TextureImage& image = scene.textureImages[t.image];
            if (imageOffset[t.image] < 0) imageOffset[t.image] = appendImage(image, flat.texels);
            g.type = TEXTURE_IMAGE;
            g.texelOffset = static_cast<uint32_t>(imageOffset[t.image]);
            g.width = static_cast<uint32_t>(image.width);
            g.height = static_cast<uint32_t>(image.height);
            if (!image.rgbaF.empty()) g.flags |= TEXTURE_FLAG_FLOAT;
            if (t.bilinear) g.flags |= TEXTURE_FLAG_BILINEAR;
            if (t.encoding == Texture::Encoding::Srgb) g.flags |= TEXTURE_FLAG_SRGB;
            if (t.encoding == Texture::Encoding::Gamma22) g.flags |= TEXTURE_FLAG_GAMMA_22;
            g.flags |= wrapBits(t.wrapU) << TEXTURE_WRAP_U_SHIFT;
            g.flags |= wrapBits(t.wrapV) << TEXTURE_WRAP_V_SHIFT;
            break;
        }
        case Texture::Type::Checkerboard: g.type = TEXTURE_CHECKERBOARD; break;
        case Texture::Type::Perlin:
            g.type = TEXTURE_PERLIN;
            if (t.perlinAbs) g.flags |= TEXTURE_FLAG_PERLIN_ABS;
            break;
        }
        flat.textures.push_back(g);
    }
    if (scene.backgroundTexture) flat.backgroundTexture = *scene.backgroundTexture;
    // The sheen lobe's tables, where a material has a sheen.
    if (std::any_of(flat.materials.begin(), flat.materials.end(), hasSheen)) {
        flat.sheenTables = static_cast<uint32_t>(flat.texels.size());
        for (const auto* table : {&kSheenProjectedArea, &kSheenAlbedo})
            for (float v : *table) flat.texels.push_back(std::bit_cast<uint32_t>(v));
    }
    for (const gpu::GpuMaterial& m : flat.materials)
        for (uint32_t slot : materialTextureSlots(m))
            if (slot != NO_TEXTURE && slot >= flat.textures.size())
                throw std::runtime_error(scene.source + ": a material refers to a texture that does not exist");
}

} // namespace pt
