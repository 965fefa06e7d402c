#ifndef PT_BSDF_BSDF_SAMPLE_GLSL
#define PT_BSDF_BSDF_SAMPLE_GLSL

// Result of sampling a BSDF. Directions in world space, pointing away from the surface.
struct BsdfSample {
    vec3 wi;
    vec3 weight;    // f * |cos| / pdf
    float pdf;      // solid angle; for delta lobes the discrete probability of the lobe
    float etaScale; // (n_t / n_i)^2 across a refraction, else 1: undoes radiance scaling for RR
    bool isDelta;
    bool valid;
};

BsdfSample invalidBsdfSample() {
    BsdfSample s;
    s.wi = vec3(0.0, 0.0, 1.0);
    s.weight = vec3(0.0);
    s.pdf = 0.0;
    s.etaScale = 1.0;
    s.isDelta = false;
    s.valid = false;
    return s;
}

#endif
