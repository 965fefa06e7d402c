#ifndef PT_BSDF_FRESNEL_GLSL
#define PT_BSDF_FRESNEL_GLSL

// Unpolarised Fresnel reflectance of a dielectric interface. cosI >= 0 on the incident side;
// eta = n_transmitted / n_incident. Returns 1 under total internal reflection.
float fresnelDielectric(float cosI, float eta, out float cosT) {
    float sin2T = (1.0 - cosI * cosI) / (eta * eta);
    if (sin2T >= 1.0) {
        cosT = 0.0;
        return 1.0;
    }
    cosT = sqrt(1.0 - sin2T);
    float rs = (cosI - eta * cosT) / (cosI + eta * cosT);
    float rp = (eta * cosI - cosT) / (eta * cosI + cosT);
    return 0.5 * (rs * rs + rp * rp);
}

// Schlick's approximation with a coloured F0, the glTF metal model.
vec3 fresnelSchlick(vec3 f0, float cosI) {
    float m = clamp(1.0 - cosI, 0.0, 1.0);
    float m2 = m * m;
    return f0 + (1.0 - f0) * (m2 * m2 * m);
}

#endif
