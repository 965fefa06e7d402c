// The layers over the glTF metallic-roughness base (shaders/bsdf/gltf_pbr.glsl), in the order
// the extensions stack them: KHR_materials_clearcoat over KHR_materials_sheen over the base.
//   f = f_coat + Tc(wo) Tc(wi) (sheenColor f_sheen + S(wo, wi) f_base)
// - The coat: GGX reflection about the coat's own normal nc (the surface's normal without the
//   base's normal map, or the coat's normal map), Schlick's Fresnel with F0 = 0.04 (ior 1.5),
//   weighted by clearcoatFactor; a delta mirror when its alpha is below MIN_ROUGH_ALPHA.
// - Tc(w) = 1 - clearcoat Fc(nc . w): the share of light that crosses the coat, on the way in
//   and on the way out. The extension's text scales the layers below by 1 - clearcoat Fc(n . v)
//   alone; counting both crossings keeps the BSDF reciprocal and is what a coat does to light
//   that enters and leaves it (the same choice as the base's own dielectric layer).
// - The sheen (shaders/bsdf/sheen.glsl) with the extension's albedo scaling
//   S = min(1 - max(sheenColor) E(wo), 1 - max(sheenColor) E(wi)), which is reciprocal.
// Both layers sit on the front side only: a direction on the back (transmission, or wo inside a
// volume) crosses neither, so Tc = 1 and 1 - max(sheenColor) E = 1 for it and S is their product.
// Since the coat's albedo at wo is at most about clearcoat Fc(wo) and the sheen's at most
// max(sheenColor) E(wo), every layer passes on at most what the layers above leave: the stack
// never reflects more than arrives (MicrofacetBsdf.WhiteFurnace... tests).
// Vectors here are in the BSDF's local frame as the caller has it (z the shading normal, on
// the side of wo for opaque materials, on the front for transmissive ones): "front" is z > 0.
#ifndef PT_BSDF_PBR_LAYERS_GLSL
#define PT_BSDF_PBR_LAYERS_GLSL
#include "bsdf/ggx.glsl"
#include "bsdf/fresnel.glsl"
#include "bsdf/sheen.glsl"
#include "shared/features.glsl"

const float CLEARCOAT_F0 = 0.04;

bool pbrHasCoat(GpuMaterial m) { return HAS_CLEARCOAT && m.clearcoat > 0.0; }
bool pbrHasSheen(GpuMaterial m) { return HAS_SHEEN && maxComponent(m.sheenColor) > 0.0; }
bool pbrLayered(GpuMaterial m) { return pbrHasCoat(m) || pbrHasSheen(m); }
bool pbrSmoothCoat(GpuMaterial m) { return m.clearcoatAlpha <= 0.0; }

float clearcoatFresnel(float cosTheta) { return fresnelSchlick(vec3(CLEARCOAT_F0), cosTheta).x; }

// Moves the coat's normal (world space, from applyTextures) into the BSDF's local frame, on the
// frame's side. The buffer's (0, 0, 0) -- no hit has set it, as in the test kernels -- is the
// frame's own normal.
void orientClearcoat(inout GpuMaterial m, Frame frame) {
    if (!HAS_CLEARCOAT) return;
    vec3 n = m.clearcoatNormal;
    if (!(dot(n, n) > 0.0)) {
        m.clearcoatNormal = vec3(0.0, 0.0, 1.0);
        return;
    }
    n = normalize(toLocal(frame, n));
    m.clearcoatNormal = n.z < 0.0 ? -n : n;
}

// A local direction in the coat's frame (z = nc).
vec3 toCoat(GpuMaterial m, vec3 w) { return toLocal(makeFrame(m.clearcoatNormal), w); }

// The share of light crossing the coat at w (1 on the back side, where there is no coat).
float coatTransmittance(GpuMaterial m, vec3 w) {
    if (!pbrHasCoat(m) || w.z <= 0.0) return 1.0;
    return 1.0 - m.clearcoat * clearcoatFresnel(dot(m.clearcoatNormal, w));
}

// 1 - max(sheenColor) E(w) (1 on the back side).
float sheenTransmittance(GpuMaterial m, vec3 w) {
    if (!pbrHasSheen(m) || w.z <= 0.0) return 1.0;
    return 1.0 - maxComponent(m.sheenColor) * sheenAlbedo(w.z, m.sheenRoughness);
}

// What the layers leave of the base's f between wo and wi.
float pbrBaseScale(GpuMaterial m, vec3 wo, vec3 wi) {
    float sheenO = sheenTransmittance(m, wo), sheenI = sheenTransmittance(m, wi);
    float sheen = wo.z > 0.0 && wi.z > 0.0 ? min(sheenO, sheenI) : sheenO * sheenI;
    return coatTransmittance(m, wo) * coatTransmittance(m, wi) * sheen;
}

// f cos of the rough coat alone; zero unless wo and wi are both above the coat.
vec3 coatEval(GpuMaterial m, vec3 wo, vec3 wi) {
    if (!pbrHasCoat(m) || pbrSmoothCoat(m)) return vec3(0.0);
    vec3 o = toCoat(m, wo), i = toCoat(m, wi);
    if (o.z <= 0.0 || i.z <= 0.0) return vec3(0.0);
    vec3 wm = normalize(o + i);
    float f = m.clearcoat * clearcoatFresnel(dot(o, wm)) * ggxD(wm, m.clearcoatAlpha) *
              ggxG2OverCosO(o, i, m.clearcoatAlpha) * 0.25;
    return vec3(f);
}

float coatPdf(GpuMaterial m, vec3 wo, vec3 wi) {
    if (!pbrHasCoat(m) || pbrSmoothCoat(m)) return 0.0;
    return ggxReflectionPdf(toCoat(m, wo), toCoat(m, wi), m.clearcoatAlpha);
}

// f cos of the layers' own lobes (the coat, and the sheen under it), front side only.
vec3 pbrLayerEval(GpuMaterial m, vec3 wo, vec3 wi) {
    if (wo.z <= 0.0 || wi.z <= 0.0) return vec3(0.0);
    vec3 f = coatEval(m, wo, wi);
    if (pbrHasSheen(m))
        f += coatTransmittance(m, wo) * coatTransmittance(m, wi) * m.sheenColor * sheenEval(wo, wi, m.sheenRoughness);
    return f;
}

// Lobe-selection weights at wo (front side): the coat's and the sheen's estimated albedos, and
// what they leave to the base (the base's own estimate is multiplied by it).
struct PbrLayerWeights {
    float coat;
    float sheen;
    float base;
};

PbrLayerWeights pbrLayerWeights(GpuMaterial m, vec3 wo) {
    PbrLayerWeights w;
    w.coat = 0.0;
    w.sheen = 0.0;
    w.base = 1.0;
    if (wo.z <= 0.0 || !pbrLayered(m)) return w;
    float coatT = coatTransmittance(m, wo);
    if (pbrHasCoat(m)) w.coat = m.clearcoat * clearcoatFresnel(dot(m.clearcoatNormal, wo));
    if (pbrHasSheen(m))
        w.sheen = coatT * (m.sheenColor.x + m.sheenColor.y + m.sheenColor.z) * (1.0 / 3.0) *
                  sheenAlbedo(wo.z, m.sheenRoughness);
    w.base = coatT * sheenTransmittance(m, wo);
    return w;
}

// A direction from the coat lobe (rough: from its visible normals; smooth: the mirror direction,
// returned with isDelta and the lobe's probability `p` as pdf). Rough samples carry only wi: the
// caller evaluates the whole material for their weight and pdf.
BsdfSample coatSample(GpuMaterial m, vec3 wo, float p, vec2 u) {
    BsdfSample s = invalidBsdfSample();
    vec3 o = toCoat(m, wo);
    if (o.z <= 0.0) return s;
    Frame coat = makeFrame(m.clearcoatNormal);
    if (pbrSmoothCoat(m)) {
        vec3 wi = toWorld(coat, vec3(-o.xy, o.z));
        if (wi.z <= 0.0) return s;
        s.wi = wi;
        s.weight = vec3(m.clearcoat * clearcoatFresnel(o.z) / p);
        s.pdf = p;
        s.isDelta = true;
        s.valid = true;
        return s;
    }
    vec3 wi = toWorld(coat, reflectAbout(o, ggxSampleVisibleNormal(o, m.clearcoatAlpha, u)));
    if (wi.z <= 0.0 || dot(wi, m.clearcoatNormal) <= 0.0) return s;
    s.wi = wi;
    s.valid = true;
    return s;
}

#endif
