#ifndef PT_COMMON_RAY_GLSL
#define PT_COMMON_RAY_GLSL

struct Ray {
    vec3 origin;
    vec3 direction; // not necessarily unit length for the intersectors; the integrator keeps it unit
};

#endif
