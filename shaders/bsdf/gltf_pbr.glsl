// The glTF 2.0 metallic-roughness material (glTF 2.0 specification, appendix B), with
// KHR_materials_ior, KHR_materials_specular and KHR_materials_transmission:
//   material   = mix(dielectric, metal, metallic)
//   metal      = GGX reflection, Fresnel = Schlick with F0 = baseColor
//   dielectric = GGX reflection with Fresnel Fs (from ior, scaled by the specular factors)
//                over a base: mix(mix(Lambert(baseColor), Lambertian transmission(dtColor), dt),
//                                 GGX transmission tinted by baseColor, transmission)
//   (dt: KHR_materials_diffuse_transmission's factor, dtColor its colour; the Lambertian
//   transmission goes to the other side without bending, as through a thin wall, weighted by the
//   base's share at both directions like the Lambertian reflection, so it is reciprocal on thin
//   walls and never gives more than arrives)
// Over it the layers of KHR_materials_clearcoat and KHR_materials_sheen (shaders/bsdf/pbr_layers.glsl),
// and in its Fresnel terms KHR_materials_iridescence's thin film (shaders/bsdf/thin_film.glsl).
// Lobes: coat and sheen (front side only), diffuse (Lambert), specular (the dielectric and metal reflections share D and G2, so
// they are one lobe with a blended Fresnel), transmission and diffuse transmission. Each is sampled with a
// probability from its estimated albedo at wo; eval and pdf are the sums over the lobes, so a
// sample's weight is f cos / pdf of the whole material and MIS sees one pdf. When alpha == 0
// the specular and transmission lobes are delta: eval and pdf leave them out, and sampling
// returns them with isDelta and their discrete probability as pdf.
//
// Choices the appendix leaves open, and why:
// - Fs is the exact dielectric Fresnel remapped so that Fs(normal incidence) = F0(ior) x
//   specularColorFactor and Fs -> 1 at grazing angles, times specularFactor. With the default
//   specular factors that is the exact Fresnel, so full transmission equals the rough
//   dielectric (shaders/bsdf/rough_dielectric.glsl), total internal reflection included.
// - The Lambertian base is scaled by (1 - max Fs(cos theta_o)) (1 - max Fs(cos theta_i)) instead
//   of the appendix's 1 - F(V.H): the V.H form reflects up to ~1.9x the incident energy at
//   grazing angles on smooth surfaces, the product form stays below 1 and is reciprocal.
// - Transmission through a thin wall (MATERIAL_FLAG_THIN_WALLED: no KHR_materials_volume) does
//   not bend: wi is the microfacet reflection mirrored through the surface plane, so roughness
//   still spreads it. With a volume it refracts with ior (shaders/bsdf/rough_dielectric.glsl's
//   geometry). From inside a volume (wo.z < 0) the lobes are the same, mirrored, with 1 / ior.
// Local frame: opaque materials (transmission 0) have z on the side of wo, like every surface
// BSDF; transmissive ones have z on the front (outside) side and wo.z < 0 inside.
#ifndef PT_BSDF_GLTF_PBR_GLSL
#define PT_BSDF_GLTF_PBR_GLSL
#include "bsdf/ggx.glsl"
#include "bsdf/fresnel.glsl"
#include "bsdf/lambert.glsl"
#include "bsdf/rough_dielectric.glsl"
#include "bsdf/bsdf_sample.glsl"
#include "bsdf/pbr_layers.glsl"
#include "bsdf/thin_film.glsl"

// Lower bounds on the lobe-selection estimates, so a lobe that can be non-zero somewhere is
// never given probability 0 by an estimate made at wo only: the base share can be 0 at wo
// (total internal reflection at the macro normal) while tilted facets still transmit, and
// Schlick's F of a black metal vanishes at normal incidence but not at tilted facets.
const float PBR_MIN_BASE_SHARE = 0.1;
const float PBR_MIN_SPECULAR_ESTIMATE = 0.02;

float average(vec3 c) { return (c.x + c.y + c.z) * (1.0 / 3.0); }
bool pbrThin(GpuMaterial m) { return (m.flags & MATERIAL_FLAG_THIN_WALLED) != 0u; }
// The specular lobes' GGX alpha along the local x and y axes. KHR_materials_anisotropy raises it
// along x, which the caller has turned to the anisotropy direction (alignAnisotropy), to
// mix(alpha, 1, strength^2); both stay at least MIN_ROUGH_ALPHA there, so a smooth material made
// anisotropic becomes a rough one.
vec2 pbrAlpha(GpuMaterial m) {
    if (!HAS_ANISOTROPY || m.anisotropy <= 0.0) return vec2(m.alpha);
    return max(vec2(mix(m.alpha, 1.0, m.anisotropy * m.anisotropy), m.alpha), vec2(MIN_ROUGH_ALPHA));
}
bool pbrSmooth(GpuMaterial m) { return pbrAlpha(m).x <= 0.0; }

// What a glTF material needs of the local frame the integrator builds at a hit: its x axis along
// the anisotropy direction (in the tangent plane of the frame's normal), and the coat's normal in
// it. Every other material leaves both alone.
void orientMaterialFrame(inout Frame frame, inout GpuMaterial m) {
    if (HAS_ANISOTROPY && m.anisotropy > 0.0) {
        vec3 t = m.anisotropyDirection - frame.n * dot(frame.n, m.anisotropyDirection);
        float len2 = dot(t, t);
        if (len2 > 0.0 && !isinf(len2)) {
            frame.t = t * inversesqrt(len2);
            frame.b = cross(frame.n, frame.t);
        }
    }
    orientClearcoat(m, frame);
}

// KHR_materials_iridescence's film (shaders/bsdf/thin_film.glsl) over a base of reflectance f0
// at normal incidence, mixed into the base's Fresnel F by the iridescence weight. The film sees
// air, or the coat's index 1.5 under a clearcoat. A film thinner than 30 nm fades out (smoothly,
// to exactly the base's Fresnel at 0 nm, where the Schlick interfaces of the film model would
// still reflect). Not from inside a volume (eta < 1), where the exact Fresnel's total internal
// reflection is kept.
vec3 pbrIridescent(GpuMaterial m, vec3 F, vec3 f0, float cosI, float eta) {
    float weight = m.iridescence * smoothstep(0.0, 30.0, m.iridescenceThickness);
    if (!HAS_IRIDESCENCE || weight <= 0.0 || eta < 1.0) return F;
    float outside = pbrHasCoat(m) ? 1.5 : 1.0;
    vec3 film = thinFilmFresnel(outside, m.iridescenceIor, m.iridescenceThickness, f0, cosI);
    return mix(F, film, weight);
}

// Fresnel reflectance of the dielectric layer (see the header): exact, remapped to the
// KHR_materials_specular F0 and scaled by its factor; iridescent where there is a film.
vec3 pbrDielectricFresnel(GpuMaterial m, float cosI, float eta) {
    float cosT;
    float F = fresnelDielectric(clamp(cosI, 0.0, 1.0), eta, cosT);
    float r0 = (eta - 1.0) / (eta + 1.0);
    float F0 = r0 * r0;
    vec3 f0 = min(F0 * m.specular, vec3(1.0));
    float t = F0 < 1.0 ? clamp((F - F0) / (1.0 - F0), 0.0, 1.0) : 1.0;
    return m.specularWeight * pbrIridescent(m, f0 + (1.0 - f0) * t, f0, cosI, eta);
}

// The metal's Fresnel: Schlick's with F0 = base colour, iridescent where there is a film.
vec3 pbrMetalFresnel(GpuMaterial m, float cosI) {
    return pbrIridescent(m, fresnelSchlick(m.baseColor, cosI), m.baseColor, cosI, 1.0);
}

// The blended Fresnel of the specular (reflection) lobe at a facet.
vec3 pbrSpecularFresnel(GpuMaterial m, float cosI, float eta) {
    return (1.0 - m.metallic) * pbrDielectricFresnel(m, cosI, eta) + m.metallic * pbrMetalFresnel(m, cosI);
}

// The share of light the dielectric layer passes to the base at a facet.
float pbrBaseShare(GpuMaterial m, float cosI, float eta) {
    return 1.0 - maxComponent(pbrDielectricFresnel(m, cosI, eta));
}

// n_t / n_i seen from wo (1 / ior from inside a volume; a thin wall has air on both sides),
// and both directions moved to the z > 0 side of wo.
float pbrSide(GpuMaterial m, inout vec3 wo, inout vec3 wi) {
    float eta = m.ior;
    if (wo.z < 0.0) {
        wo.z = -wo.z;
        wi.z = -wi.z;
        if (!pbrThin(m)) eta = 1.0 / m.ior;
    }
    return eta;
}

struct PbrLobeProbabilities {
    float coat; // the layers (shaders/bsdf/pbr_layers.glsl), front side only
    float sheen;
    float specular;
    float transmission;
    float diffuse;
    float diffuseTransmission;
};

// KHR_materials_diffuse_transmission's factor (0 where the kernel has no such material).
float pbrDiffuseTransmission(GpuMaterial m) { return HAS_DIFFUSE_TRANSMISSION ? m.diffuseTransmission : 0.0; }

// Lobe probabilities from the albedo each lobe would have at wo (wo.z > 0); `front`: wo is on
// the side of the layers (not inside a volume or behind a thin wall).
PbrLobeProbabilities pbrLobeProbabilities(GpuMaterial m, vec3 wo, float eta, bool front) {
    PbrLobeProbabilities p;
    float dielectric = 1.0 - m.metallic;
    float specular =
        dielectric * average(pbrDielectricFresnel(m, wo.z, eta)) + m.metallic * average(pbrMetalFresnel(m, wo.z));
    float specularMass = dielectric * m.specularWeight + m.metallic;
    specular = max(specular, PBR_MIN_SPECULAR_ESTIMATE * specularMass);
    float share = dielectric * max(pbrBaseShare(m, wo.z, eta), PBR_MIN_BASE_SHARE);
    float base = share * average(m.baseColor);
    float dt = pbrDiffuseTransmission(m);
    float transmission = base * m.transmission;
    float diffuse = base * (1.0 - m.transmission) * (1.0 - dt);
    float diffuseTransmission = share * (1.0 - m.transmission) * dt * average(m.diffuseTransmissionColor);
    PbrLayerWeights layers = pbrLayerWeights(m, front ? wo : vec3(0.0));
    float baseTotal = specular + transmission + diffuse + diffuseTransmission;
    // The base's lobes share what the layers leave (all of it without layers).
    float scale = baseTotal > 0.0 ? layers.base / baseTotal : 0.0;
    float total = layers.coat + layers.sheen + (baseTotal > 0.0 ? layers.base : 0.0);
    float inv = total > 0.0 ? 1.0 / total : 0.0;
    p.coat = layers.coat * inv;
    p.sheen = layers.sheen * inv;
    p.specular = specular * scale * inv;
    p.transmission = transmission * scale * inv;
    p.diffuse = diffuse * scale * inv;
    p.diffuseTransmission = diffuseTransmission * scale * inv;
    return p;
}

// The thin-wall transmitted direction's reflection partner: wi mirrored through the surface.
vec3 mirrorThroughSurface(vec3 w) { return vec3(w.xy, -w.z); }

// f * |cos(theta_i)| of the non-delta lobes; wo.z > 0, eta from pbrSide.
vec3 pbrEvalUpper(GpuMaterial m, vec3 wo, vec3 wi, float eta) {
    float dielectric = 1.0 - m.metallic;
    float dt = pbrDiffuseTransmission(m);
    if (wi.z > 0.0) {
        vec3 f = dielectric * (1.0 - m.transmission) * (1.0 - dt) * m.baseColor * (INV_PI * wi.z) *
                 pbrBaseShare(m, wo.z, eta) * pbrBaseShare(m, wi.z, eta);
        if (!pbrSmooth(m)) {
            vec3 wm = normalize(wo + wi);
            f += pbrSpecularFresnel(m, dot(wo, wm), eta) *
                 (ggxD(wm, pbrAlpha(m)) * ggxG2OverCosO(wo, wi, pbrAlpha(m)) * 0.25);
        }
        return f;
    }
    vec3 f = vec3(0.0);
    if (dt > 0.0)
        f = dielectric * (1.0 - m.transmission) * dt * m.diffuseTransmissionColor * (INV_PI * -wi.z) *
            pbrBaseShare(m, wo.z, eta) * pbrBaseShare(m, -wi.z, eta);
    if (pbrSmooth(m) || m.transmission <= 0.0) return f;
    vec3 tint = dielectric * m.transmission * m.baseColor;
    if (pbrThin(m)) {
        vec3 wr = mirrorThroughSurface(wi);
        vec3 wm = normalize(wo + wr);
        return f + tint * pbrBaseShare(m, dot(wo, wm), eta) *
                       (ggxD(wm, pbrAlpha(m)) * ggxG2OverCosO(wo, wr, pbrAlpha(m)) * 0.25);
    }
    vec3 wm;
    if (!refractionHalfVector(wo, wi, eta, wm)) return f;
    return f + tint * pbrBaseShare(m, dot(wo, wm), eta) * ggxTransmissionNoFresnel(wo, wi, wm, eta, pbrAlpha(m));
}

// The pdf over the base's non-delta lobes and the layers' (wo.z > 0, eta from pbrSide; `front`:
// wo and wi are as the caller gave them, not mirrored from inside).
float pbrPdfUpper(GpuMaterial m, vec3 wo, vec3 wi, float eta, bool front) {
    PbrLobeProbabilities p = pbrLobeProbabilities(m, wo, eta, front);
    if (wi.z > 0.0) {
        float pdf = p.diffuse * lambertPdf(wo, wi);
        if (!pbrSmooth(m)) pdf += p.specular * ggxReflectionPdf(wo, wi, pbrAlpha(m));
        if (p.coat > 0.0) pdf += p.coat * coatPdf(m, wo, wi);
        if (p.sheen > 0.0) pdf += p.sheen * uniformHemispherePdf(wi.z);
        return pdf;
    }
    float pdf = p.diffuseTransmission > 0.0 ? p.diffuseTransmission * lambertPdf(wo, mirrorThroughSurface(wi)) : 0.0;
    if (pbrSmooth(m) || p.transmission <= 0.0) return pdf;
    if (pbrThin(m)) return pdf + p.transmission * ggxReflectionPdf(wo, mirrorThroughSurface(wi), pbrAlpha(m));
    vec3 wm;
    if (!refractionHalfVector(wo, wi, eta, wm)) return pdf;
    return pdf + p.transmission * ggxVisibleNormalPdf(wo, wm, pbrAlpha(m)) * refractionJacobian(wo, wi, wm, eta);
}

vec3 pbrEval(GpuMaterial m, vec3 wo, vec3 wi) {
    if (wo.z == 0.0 || wi.z == 0.0) return vec3(0.0);
    vec3 woSide = wo, wiSide = wi;
    float eta = pbrSide(m, woSide, wiSide);
    vec3 f = pbrEvalUpper(m, woSide, wiSide, eta);
    if (pbrLayered(m)) f = f * pbrBaseScale(m, wo, wi) + pbrLayerEval(m, wo, wi);
    return f;
}

float pbrPdf(GpuMaterial m, vec3 wo, vec3 wi) {
    if (wo.z == 0.0 || wi.z == 0.0) return 0.0;
    bool front = wo.z > 0.0;
    float eta = pbrSide(m, wo, wi);
    return pbrPdfUpper(m, wo, wi, eta, front);
}

// A delta sample's direction and weight: `weight` is the lobe's f cos over its probability
// before the layers, which scale it by what they let through both ways.
BsdfSample pbrDeltaSample(GpuMaterial m, Frame frame, vec3 wo, vec3 wi, vec3 weight, float p, float etaScale) {
    BsdfSample s = invalidBsdfSample();
    s.wi = normalize(toWorld(frame, wi));
    s.weight = pbrLayered(m) ? weight * pbrBaseScale(m, wo, wi) : weight;
    s.pdf = p;
    s.etaScale = etaScale;
    s.isDelta = true;
    s.valid = true;
    return s;
}

BsdfSample pbrSample(GpuMaterial m, Frame frame, vec3 wo, float uLobe, vec2 u) {
    BsdfSample s = invalidBsdfSample();
    if (wo.z == 0.0) return s;
    bool front = wo.z > 0.0;
    float side = front ? 1.0 : -1.0;
    vec3 woUp = wo, unused = vec3(0.0);
    float eta = pbrSide(m, woUp, unused);
    PbrLobeProbabilities p = pbrLobeProbabilities(m, woUp, eta, front);
    vec3 wi;
    if (uLobe < p.coat) {
        BsdfSample c = coatSample(m, wo, p.coat, u);
        if (!c.valid || c.isDelta) {
            if (c.valid) c.wi = normalize(toWorld(frame, c.wi));
            return c;
        }
        wi = c.wi;
    } else if (uLobe < p.coat + p.sheen) {
        wi = sampleUniformHemisphere(u);
    } else {
        uLobe -= p.coat + p.sheen;
        if (uLobe < p.specular) {
            if (pbrSmooth(m)) {
                vec3 mirror = vec3(-woUp.xy, woUp.z);
                vec3 weight = pbrSpecularFresnel(m, woUp.z, eta) / p.specular;
                return pbrDeltaSample(m, frame, wo, mirror * vec3(1.0, 1.0, side), weight, p.specular, 1.0);
            }
            wi = reflectAbout(woUp, ggxSampleVisibleNormal(woUp, pbrAlpha(m), u));
            if (wi.z <= 0.0) return s;
        } else if (uLobe < p.specular + p.transmission) {
            bool thin = pbrThin(m);
            vec3 tint = (1.0 - m.metallic) * m.transmission * m.baseColor;
            if (pbrSmooth(m)) {
                float cosT;
                float share = pbrBaseShare(m, woUp.z, eta);
                if (thin) return pbrDeltaSample(m, frame, wo, -wo, tint * share / p.transmission, p.transmission, 1.0);
                fresnelDielectric(woUp.z, eta, cosT);
                if (cosT <= 0.0) return s; // total internal reflection: nothing refracts
                wi = vec3(-woUp.xy / eta, -cosT);
                wi.z *= side;
                return pbrDeltaSample(
                    m, frame, wo, wi, tint * share / (eta * eta * p.transmission), p.transmission, eta * eta);
            }
            vec3 wm = ggxSampleVisibleNormal(woUp, pbrAlpha(m), u);
            if (thin) {
                wi = mirrorThroughSurface(reflectAbout(woUp, wm));
                if (wi.z >= 0.0) return s;
            } else {
                if (!refractAbout(woUp, wm, eta, wi) || wi.z >= 0.0) return s;
                s.etaScale = eta * eta;
            }
        } else {
            // The Lambertian lobes: reflection, or the same direction mirrored to the other side.
            BsdfSample d = lambertSample(vec3(1.0), makeFrame(vec3(0.0, 0.0, 1.0)), woUp, u);
            if (!d.valid) return s;
            wi = uLobe < p.specular + p.transmission + p.diffuse ? d.wi : mirrorThroughSurface(d.wi);
        }
        wi.z *= side;
    }
    // Non-delta: the whole material's f cos over its pdf, so MIS sees one pdf. (Coat and sheen
    // directions are front-side ones, as given.)
    vec3 woSide = wo, wiSide = wi;
    pbrSide(m, woSide, wiSide);
    s.pdf = pbrPdfUpper(m, woSide, wiSide, eta, front);
    if (!(s.pdf > 0.0)) return invalidBsdfSample();
    vec3 f = pbrEvalUpper(m, woSide, wiSide, eta);
    if (pbrLayered(m)) f = f * pbrBaseScale(m, wo, wi) + pbrLayerEval(m, wo, wi);
    s.weight = f / s.pdf;
    s.wi = toWorld(frame, wi);
    s.valid = true;
    return s;
}

#endif
