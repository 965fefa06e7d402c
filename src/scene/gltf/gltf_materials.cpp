// glTF materials into the scene model (gltf_importer.h): the metallic-roughness factors, the
// KHR_materials_* extensions (emissive_strength, ior, specular, transmission, volume,
// diffuse_transmission, clearcoat, sheen, iridescence, anisotropy, dispersion, unlit), the
// textures with their samplers and KHR_texture_transform, the images they use, and the glTF
// default material for primitives without one.
#include "scene/gltf/gltf_importer.h"

namespace pt::gltf {
namespace {

const tinygltf::Value* extension(const tinygltf::Material& m, const char* name) {
    auto it = m.extensions.find(name);
    return it == m.extensions.end() ? nullptr : &it->second;
}

} // namespace

// An extension's number: absent, the extension's default (no note: the glTF spec defines it);
// present but not a number, the default too, and a note saying so.
double GltfImporter::number(const tinygltf::Value& obj, const char* key, double fallback, const std::string& where) {
    if (!obj.IsObject() || !obj.Has(key)) return fallback;
    const tinygltf::Value& v = obj.Get(key);
    if (v.IsNumber()) return v.GetNumberAsDouble();
    unsupported(where + ": " + key + " is not a number (" + formatNumber(fallback) + " assumed)");
    return fallback;
}

// An extension's RGB colour, the same way: three numbers, else the default and a note.
glm::vec3 GltfImporter::color(
    const tinygltf::Value& obj, const char* key, glm::vec3 fallback, const std::string& where) {
    if (!obj.IsObject() || !obj.Has(key)) return fallback;
    const tinygltf::Value& v = obj.Get(key);
    bool ok = v.IsArray() && v.ArrayLen() == 3;
    glm::vec3 c = fallback;
    for (int i = 0; ok && i < 3; ++i) {
        ok = v.Get(i).IsNumber();
        if (ok) c[i] = static_cast<float>(v.Get(i).GetNumberAsDouble());
    }
    if (ok) return c;
    unsupported(where + ": " + key + " is not 3 numbers (" + formatNumber(fallback.x) + " " + formatNumber(fallback.y) +
                " " + formatNumber(fallback.z) + " assumed)");
    return fallback;
}

void GltfImporter::convertMaterials() {
    for (size_t i = 0; i < model_.materials.size(); ++i) {
        const tinygltf::Material& src = model_.materials[i];
        const std::string label = "material " + std::to_string(i) + (src.name.empty() ? "" : " '" + src.name + "'");
        Material m;
        m.name = src.name.empty() ? "material " + std::to_string(i) : src.name;
        m.doubleSided = src.doubleSided;
        const auto& pbr = src.pbrMetallicRoughness;
        // tinygltf fills in the spec's defaults and rejects any other length.
        for (int c = 0; c < 3; ++c)
            m.baseColor[c] = pbr.baseColorFactor.size() > 2 ? static_cast<float>(pbr.baseColorFactor[c]) : 1.0f;
        for (int c = 0; c < 3; ++c)
            m.emission[c] = src.emissiveFactor.size() > 2 ? static_cast<float>(src.emissiveFactor[c]) : 0.0f;
        if (const auto* e = extension(src, "KHR_materials_emissive_strength"))
            m.emission *= static_cast<float>(number(*e, "emissiveStrength", 1.0, label));
        if (!finite(m.baseColor) || !finite(m.emission) || glm::any(glm::lessThan(m.emission, glm::vec3(0))))
            fail(label + ": base colour and emission must be finite and non-negative");
        if (glm::any(glm::greaterThan(m.baseColor, glm::vec3(1.0f))))
            unsupported("baseColorFactor above 1 (clamped to 1)");
        m.baseColor = glm::clamp(m.baseColor, 0.0f, 1.0f);

        convertFactors(src, label, m);
        convertTextures(src, label, m);
        if (extension(src, "KHR_materials_pbrSpecularGlossiness")) convertSpecularGlossiness(src, label, m);
        scene_.materials.push_back(m);
    }
}

// The glTF metallic-roughness factors and the KHR_materials_* extensions. Everything is a
// MaterialType::Pbr (shaders/bsdf/gltf_pbr.glsl) except three cases where the glTF model
// reduces exactly to a simpler one, which the kernel evaluates and samples for less (a scene
// with none of the full model left compiles none of its code): scenes made for other renderers
// (the Mitsuba references in tests/references) use them to say "Lambertian", "metal" and "glass":
//   metallic 0, transmission 0, KHR_materials_specular specularFactor 0  -> Lambertian
//   metallic 1                                                            -> Schlick metal: a
//     mirror, GGX-rough when rough (the model's dielectric half, its base and transmission
//     included, has weight 0 there)
//   metallic 0, transmission 1, default specular, KHR_materials_volume    -> dielectric (GGX
//     when rough), which also carries the volume's Beer-Lambert absorption.
void GltfImporter::convertFactors(const tinygltf::Material& src, const std::string& label, Material& m) {
    const auto& pbr = src.pbrMetallicRoughness;
    auto unit = [&](double v, const char* what) {
        if (!(v >= 0.0 && v <= 1.0)) fail(label + ": " + what + " " + std::to_string(v) + " must be in [0, 1]");
        return static_cast<float>(v);
    };
    m.metallic = unit(pbr.metallicFactor, "metallicFactor");
    m.roughness = unit(pbr.roughnessFactor, "roughnessFactor");
    if (const auto* e = extension(src, "KHR_materials_transmission"))
        m.transmission = unit(number(*e, "transmissionFactor", 0.0, label), "transmissionFactor");
    if (const auto* e = extension(src, "KHR_materials_ior")) m.ior = static_cast<float>(number(*e, "ior", 1.5, label));
    if (!(m.ior >= 1.0f && m.ior < 10.0f)) fail(label + ": ior " + std::to_string(m.ior) + " must be in [1, 10)");
    m.specular = glm::vec3(1.0f);
    if (const auto* e = extension(src, "KHR_materials_specular")) {
        m.specularWeight = unit(number(*e, "specularFactor", 1.0, label), "specularFactor");
        m.specular = color(*e, "specularColorFactor", glm::vec3(1.0f), label);
        if (!finite(m.specular) || glm::any(glm::lessThan(m.specular, glm::vec3(0))))
            fail(label + ": specularColorFactor must be finite and non-negative");
    }
    // A volume makes transmission refract; thicknessFactor only approximates the volume's
    // depth for rasterisers (the path tracer has the mesh itself), so only 0 -- "thin
    // walled" -- is used from it.
    const tinygltf::Value* volume = extension(src, "KHR_materials_volume");
    m.thinWalled = volume == nullptr || number(*volume, "thicknessFactor", 0.0, label) <= 0.0;
    if (volume) {
        m.attenuationColor = color(*volume, "attenuationColor", glm::vec3(1.0f), label);
        m.attenuationDistance = static_cast<float>(number(*volume, "attenuationDistance", INFINITY, label));
        if (!(m.attenuationDistance > 0) || !finite(m.attenuationColor) ||
            glm::any(glm::lessThan(m.attenuationColor, glm::vec3(0))))
            fail(label + ": KHR_materials_volume attenuation must be positive");
    }
    if (const auto* e = extension(src, "KHR_materials_diffuse_transmission")) {
        m.diffuseTransmission = unit(number(*e, "diffuseTransmissionFactor", 0.0, label), "diffuseTransmissionFactor");
        m.diffuseTransmissionColor = color(*e, "diffuseTransmissionColorFactor", glm::vec3(1.0f), label);
        if (!finite(m.diffuseTransmissionColor) || glm::any(glm::lessThan(m.diffuseTransmissionColor, glm::vec3(0))) ||
            glm::any(glm::greaterThan(m.diffuseTransmissionColor, glm::vec3(1))))
            fail(label + ": diffuseTransmissionColorFactor must be in [0, 1]");
    }
    if (const auto* e = extension(src, "KHR_materials_clearcoat")) {
        m.clearcoat = unit(number(*e, "clearcoatFactor", 0.0, label), "clearcoatFactor");
        m.clearcoatRoughness = unit(number(*e, "clearcoatRoughnessFactor", 0.0, label), "clearcoatRoughnessFactor");
    }
    if (const auto* e = extension(src, "KHR_materials_sheen")) {
        m.sheenColor = color(*e, "sheenColorFactor", glm::vec3(0.0f), label);
        if (!finite(m.sheenColor) || glm::any(glm::lessThan(m.sheenColor, glm::vec3(0))) ||
            glm::any(glm::greaterThan(m.sheenColor, glm::vec3(1))))
            fail(label + ": sheenColorFactor must be in [0, 1]");
        m.sheenRoughness = unit(number(*e, "sheenRoughnessFactor", 0.0, label), "sheenRoughnessFactor");
    }
    if (const auto* e = extension(src, "KHR_materials_iridescence")) {
        m.iridescence = unit(number(*e, "iridescenceFactor", 0.0, label), "iridescenceFactor");
        m.iridescenceIor = static_cast<float>(number(*e, "iridescenceIor", 1.3, label));
        m.iridescenceThicknessMinimum = static_cast<float>(number(*e, "iridescenceThicknessMinimum", 100.0, label));
        m.iridescenceThicknessMaximum = static_cast<float>(number(*e, "iridescenceThicknessMaximum", 400.0, label));
        if (!(m.iridescenceIor >= 1.0f && m.iridescenceIor < 10.0f))
            fail(label + ": iridescenceIor " + std::to_string(m.iridescenceIor) + " must be in [1, 10)");
        if (!(m.iridescenceThicknessMinimum >= 0.0f && m.iridescenceThicknessMaximum >= 0.0f &&
                m.iridescenceThicknessMinimum < 1e6f && m.iridescenceThicknessMaximum < 1e6f))
            fail(label + ": iridescence thicknesses must be in [0, 1e6) nm");
    }
    if (const auto* e = extension(src, "KHR_materials_anisotropy")) {
        m.anisotropy = unit(number(*e, "anisotropyStrength", 0.0, label), "anisotropyStrength");
        m.anisotropyRotation = static_cast<float>(number(*e, "anisotropyRotation", 0.0, label));
        if (!std::isfinite(m.anisotropyRotation)) fail(label + ": anisotropyRotation must be finite");
    }
    // KHR_materials_dispersion (20 / Abbe number): the dielectric's or the transmission's index
    // varies with wavelength (shaders/common/spectrum.glsl).
    if (const auto* e = extension(src, "KHR_materials_dispersion")) {
        const double dispersion = number(*e, "dispersion", 0.0, label);
        if (!(dispersion >= 0.0 && dispersion <= 1000.0))
            fail(label + ": dispersion " + std::to_string(dispersion) + " must be in [0, 1000]");
        m.dispersion = static_cast<float>(dispersion);
    }
    // A coat, a sheen, a film or anisotropy changes whatever the base is: only the full model has
    // them.
    const bool layered = m.clearcoat > 0.0f || glm::any(glm::greaterThan(m.sheenColor, glm::vec3(0))) ||
                         m.iridescence > 0.0f || m.anisotropy > 0.0f;
    const bool defaultSpecular = m.specularWeight == 1.0f && m.specular == glm::vec3(1.0f);
    if (layered) {
        m.type = MaterialType::Pbr;
    } else if (m.metallic == 0.0f && m.transmission == 0.0f && m.specularWeight == 0.0f &&
               m.diffuseTransmission == 0.0f) {
        m.type = MaterialType::Diffuse;
    } else if (m.metallic == 1.0f) {
        m.type = MaterialType::Mirror;
    } else if (m.metallic == 0.0f && m.transmission == 1.0f && defaultSpecular && !m.thinWalled) {
        m.type = MaterialType::Dielectric;
    } else {
        m.type = MaterialType::Pbr;
    }
    // KHR_materials_unlit: the base colour (and texture) shown as is, the course's replace_all
    // surfaces' model: radiance baseColor toward every ray that hits it, no reflection.
    if (extension(src, "KHR_materials_unlit")) {
        m.unlit = true;
        m.type = MaterialType::Diffuse;
    }
}

// KHR_materials_pbrSpecularGlossiness (archived by Khronos, still in files people have): it takes
// the place of the metallic-roughness factors. Its model is a Lambertian diffuse under a GGX
// specular of F0 = specularFactor, roughness 1 - glossiness, which is the metallic-roughness
// model's dielectric with metallic 0, ior 1.5 (F0 0.04) and KHR_materials_specular's colour
// specularFactor / 0.04 (F0 is that product, shaders/bsdf/gltf_pbr.glsl). Its textures: diffuse
// (sRGB, alpha = opacity) as the base colour; specularGlossiness's sRGB rgb as the specular
// colour and its alpha as glossiness (MATERIAL_FLAG_GLOSSINESS).
void GltfImporter::convertSpecularGlossiness(const tinygltf::Material& src, const std::string& label, Material& m) {
    const tinygltf::Value& e = *extension(src, "KHR_materials_pbrSpecularGlossiness");
    const std::string where = label + ": KHR_materials_pbrSpecularGlossiness";
    glm::vec4 diffuse(1.0f);
    if (e.Has("diffuseFactor") && e.Get("diffuseFactor").IsArray() && e.Get("diffuseFactor").ArrayLen() == 4)
        for (int c = 0; c < 4; ++c) diffuse[c] = static_cast<float>(e.Get("diffuseFactor").Get(c).GetNumberAsDouble());
    const glm::vec3 specular = color(e, "specularFactor", glm::vec3(1.0f), where);
    const double glossiness = number(e, "glossinessFactor", 1.0, where);
    if (!finite(glm::vec3(diffuse)) || !std::isfinite(diffuse.w) || glm::any(glm::lessThan(diffuse, glm::vec4(0))) ||
        glm::any(glm::greaterThan(diffuse, glm::vec4(1))))
        fail(where + ": diffuseFactor must be 4 numbers in [0, 1]");
    if (!finite(specular) || glm::any(glm::lessThan(specular, glm::vec3(0))) ||
        glm::any(glm::greaterThan(specular, glm::vec3(1))))
        fail(where + ": specularFactor must be in [0, 1]");
    if (!(glossiness >= 0.0 && glossiness <= 1.0)) fail(where + ": glossinessFactor must be in [0, 1]");
    m.type = MaterialType::Pbr;
    m.baseColor = glm::vec3(diffuse);
    m.opacity = diffuse.w;
    m.metallic = 0.0f;
    m.transmission = 0.0f;
    m.ior = 1.5f;
    m.specularWeight = 1.0f;
    m.specular = specular / 0.04f;
    m.glossiness = static_cast<float>(glossiness);
    m.roughness = 1.0f - m.glossiness;
    m.baseColorTexture = extensionTexture(&e, "diffuseTexture", Texture::Encoding::Srgb, where);
    m.specularTexture = extensionTexture(&e, "specularGlossinessTexture", Texture::Encoding::Srgb, where);
    m.metallicRoughnessTexture = m.specularTexture;
    m.glossinessTexture = m.specularTexture.has_value();
    m.specularWeightTexture.reset();
}

// ---- textures ----
// baseColor and emissive are sRGB-encoded, metallicRoughness and normal linear (glTF 2.0
// section 3.9). Occlusion is for rasterisers: a path tracer computes it.
void GltfImporter::convertTextures(const tinygltf::Material& src, const std::string& label, Material& m) {
    const auto& pbr = src.pbrMetallicRoughness;
    m.baseColorTexture = texture(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
        pbr.baseColorTexture.extensions, Texture::Encoding::Srgb, label + ": baseColorTexture");
    m.metallicRoughnessTexture = texture(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
        pbr.metallicRoughnessTexture.extensions, Texture::Encoding::Linear, label + ": metallicRoughnessTexture");
    m.normalTexture = texture(src.normalTexture.index, src.normalTexture.texCoord, src.normalTexture.extensions,
        Texture::Encoding::Linear, label + ": normalTexture");
    m.normalScale = static_cast<float>(src.normalTexture.scale);
    if (!std::isfinite(m.normalScale)) fail(label + ": normalTexture scale must be finite");
    m.emissiveTexture = texture(src.emissiveTexture.index, src.emissiveTexture.texCoord, src.emissiveTexture.extensions,
        Texture::Encoding::Srgb, label + ": emissiveTexture");
    // The extensions' textures: specularTexture's alpha scales specularFactor, specularColorTexture
    // (sRGB) the specular colour, transmissionTexture's red channel the transmission factor.
    const tinygltf::Value* specular = extension(src, "KHR_materials_specular");
    m.specularWeightTexture =
        extensionTexture(specular, "specularTexture", Texture::Encoding::Linear, label + ": KHR_materials_specular");
    m.specularTexture =
        extensionTexture(specular, "specularColorTexture", Texture::Encoding::Srgb, label + ": KHR_materials_specular");
    m.transmissionTexture = extensionTexture(extension(src, "KHR_materials_transmission"), "transmissionTexture",
        Texture::Encoding::Linear, label + ": KHR_materials_transmission");
    // KHR_materials_diffuse_transmission: the factor's texture in alpha (linear), the colour's in
    // RGB (sRGB).
    const tinygltf::Value* diffuse = extension(src, "KHR_materials_diffuse_transmission");
    m.diffuseTransmissionTexture = extensionTexture(diffuse, "diffuseTransmissionTexture", Texture::Encoding::Linear,
        label + ": KHR_materials_diffuse_transmission");
    m.diffuseTransmissionColorTexture = extensionTexture(diffuse, "diffuseTransmissionColorTexture",
        Texture::Encoding::Srgb, label + ": KHR_materials_diffuse_transmission");
    // KHR_materials_clearcoat: the factor's texture in red, the roughness's in green (both
    // linear), and the coat's own normal map (none: the coat keeps the surface's normal, not the
    // base's normal map). KHR_materials_sheen: the colour's texture in RGB (sRGB), the
    // roughness's in alpha (linear).
    const tinygltf::Value* clearcoat = extension(src, "KHR_materials_clearcoat");
    m.clearcoatTexture =
        extensionTexture(clearcoat, "clearcoatTexture", Texture::Encoding::Linear, label + ": KHR_materials_clearcoat");
    m.clearcoatRoughnessTexture = extensionTexture(
        clearcoat, "clearcoatRoughnessTexture", Texture::Encoding::Linear, label + ": KHR_materials_clearcoat");
    m.clearcoatNormalTexture = extensionTexture(
        clearcoat, "clearcoatNormalTexture", Texture::Encoding::Linear, label + ": KHR_materials_clearcoat");
    if (m.clearcoatNormalTexture) {
        const tinygltf::Value& info = clearcoat->Get("clearcoatNormalTexture");
        m.clearcoatNormalScale =
            static_cast<float>(number(info, "scale", 1.0, label + ": KHR_materials_clearcoat clearcoatNormalTexture"));
        if (!std::isfinite(m.clearcoatNormalScale)) fail(label + ": clearcoatNormalTexture scale must be finite");
    }
    const tinygltf::Value* sheen = extension(src, "KHR_materials_sheen");
    m.sheenColorTexture =
        extensionTexture(sheen, "sheenColorTexture", Texture::Encoding::Srgb, label + ": KHR_materials_sheen");
    m.sheenRoughnessTexture =
        extensionTexture(sheen, "sheenRoughnessTexture", Texture::Encoding::Linear, label + ": KHR_materials_sheen");
    // KHR_materials_iridescence: the factor's texture in red, the thickness's in green (linear).
    const tinygltf::Value* film = extension(src, "KHR_materials_iridescence");
    m.iridescenceTexture =
        extensionTexture(film, "iridescenceTexture", Texture::Encoding::Linear, label + ": KHR_materials_iridescence");
    m.iridescenceThicknessTexture = extensionTexture(
        film, "iridescenceThicknessTexture", Texture::Encoding::Linear, label + ": KHR_materials_iridescence");
    // KHR_materials_anisotropy: direction in red and green, strength in blue (linear).
    m.anisotropyTexture = extensionTexture(extension(src, "KHR_materials_anisotropy"), "anisotropyTexture",
        Texture::Encoding::Linear, label + ": KHR_materials_anisotropy");
    // A texture can make a "metal" vary in roughness or part-dielectric, and a "glass"
    // part-transmissive or of varying specular: only the full model covers those.
    if (m.metallicRoughnessTexture && m.type == MaterialType::Mirror) m.type = MaterialType::Pbr;
    if ((m.specularWeightTexture || m.specularTexture || m.transmissionTexture) && m.type == MaterialType::Dielectric)
        m.type = MaterialType::Pbr;

    m.opacity = pbr.baseColorFactor.size() > 3 ? static_cast<float>(pbr.baseColorFactor[3]) : 1.0f;
    if (!(m.opacity >= 0.0f && m.opacity <= 1.0f)) fail(label + ": baseColorFactor alpha must be in [0, 1]");
    if (src.alphaMode == "MASK") {
        m.alphaMode = Material::AlphaMode::Mask;
        m.alphaCutoff = static_cast<float>(src.alphaCutoff);
        if (!std::isfinite(m.alphaCutoff)) fail(label + ": alphaCutoff must be finite");
    } else if (src.alphaMode == "BLEND") {
        m.alphaMode = Material::AlphaMode::Blend;
    } else if (!src.alphaMode.empty() && src.alphaMode != "OPAQUE") {
        fail(label + ": unknown alphaMode '" + src.alphaMode + "'");
    }
}

int GltfImporter::wrap(int mode, const std::string& where, const GltfImporter& self) {
    switch (mode) {
    case 10497: return static_cast<int>(TextureWrap::Repeat);
    case 33071: return static_cast<int>(TextureWrap::Clamp);
    case 33648: return static_cast<int>(TextureWrap::Mirror);
    default: self.fail(where + ": unknown wrap mode " + std::to_string(mode));
    }
}

// The textureInfo `key` of a material extension's object, or none.
std::optional<uint32_t> GltfImporter::extensionTexture(
    const tinygltf::Value* ext, const char* key, Texture::Encoding encoding, const std::string& where) {
    if (ext == nullptr || !ext->IsObject() || !ext->Has(key)) return std::nullopt;
    const tinygltf::Value& info = ext->Get(key);
    const std::string what = where + ": " + key;
    if (!info.IsObject() || !info.Has("index") || !info.Get("index").IsInt()) fail(what + " has no texture index");
    const int texCoord =
        info.Has("texCoord") && info.Get("texCoord").IsInt() ? info.Get("texCoord").GetNumberAsInt() : 0;
    tinygltf::ExtensionMap extensions;
    if (info.Has("extensions") && info.Get("extensions").IsObject())
        for (const std::string& name : info.Get("extensions").Keys())
            extensions[name] = info.Get("extensions").Get(name);
    return texture(info.Get("index").GetNumberAsInt(), texCoord, extensions, encoding, what);
}

// A scene texture for one textureInfo (with its KHR_texture_transform), or none.
std::optional<uint32_t> GltfImporter::texture(int index, int texCoord, const tinygltf::ExtensionMap& extensions,
    Texture::Encoding encoding, const std::string& where) {
    if (index < 0) return std::nullopt;
    if (index >= static_cast<int>(model_.textures.size()))
        fail(where + ": texture " + std::to_string(index) + " does not exist");
    const tinygltf::Texture& src = model_.textures[index];
    if (src.source < 0 || src.source >= static_cast<int>(model_.images.size()))
        fail(where + ": texture " + std::to_string(index) + " has no image (or one in an unsupported extension)");
    Texture t;
    t.encoding = encoding;
    t.image = imageIndex(src.source, where);
    if (src.sampler >= 0) {
        if (src.sampler >= static_cast<int>(model_.samplers.size()))
            fail(where + ": sampler " + std::to_string(src.sampler) + " does not exist");
        const tinygltf::Sampler& sampler = model_.samplers[src.sampler];
        t.bilinear = sampler.magFilter != 9728; // NEAREST
        t.wrapU = static_cast<TextureWrap>(wrap(sampler.wrapS, where, *this));
        t.wrapV = static_cast<TextureWrap>(wrap(sampler.wrapT, where, *this));
    }
    // KHR_texture_transform: uv' = T(offset) R(rotation) S(scale) uv.
    if (auto e = extensions.find("KHR_texture_transform"); e != extensions.end()) {
        const tinygltf::Value& x = e->second;
        const double rotation = number(x, "rotation", 0.0, where + ": KHR_texture_transform");
        glm::dvec2 offset(0.0), scale(1.0);
        auto pair = [&](const char* key, glm::dvec2& out) {
            if (!x.IsObject() || !x.Has(key)) return;
            const tinygltf::Value& v = x.Get(key);
            if (v.IsArray() && v.ArrayLen() == 2 && v.Get(0).IsNumber() && v.Get(1).IsNumber()) {
                out = glm::dvec2(v.Get(0).GetNumberAsDouble(), v.Get(1).GetNumberAsDouble());
                return;
            }
            unsupported(where + ": KHR_texture_transform: " + key + " is not 2 numbers (" + formatNumber(out.x) + " " +
                        formatNumber(out.y) + " assumed)");
        };
        pair("offset", offset);
        pair("scale", scale);
        if (!std::isfinite(rotation) || !std::isfinite(offset.x + offset.y + scale.x + scale.y))
            fail(where + ": KHR_texture_transform values must be finite");
        const double c = std::cos(rotation), s = std::sin(rotation);
        t.uvRow0 = glm::vec3(c * scale.x, s * scale.y, offset.x);
        t.uvRow1 = glm::vec3(-s * scale.x, c * scale.y, offset.y);
        if (x.Has("texCoord") && x.Get("texCoord").IsInt()) texCoord = x.Get("texCoord").GetNumberAsInt();
    }
    if (texCoord != 0) unsupported("texture coordinate sets other than TEXCOORD_0 (TEXCOORD_0 used)");
    scene_.textures.push_back(t);
    return static_cast<uint32_t>(scene_.textures.size() - 1);
}

// The scene image for glTF image `index`, moved out of the decoded set on first use.
uint32_t GltfImporter::imageIndex(int index, const std::string& where) {
    if (auto it = imageIndices_.find(index); it != imageIndices_.end()) return it->second;
    if (static_cast<size_t>(index) >= decoded_.images.size() || !decoded_.images[index])
        fail(where + ": image " + std::to_string(index) +
             (model_.images[index].uri.empty() || model_.images[index].uri.rfind("data:", 0) == 0
                     ? ""
                     : " '" + model_.images[index].uri + "'") +
             " has no data (its file was not found or could not be read)");
    scene_.textureImages.push_back(std::move(*decoded_.images[index]));
    decoded_.images[index].reset();
    const uint32_t i = static_cast<uint32_t>(scene_.textureImages.size() - 1);
    imageIndices_.emplace(index, i);
    return i;
}

uint32_t GltfImporter::defaultMaterial() {
    if (defaultMaterial_ < 0) {
        Material m;
        m.name = "glTF default";
        // The glTF default material: white, metallic 1, roughness 1.
        m.type = MaterialType::Pbr;
        m.baseColor = glm::vec3(1.0f);
        m.metallic = 1.0f;
        m.roughness = 1.0f;
        m.specular = glm::vec3(1.0f);
        defaultMaterial_ = static_cast<int>(scene_.materials.size());
        scene_.materials.push_back(m);
    }
    return static_cast<uint32_t>(defaultMaterial_);
}

} // namespace pt::gltf
