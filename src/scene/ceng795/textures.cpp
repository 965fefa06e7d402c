#include "scene/ceng795/textures.h"

#include "image/texture_image.h"

#include <cmath>
#include <utility>

namespace pt::ceng795 {
namespace {

const char* const kDecalModes[] = {
    "replace_kd", "blend_kd", "replace_ks", "replace_background", "replace_normal", "bump_normal", "replace_all"};

std::string decalMode(const Context& ctx, pugi::xml_node map) {
    pugi::xml_node d = required(ctx, map, "DecalMode");
    const std::string text = textOf(d);
    const std::vector<std::string_view> t = tokens(text);
    const std::string mode = t.size() == 1 ? lowercase(t[0]) : "";
    for (const char* known : kDecalModes)
        if (mode == known) return mode;
    ctx.fail(d, "unknown decal mode " + quote(textOf(d)));
}

bool degamma(const Context& ctx, pugi::xml_node e) {
    pugi::xml_attribute a = e.attribute("degamma");
    return a && booleanValue(ctx, e, a.value(), "degamma");
}

float positive(const Context& ctx, pugi::xml_node parent, const char* child, float fallback) {
    const std::optional<float> v = optionalScalar(ctx, parent, child);
    if (!v) return fallback;
    if (!(*v > 0.0f)) ctx.fail(parent.child(child), "must be positive");
    return *v;
}

} // namespace

TextureTable TextureTable::read(Context& ctx, pugi::xml_node scene, Scene& out) {
    TextureTable table;
    table.scene_ = scene;
    for (pugi::xml_node textures : scene.children("Textures"))
        for (pugi::xml_node map : textures.children("TextureMap")) {
            const long long id = idOf(ctx, map);
            if (table.maps_.count(id)) ctx.fail(map, "duplicate id");
            table.maps_.emplace(id, MapDefinition{map, decalMode(ctx, map), std::nullopt});
        }
    for (auto& [id, map] : table.maps_)
        if (map.decalMode == "replace_background") {
            if (out.backgroundTexture) ctx.fail(map.element, "a second replace_background texture");
            out.backgroundTexture = table.texture(ctx, map, out);
        }
    return table;
}

uint32_t TextureTable::image(Context& ctx, pugi::xml_node where, long long imageId, Scene& out) {
    if (auto it = images_.find(imageId); it != images_.end()) return it->second;
    for (pugi::xml_node images : scene_.children("Textures"))
        for (pugi::xml_node image : images.children("Images"))
            for (pugi::xml_node e : image.children("Image")) {
                if (idOf(ctx, e) != imageId) continue;
                // A file name: the element's text without surrounding whitespace.
                const std::string text = textOf(e);
                const std::vector<std::string_view> name = tokens(text);
                if (name.size() != 1) ctx.fail(e, "is not one file name");
                TextureImage loaded;
                try {
                    loaded = loadTextureImage(ctx.resolve(name[0]));
                } catch (const std::exception& err) {
                    ctx.fail(e, err.what());
                }
                out.textureImages.push_back(std::move(loaded));
                const uint32_t index = static_cast<uint32_t>(out.textureImages.size() - 1);
                images_.emplace(imageId, index);
                return index;
            }
    ctx.fail(where, "unknown image " + std::to_string(imageId));
}

uint32_t TextureTable::texture(Context& ctx, MapDefinition& map, Scene& out) {
    if (map.texture) return *map.texture;
    pugi::xml_node e = map.element;
    const std::string type = lowercase(e.attribute("type").value());
    Texture t;
    if (type == "image") {
        pugi::xml_node id = required(ctx, e, "ImageId");
        t.type = Texture::Type::Image;
        t.image = image(ctx, id,
            integer(ctx, id, std::numeric_limits<long long>::min(), std::numeric_limits<long long>::max()), out);
        const TextureImage& img = out.textureImages[t.image];
        // Values are texel / Normalizer with 8-bit texels in 0..255 (default 255, so 0..1).
        // HDR texels are used as they are unless a Normalizer is given.
        const std::optional<float> normalizer = optionalScalar(ctx, e, "Normalizer");
        if (normalizer && !(*normalizer > 0.0f)) ctx.fail(e.child("Normalizer"), "must be positive");
        if (img.rgbaF.empty()) {
            t.valueScale = 255.0f / normalizer.value_or(255.0f);
        } else {
            t.valueScale = 1.0f / normalizer.value_or(1.0f);
            // The course's default of 255 is for 8-bit texels.
            if (!normalizer) ctx.note(label(e) + ": no Normalizer for an HDR image (1, texels as stored, assumed)");
        }
        if (pugi::xml_node interp = e.child("Interpolation")) {
            const std::string mode = lowercase(textOf(interp));
            if (mode.find("nearest") != std::string::npos)
                t.bilinear = false;
            else if (mode.find("bilinear") == std::string::npos)
                ctx.fail(interp, "is not nearest or bilinear");
        } else {
            // The format leaves it unspecified (docs/ceng795-format.md section 12).
            ctx.note(label(e) + ": no Interpolation (bilinear assumed)");
        }
        if (degamma(ctx, e)) t.encoding = Texture::Encoding::Gamma22;
    } else if (type == "checkerboard") {
        t.type = Texture::Type::Checkerboard;
        t.black = optionalVec3(ctx, e, "BlackColor").value_or(glm::vec3(0.0f));
        t.white = optionalVec3(ctx, e, "WhiteColor").value_or(glm::vec3(1.0f));
        t.scale = optionalScalar(ctx, e, "Scale").value_or(1.0f);
        t.offset = optionalScalar(ctx, e, "Offset").value_or(0.0f);
        for (auto [child, value] : {std::pair{"BlackColor", "0 0 0"}, std::pair{"WhiteColor", "1 1 1"},
                 std::pair{"Scale", "1"}, std::pair{"Offset", "0"}})
            if (!e.child(child)) ctx.note(label(e) + ": no " + child + " (" + value + " assumed)");
        if (degamma(ctx, e)) {
            t.black = glm::pow(t.black, glm::vec3(2.2f));
            t.white = glm::pow(t.white, glm::vec3(2.2f));
        }
    } else if (type == "perlin") {
        t.type = Texture::Type::Perlin;
        t.scale = positive(ctx, e, "NoiseScale", 1.0f);
        const std::string conversion = lowercase(textOf(e.child("NoiseConversion")));
        if (conversion.find("absval") != std::string::npos)
            t.perlinAbs = true;
        else if (!conversion.empty() && conversion.find("linear") == std::string::npos)
            ctx.fail(e.child("NoiseConversion"), "is not absval or linear");
        if (!e.child("NoiseConversion")) ctx.note(label(e) + ": no NoiseConversion (linear assumed)");
    } else {
        ctx.fail(e, "unknown TextureMap type " + quote(e.attribute("type").value()));
    }
    out.textures.push_back(t);
    map.texture = static_cast<uint32_t>(out.textures.size() - 1);
    return *map.texture;
}

uint32_t TextureTable::apply(Context& ctx, pugi::xml_node objectTextures, uint32_t base, Scene& out) {
    if (!objectTextures) return base;
    std::vector<long long> ids;
    const std::string text = textOf(objectTextures);
    for (std::string_view token : tokens(text)) ids.push_back(toInteger(ctx, objectTextures, token));
    if (ids.empty()) return base;
    if (auto it = variants_.find({base, ids}); it != variants_.end()) return it->second;

    Material m = out.materials.at(base);
    for (long long id : ids) {
        auto it = maps_.find(id);
        if (it == maps_.end()) ctx.fail(objectTextures, "unknown TextureMap " + std::to_string(id));
        MapDefinition& map = it->second;
        const std::string& mode = map.decalMode;
        if (mode == "replace_background") continue; // the scene's, not the object's
        const uint32_t t = texture(ctx, map, out);
        if (mode == "replace_kd" || mode == "blend_kd") {
            m.baseColorTexture = t;
            m.blendBaseColor = mode == "blend_kd";
            if (!m.blendBaseColor) m.baseColor = m.classicDiffuse = glm::vec3(1.0f);
        } else if (mode == "replace_ks") {
            // Path tracing needs a specular lobe to texture; the classic shading always has one.
            if (m.type != MaterialType::Glossy && !m.classicPhong) {
                ctx.note("replace_ks on a material without a specular lobe (ignored)");
                continue;
            }
            m.specularTexture = t;
            m.specular = m.classicSpecular = glm::vec3(1.0f);
        } else if (mode == "replace_normal" || mode == "bump_normal") {
            m.normalTexture = t;
            m.bumpMap = mode == "bump_normal";
            m.normalMapYDown = true;
            m.normalScale = m.bumpMap ? optionalScalar(ctx, map.element, "BumpFactor").value_or(1.0f) : 1.0f;
            if (!std::isfinite(m.normalScale)) ctx.fail(map.element.child("BumpFactor"), "must be finite");
        } else if (mode == "replace_all") {
            m.baseColorTexture = t;
            m.baseColor = m.classicDiffuse = glm::vec3(1.0f);
            m.unlit = true;
        }
    }
    m.name += " textured";
    out.materials.push_back(m);
    const uint32_t index = static_cast<uint32_t>(out.materials.size() - 1);
    variants_.emplace(std::make_pair(base, ids), index);
    return index;
}

} // namespace pt::ceng795
