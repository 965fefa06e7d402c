// A material's textures applied at a hit: colour slots scale (or, for the course's blend_kd,
// average with) the material's factors, and normal or bump maps tilt the shading normal. The
// BSDFs then see a plain GpuMaterial and know nothing about textures.
#ifndef PT_MATERIAL_MATERIAL_TEXTURES_GLSL
#define PT_MATERIAL_MATERIAL_TEXTURES_GLSL
#include "geometry/interaction.glsl"
#include "textures/texture.glsl"

bool hasAnyTexture(GpuMaterial m) {
    return (m.baseColorTexture & m.specularTexture & m.metallicRoughnessTexture & m.normalTexture & m.emissiveTexture &
               m.specularWeightTexture & m.transmissionTexture & m.diffuseTransmissionTexture &
               m.diffuseTransmissionColorTexture & m.clearcoatTexture & m.clearcoatRoughnessTexture &
               m.clearcoatNormalTexture & m.sheenColorTexture & m.sheenRoughnessTexture & m.iridescenceTexture &
               m.iridescenceThicknessTexture & m.anisotropyTexture) != NO_TEXTURE;
}

// Shading normal from a tangent-space normal map: +x along dp/du, +y up the image (towards
// decreasing v), as glTF and OpenGL-style maps store it, or, with `yDown`, along dp/dv as the
// course's maps are (their official images match only that way). Following dp/dv rather than
// a fixed handedness keeps mirrored uv layouts right, as generated tangents do.
// The tangent frame at a hit: t along dp/du in the shading normal's plane, b up the image (or
// along dp/dv with `yDown`). False where dp/du has no length there.
bool tangentFrame(SurfaceInteraction si, bool yDown, out vec3 t, out vec3 b) {
    vec3 n = si.ns;
    t = si.dpdu - n * dot(n, si.dpdu);
    b = vec3(0.0);
    float tLen2 = dot(t, t);
    if (!(tLen2 > 0.0) || isinf(tLen2)) return false;
    t *= inversesqrt(tLen2);
    // Bitangent up the image; mirrored uv layouts flip it with dp/dv, as generated tangents do.
    b = si.dpdv - n * dot(n, si.dpdv) - t * dot(t, si.dpdv);
    float bLen2 = dot(b, b);
    b = (bLen2 > 0.0 && !isinf(bLen2)) ? b * inversesqrt(bLen2) : cross(n, t);
    if (!yDown) b = -b;
    return true;
}

vec3 normalFromMap(SurfaceInteraction si, vec3 texel, float scale, bool yDown) {
    vec3 n = si.ns, t, b;
    if (!tangentFrame(si, yDown, t, b)) return n;
    vec3 m = texel * 2.0 - 1.0;
    m.xy *= scale;
    vec3 mapped = m.x * t + m.y * b + m.z * n;
    float len2 = dot(mapped, mapped);
    return (len2 > 0.0 && !isinf(len2)) ? mapped * inversesqrt(len2) : n;
}

float bumpHeight(GpuTexture tex, vec2 uv, vec3 p) {
    vec3 c = evalTexture(tex, uv, p).rgb;
    return (c.r + c.g + c.b) * (1.0 / 3.0);
}

// Bump mapping (Blinn 1978): the surface displaced along n, its normal from the displaced
// tangents dp/du + factor dh n. Image heights (mean of r, g, b) are differenced one texel apart,
// per texel rather than per unit of u, which is the course's scale for BumpFactor (checked
// against its official bump images); procedural ones by a central difference in 3D, keeping
// the gradient's part in the tangent plane.
vec3 normalFromBump(SurfaceInteraction si, uint index, float factor) {
    vec3 n = si.ns;
    GpuTexture tex = loadTexture(index);
    vec3 bumped;
    if (tex.type == TEXTURE_IMAGE) {
        vec2 duv = 1.0 / vec2(max(tex.width, 1u), max(tex.height, 1u));
        float h0 = bumpHeight(tex, si.uv, si.p);
        float dhdu = bumpHeight(tex, si.uv + vec2(duv.x, 0.0), si.p) - h0;
        float dhdv = bumpHeight(tex, si.uv + vec2(0.0, duv.y), si.p) - h0;
        vec3 qu = si.dpdu + factor * dhdu * n;
        vec3 qv = si.dpdv + factor * dhdv * n;
        bumped = cross(qu, qv);
        if (dot(bumped, n) < 0.0) bumped = -bumped;
    } else {
        // Step relative to the noise's feature size.
        float h = 1e-3 / max(abs(tex.patternScale), 1e-6);
        vec3 g = vec3(bumpHeight(tex, si.uv, si.p + vec3(h, 0, 0)) - bumpHeight(tex, si.uv, si.p - vec3(h, 0, 0)),
                     bumpHeight(tex, si.uv, si.p + vec3(0, h, 0)) - bumpHeight(tex, si.uv, si.p - vec3(0, h, 0)),
                     bumpHeight(tex, si.uv, si.p + vec3(0, 0, h)) - bumpHeight(tex, si.uv, si.p - vec3(0, 0, h))) /
                 (2.0 * h);
        bumped = n - factor * (g - n * dot(g, n));
    }
    float len2 = dot(bumped, bumped);
    return (len2 > 0.0 && !isinf(len2)) ? bumped * inversesqrt(len2) : n;
}

// A GGX alpha a roughness texture has scaled: below MIN_ROUGH_ALPHA a smooth (delta) surface, as
// the flattener maps the factors (src/flatten/flat_scene.cpp).
float texturedAlpha(float alpha) { return alpha >= MIN_ROUGH_ALPHA ? min(alpha, 1.0) : 0.0; }

// KHR_materials_clearcoat's textures: the factor in red, the roughness in green (alpha scales by
// its square), and the coat's normal, which is the surface's own (not the base's normal map)
// unless the coat has a map of its own; called before the base's normal map changes si.ns.
void applyClearcoatTextures(inout GpuMaterial m, SurfaceInteraction si) {
    if (m.clearcoatTexture != NO_TEXTURE) m.clearcoat *= evalTexture(m.clearcoatTexture, si.uv, si.p).r;
    if (m.clearcoatRoughnessTexture != NO_TEXTURE) {
        float g = evalTexture(m.clearcoatRoughnessTexture, si.uv, si.p).g;
        m.clearcoatAlpha = texturedAlpha(m.clearcoatAlpha * g * g);
    }
    if (m.clearcoatNormalTexture != NO_TEXTURE) {
        vec3 n =
            normalFromMap(si, evalTexture(m.clearcoatNormalTexture, si.uv, si.p).rgb, m.clearcoatNormalScale, false);
        m.clearcoatNormal = dot(n, si.ng) < 0.0 ? -n : n;
    } else {
        m.clearcoatNormal = si.nSurface;
    }
}

// KHR_materials_anisotropy's direction at a hit, in world space: the tangent (dp/du; glTF
// tangent space, y up the image) turned by the rotation, or the texture's rg direction turned by
// it, whose b scales the strength. Set before the base's normal map tilts si.ns; the frame the
// BSDF works in takes the direction's part in its own tangent plane (orientMaterialFrame).
void applyAnisotropy(inout GpuMaterial m, SurfaceInteraction si) {
    vec2 d = vec2(1.0, 0.0);
    if ((HAS_TEXTURES || HAS_PROCEDURAL) && m.anisotropyTexture != NO_TEXTURE) {
        vec3 c = evalTexture(m.anisotropyTexture, si.uv, si.p).rgb;
        vec2 v = c.rg * 2.0 - 1.0;
        d = dot(v, v) > 0.0 ? normalize(v) : d;
        m.anisotropy *= c.b;
    }
    float cr = cos(m.anisotropyRotation), sr = sin(m.anisotropyRotation);
    d = vec2(cr * d.x - sr * d.y, sr * d.x + cr * d.y);
    vec3 t, b;
    if (!tangentFrame(si, false, t, b)) {
        t = si.dpdu;
        b = cross(si.ns, t);
    }
    m.anisotropyDirection = d.x * t + d.y * b;
}

void applyTextures(inout GpuMaterial m, inout SurfaceInteraction si) {
    if (HAS_ANISOTROPY && m.anisotropy > 0.0) applyAnisotropy(m, si);
    if (!(HAS_TEXTURES || HAS_PROCEDURAL)) return;
    if (!hasAnyTexture(m)) return;
    if (m.baseColorTexture != NO_TEXTURE) {
        vec4 c = evalTexture(m.baseColorTexture, si.uv, si.p);
        bool blend = (m.flags & MATERIAL_FLAG_BLEND_KD) != 0u;
        m.baseColor = blend ? 0.5 * (m.baseColor + c.rgb) : m.baseColor * c.rgb;
        if (CLASSIC) m.classicDiffuse = blend ? 0.5 * (m.classicDiffuse + c.rgb) : m.classicDiffuse * c.rgb;
        m.opacity *= c.a;
    }
    if (m.specularTexture != NO_TEXTURE) {
        vec3 ks = evalTexture(m.specularTexture, si.uv, si.p).rgb;
        m.specular *= ks;
        if (CLASSIC) m.classicSpecular *= ks;
    }
    if (m.specularWeightTexture != NO_TEXTURE) m.specularWeight *= evalTexture(m.specularWeightTexture, si.uv, si.p).a;
    if (m.transmissionTexture != NO_TEXTURE) m.transmission *= evalTexture(m.transmissionTexture, si.uv, si.p).r;
    if (HAS_DIFFUSE_TRANSMISSION && m.diffuseTransmissionTexture != NO_TEXTURE)
        m.diffuseTransmission *= evalTexture(m.diffuseTransmissionTexture, si.uv, si.p).a;
    if (HAS_DIFFUSE_TRANSMISSION && m.diffuseTransmissionColorTexture != NO_TEXTURE)
        m.diffuseTransmissionColor *= evalTexture(m.diffuseTransmissionColorTexture, si.uv, si.p).rgb;
    if (m.metallicRoughnessTexture != NO_TEXTURE) {
        vec4 c = evalTexture(m.metallicRoughnessTexture, si.uv, si.p);
        // alpha = roughness^2, so the roughness channel scales sqrt(alpha); a specular-glossiness
        // texture's alpha is glossiness instead.
        float roughness = 1.0 - m.glossiness * c.a;
        bool glossy = (m.flags & MATERIAL_FLAG_GLOSSINESS) != 0u;
        float alpha = glossy ? roughness * roughness : m.alpha * c.g * c.g;
        m.alpha = texturedAlpha(alpha);
        if (!glossy) m.metallic *= c.b;
    }
    if (m.emissiveTexture != NO_TEXTURE) m.emission *= evalTexture(m.emissiveTexture, si.uv, si.p).rgb;
    if (HAS_CLEARCOAT) applyClearcoatTextures(m, si);
    if (HAS_SHEEN && m.sheenColorTexture != NO_TEXTURE)
        m.sheenColor *= evalTexture(m.sheenColorTexture, si.uv, si.p).rgb;
    if (HAS_SHEEN && m.sheenRoughnessTexture != NO_TEXTURE)
        m.sheenRoughness *= evalTexture(m.sheenRoughnessTexture, si.uv, si.p).a;
    if (HAS_IRIDESCENCE && m.iridescenceTexture != NO_TEXTURE)
        m.iridescence *= evalTexture(m.iridescenceTexture, si.uv, si.p).r;
    if (HAS_IRIDESCENCE && m.iridescenceThicknessTexture != NO_TEXTURE)
        m.iridescenceThickness = mix(m.iridescenceThicknessMinimum, m.iridescenceThickness,
            evalTexture(m.iridescenceThicknessTexture, si.uv, si.p).g);
    if (HAS_NORMAL_MAPS && m.normalTexture != NO_TEXTURE) {
        vec3 ns = (m.flags & MATERIAL_FLAG_BUMP_MAP) != 0u
                      ? normalFromBump(si, m.normalTexture, m.normalScale)
                      : normalFromMap(si, evalTexture(m.normalTexture, si.uv, si.p).rgb, m.normalScale,
                            (m.flags & MATERIAL_FLAG_NORMAL_Y_DOWN) != 0u);
        si.ns = dot(ns, si.ng) < 0.0 ? -ns : ns;
    }
}

#endif
