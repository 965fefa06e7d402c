#include "scene/ceng795/materials.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pt::ceng795 {
namespace {

using Notes = std::vector<std::string>;

bool anyPositive(const glm::vec3& c) { return c.x > 0.0f || c.y > 0.0f || c.z > 0.0f; }

// Reads material colours, undoing the sRGB-ish encoding when the material says degamma="true".
class ColourReader {
public:
    ColourReader(const Context& ctx, pugi::xml_node material, bool degamma)
        : ctx_(ctx), material_(material), degamma_(degamma) {}

    glm::vec3 operator()(const char* child, const glm::vec3& fallback) const {
        pugi::xml_node n = material_.child(child);
        if (!n) return fallback;
        glm::vec3 c = vec3(ctx_, n);
        if (c.x < 0.0f || c.y < 0.0f || c.z < 0.0f) ctx_.fail(n, "must not be negative");
        return degamma_ ? glm::pow(c, glm::vec3(2.2f)) : c;
    }

    glm::vec3 required(const char* child) const {
        ceng795::required(ctx_, material_, child);
        return (*this)(child, glm::vec3(0.0f));
    }

private:
    const Context& ctx_;
    pugi::xml_node material_;
    bool degamma_;
};

// Reflectances above 1 would make the path tracer gain energy; the course's classic shading
// did not care. Clamp, and say so.
glm::vec3 reflectance(Notes& notes, const glm::vec3& c) {
    if (c.x > 1.0f || c.y > 1.0f || c.z > 1.0f) notes.push_back("reflectances above 1 (clamped)");
    return glm::min(c, glm::vec3(1.0f));
}

float positiveScalar(const Context& ctx, pugi::xml_node material, const char* child) {
    pugi::xml_node n = required(ctx, material, child);
    const float v = scalar(ctx, n);
    if (!(v > 0.0f)) ctx.fail(n, "must be positive");
    return v;
}

// The Blinn-Phong exponent; 1 when the file has none, which it says when the material has a
// specular term for the exponent to shape (`used`).
float phongExponent(const Context& ctx, Notes& notes, pugi::xml_node material, bool used) {
    if (const auto p = optionalScalar(ctx, material, "PhongExponent")) return *p;
    if (used) notes.push_back(label(material) + ": no PhongExponent for its SpecularReflectance (1 assumed)");
    return 1.0f;
}

// The conductor's (or Torrance-Sparrow Fresnel's) k; 0, a dielectric's Fresnel, when absent.
float absorptionIndex(const Context& ctx, Notes& notes, pugi::xml_node material) {
    pugi::xml_node n = material.child("AbsorptionIndex");
    if (!n) {
        notes.push_back(label(material) + ": no AbsorptionIndex (0 assumed)");
        return 0.0f;
    }
    const float k = scalar(ctx, n);
    if (k < 0.0f) ctx.fail(n, "must not be negative");
    return k;
}

// A course BRDF model by its element name.
GlossyModel glossyModel(const Context& ctx, pugi::xml_node brdf) {
    const std::string name = brdf.name();
    if (name == "OriginalPhong") return GlossyModel::OriginalPhong;
    if (name == "OriginalBlinnPhong") return GlossyModel::OriginalBlinnPhong;
    if (name == "ModifiedPhong") return GlossyModel::ModifiedPhong;
    if (name == "ModifiedBlinnPhong") return GlossyModel::ModifiedBlinnPhong;
    if (name == "TorranceSparrow") return GlossyModel::TorranceSparrow;
    ctx.fail(brdf, "unknown BRDF model");
}

// Default materials: Lambertian, plus the specular lobe of their BRDF (or, without one, the
// course's default Blinn-Phong with PhongExponent) when SpecularReflectance is not black.
void convertDiffuse(const Context& ctx, Notes& notes, pugi::xml_node e, const ColourReader& colour,
    const std::optional<pugi::xml_node>& brdf, Material& m) {
    m.type = MaterialType::Diffuse;
    m.baseColor = reflectance(notes, colour("DiffuseReflectance", glm::vec3(0.0f)));
    const glm::vec3 ks = colour("SpecularReflectance", glm::vec3(0.0f));
    if (!anyPositive(ks)) return;
    m.type = MaterialType::Glossy;
    m.specular = reflectance(notes, ks);
    if (brdf) {
        m.glossyModel = glossyModel(ctx, *brdf);
        m.exponent = positiveScalar(ctx, *brdf, "Exponent");
        m.normalized = brdf->attribute("normalized") &&
                       booleanValue(ctx, *brdf, brdf->attribute("normalized").value(), "normalized");
        m.kdFresnel =
            brdf->attribute("kdfresnel") && booleanValue(ctx, *brdf, brdf->attribute("kdfresnel").value(), "kdfresnel");
        if (m.glossyModel == GlossyModel::TorranceSparrow) {
            m.conductorEta = glm::vec3(positiveScalar(ctx, e, "RefractionIndex"));
            m.conductorK = glm::vec3(absorptionIndex(ctx, notes, e));
        }
    } else {
        m.glossyModel = GlossyModel::OriginalBlinnPhong; // the course's shading before HW6
        m.exponent = phongExponent(ctx, notes, e, true);
        if (!(m.exponent > 0.0f)) ctx.fail(e.child("PhongExponent"), "must be positive");
    }
}

// The course adds its Blinn-Phong/BRDF diffuse and specular terms to mirrors, conductors and
// dielectrics too; the renderer's specular materials have no such layers.
void noteExtraLayers(Notes& notes, const ColourReader& colour, const std::string& type) {
    if (anyPositive(colour("DiffuseReflectance", glm::vec3(0.0f)))) notes.push_back(type + " with diffuse layer");
    if (anyPositive(colour("SpecularReflectance", glm::vec3(0.0f))))
        notes.push_back(type + " with specular highlights (ignored)");
}

// A mirror with diffuse or specular layers is the course's sum of its BRDF and the mirror: a
// glossy material with a mirror lobe (shaders/bsdf/glossy.glsl).
void convertMirror(const Context& ctx, Notes& notes, pugi::xml_node e, const ColourReader& colour,
    const std::optional<pugi::xml_node>& brdf, Material& m) {
    const glm::vec3 km = reflectance(notes, colour.required("MirrorReflectance"));
    if (anyPositive(colour("DiffuseReflectance", glm::vec3(0.0f))) ||
        anyPositive(colour("SpecularReflectance", glm::vec3(0.0f)))) {
        convertDiffuse(ctx, notes, e, colour, brdf, m);
        m.type = MaterialType::Glossy;
        m.mirrorReflectance = km;
        return;
    }
    m.type = MaterialType::Mirror;
    m.baseColor = km;
}

void convertDielectric(const Context& ctx, Notes& notes, pugi::xml_node e, const ColourReader& colour, Material& m) {
    m.type = MaterialType::Dielectric;
    m.baseColor = glm::vec3(1.0f); // course glass is untinted; colour comes from absorption only
    m.ior = positiveScalar(ctx, e, "RefractionIndex");
    if (pugi::xml_node a = e.child("AbsorptionCoefficient")) {
        const glm::vec3 sigma = vec3(ctx, a);
        if (sigma.x < 0.0f || sigma.y < 0.0f || sigma.z < 0.0f) ctx.fail(a, "must not be negative");
        // Beer's law L(x) = L(0) e^{-sigma x}: the transmittance after one unit of distance.
        if (anyPositive(sigma)) {
            m.attenuationDistance = 1.0f;
            m.attenuationColor = glm::exp(-sigma);
        }
    }
    noteExtraLayers(notes, colour, "dielectric");
}

void convertConductor(const Context& ctx, Notes& notes, pugi::xml_node e, const ColourReader& colour, Material& m) {
    m.type = MaterialType::Conductor;
    m.baseColor = reflectance(notes, colour.required("MirrorReflectance"));
    m.conductorEta = glm::vec3(positiveScalar(ctx, e, "RefractionIndex"));
    m.conductorK = glm::vec3(absorptionIndex(ctx, notes, e));
    noteExtraLayers(notes, colour, "conductor");
}

// The course's Roughness r perturbs the ideal reflected or refracted direction by
// r (xi - 0.5) along each of two axes orthogonal to it (docs/ceng795-format.md, material `Roughness`). We
// render it as GGX with the same spread: that recipe puts the reflected direction's tangent
// offsets uniformly in a square of side r, the microfacet normal's (half the deflection) in a
// square of side r / 2, whose median radial slope is 0.2 r (sqrt(2 / pi) r / 4); a GGX normal's
// median slope is alpha. So alpha = r / 5 (capped at 1), i.e. perceptual roughness sqrt(r / 5).
// Mirrors have no Fresnel in the course: a rough one is a conductor of reflectance 1 at every
// angle (eta = k = 0) tinted by MirrorReflectance.
constexpr float kCourseRoughnessToAlpha = 0.2f;

void makeRough(Material& m, float courseRoughness) {
    const float alpha = std::min(1.0f, kCourseRoughnessToAlpha * courseRoughness);
    m.roughness = std::sqrt(alpha);
    if (m.type == MaterialType::Mirror) {
        m.type = MaterialType::Conductor;
        m.conductorEta = glm::vec3(0.0f);
        m.conductorK = glm::vec3(0.0f);
    }
}

// The terms the course's classic ray tracer adds on every surface (the CLASSIC kernel feature), kept as the
// file gives them: ka, and, unless a BRDF replaces it, Blinn-Phong kd cos + ks cos^p(alpha_h)
// (kd without 1/pi, and on mirrors, conductors and dielectrics too).
void readClassicShading(const Context& ctx, Notes& notes, pugi::xml_node e, const ColourReader& colour,
    const std::optional<pugi::xml_node>& brdf, Material& m) {
    m.ambient = colour("AmbientReflectance", glm::vec3(0.0f));
    // A normalised BRDF (and Torrance-Sparrow) shades as in path tracing, kd / pi included,
    // also when its specular part is black and the material became plain Lambertian; the
    // official direct-lighting images agree with that to 0.02% in flux.
    if (brdf) {
        const std::string name = brdf->name();
        const bool normalised = name == "TorranceSparrow" ||
                                (brdf->attribute("normalized") &&
                                    booleanValue(ctx, *brdf, brdf->attribute("normalized").value(), "normalized"));
        if (normalised || m.type == MaterialType::Glossy)
            return; // glossy.glsl (classic.glsl undoes 1/pi if unnormalised)
    }
    m.classicPhong = true;
    m.classicDiffuse = colour("DiffuseReflectance", glm::vec3(0.0f));
    m.classicSpecular = colour("SpecularReflectance", glm::vec3(0.0f));
    m.classicExponent = phongExponent(ctx, notes, e, anyPositive(m.classicSpecular));
    // 0 is allowed (course files use it with black ks): the lobe is then constant.
    if (!(m.classicExponent >= 0.0f)) ctx.fail(e.child("PhongExponent"), "must not be negative");
}

std::map<long long, pugi::xml_node> readBrdfs(const Context& ctx, pugi::xml_node scene) {
    std::map<long long, pugi::xml_node> brdfs;
    for (pugi::xml_node list : scene.children("BRDFs"))
        for (pugi::xml_node b : list.children()) {
            if (b.type() != pugi::node_element) continue;
            if (!brdfs.emplace(idOf(ctx, b), b).second) ctx.fail(b, "duplicate id");
        }
    return brdfs;
}

} // namespace

Material convertMaterial(
    const Context& ctx, pugi::xml_node e, const std::map<long long, pugi::xml_node>& brdfs, Notes& notes) {
    Material m;
    m.name = "material " + idText(e, "?");
    const bool degamma = e.attribute("degamma") && booleanValue(ctx, e, e.attribute("degamma").value(), "degamma");
    const ColourReader colour(ctx, e, degamma);
    std::optional<pugi::xml_node> brdfElement;
    if (pugi::xml_attribute brdf = e.attribute("BRDF")) {
        const std::vector<std::string_view> t = tokens(brdf.value());
        if (t.size() != 1 || !brdfs.count(toInteger(ctx, e, t[0]))) ctx.fail(e, "unknown BRDF " + quote(brdf.value()));
        brdfElement = brdfs.at(toInteger(ctx, e, t[0]));
    }
    const std::string type = lowercase(e.attribute("type").value());
    if (type == "mirror")
        convertMirror(ctx, notes, e, colour, brdfElement, m);
    else if (type == "dielectric")
        convertDielectric(ctx, notes, e, colour, m);
    else if (type == "conductor")
        convertConductor(ctx, notes, e, colour, m);
    else {
        if (!type.empty()) notes.push_back("material type " + quote(type) + " (rendered diffuse)");
        convertDiffuse(ctx, notes, e, colour, brdfElement, m);
    }
    readClassicShading(ctx, notes, e, colour, brdfElement, m);
    if (const auto r = optionalScalar(ctx, e, "Roughness"); r && *r != 0.0f) {
        if (!(*r > 0.0f)) ctx.fail(e.child("Roughness"), "must not be negative");
        if (m.type == MaterialType::Mirror || m.type == MaterialType::Conductor || m.type == MaterialType::Dielectric)
            makeRough(m, *r);
        else if (anyPositive(m.mirrorReflectance))
            notes.push_back("Roughness on mirrors with diffuse or specular layers (their mirror stays smooth)");
        else
            notes.push_back("Roughness on diffuse and BRDF materials (ignored)");
    }
    return m;
}

MaterialTable MaterialTable::read(const Context& ctx, pugi::xml_node scene, std::vector<Material>& out) {
    const std::map<long long, pugi::xml_node> brdfs = readBrdfs(ctx, scene);
    MaterialTable table;
    for (pugi::xml_node list : scene.children("Materials"))
        for (pugi::xml_node e : list.children("Material")) {
            const long long id = idOf(ctx, e);
            if (!table.indexById_.emplace(id, static_cast<uint32_t>(out.size())).second) ctx.fail(e, "duplicate id");
            table.notes_.emplace_back();
            out.push_back(convertMaterial(ctx, e, brdfs, table.notes_.back()));
        }
    table.used_.assign(out.size(), false);
    return table;
}

uint32_t MaterialTable::lookup(const Context& ctx, pugi::xml_node reference) {
    const long long id =
        integer(ctx, reference, std::numeric_limits<long long>::min(), std::numeric_limits<long long>::max());
    auto it = indexById_.find(id);
    if (it == indexById_.end()) ctx.fail(reference, "unknown material " + std::to_string(id));
    used_[it->second] = true;
    return it->second;
}

void MaterialTable::noteUsed(Context& ctx) const {
    for (size_t i = 0; i < notes_.size(); ++i)
        if (used_[i])
            for (const std::string& n : notes_[i]) ctx.note(n);
}

uint32_t addEmissiveCopy(
    std::vector<Material>& materials, uint32_t base, const glm::vec3& radiance, const std::string& name) {
    Material m = materials[base];
    m.name = name;
    m.emission = radiance;
    // Course NEE divides by |cos| at the light (docs/ceng795-format.md §7): object lights emit from both sides.
    m.doubleSided = true;
    materials.push_back(m);
    return static_cast<uint32_t>(materials.size() - 1);
}

} // namespace pt::ceng795
