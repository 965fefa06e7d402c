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

// Unpolarised Fresnel reflectance of a conductor with complex index eta + i k, per channel
// (the exact expression, e.g. pbrt-v3's FrConductor, written for the outside medium n = 1).
vec3 fresnelConductor(float cosI, vec3 eta, vec3 k) {
    float c2 = cosI * cosI;
    float s2 = 1.0 - c2;
    vec3 eta2 = eta * eta;
    vec3 k2 = k * k;
    vec3 t0 = eta2 - k2 - s2;
    vec3 a2plusb2 = sqrt(t0 * t0 + 4.0 * eta2 * k2);
    vec3 t1 = a2plusb2 + c2;
    vec3 a = sqrt(max(0.5 * (a2plusb2 + t0), 0.0));
    vec3 t2 = 2.0 * cosI * a;
    vec3 rs = (t1 - t2) / (t1 + t2);
    vec3 t3 = c2 * a2plusb2 + s2 * s2;
    vec3 t4 = t2 * s2;
    // At normal incidence of an index with eta = k = 0 (reflectance 1) t3 = t4 = 0: rp = rs there.
    vec3 rp = mix(rs, rs * (t3 - t4) / (t3 + t4), greaterThan(t3 + t4, vec3(0.0)));
    return clamp(0.5 * (rp + rs), 0.0, 1.0);
}

#endif
