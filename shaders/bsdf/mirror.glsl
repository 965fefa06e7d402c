// Perfect specular reflection, tinted by Schlick's Fresnel with F0 = base colour (glTF metal
// at roughness 0). Local frame: z is the shading normal on the side of wo.
#ifndef PT_BSDF_MIRROR_GLSL
#define PT_BSDF_MIRROR_GLSL
#include "bsdf/fresnel.glsl"
#include "bsdf/bsdf_sample.glsl"

BsdfSample mirrorSample(vec3 baseColor, Frame frame, vec3 woLocal) {
    BsdfSample s = invalidBsdfSample();
    if (woLocal.z <= 0.0) return s;
    s.wi = toWorld(frame, vec3(-woLocal.xy, woLocal.z));
    s.weight = fresnelSchlick(baseColor, woLocal.z);
    s.pdf = 1.0;
    s.isDelta = true;
    s.valid = true;
    return s;
}

#endif
