// What this pipeline was specialised for. The host sets these from the scene and the switches
// (src/flatten/feature_set.cpp); code behind a false constant is removed when the pipeline is
// created, so a scene pays nothing for features it does not use.
#ifndef PT_INTEGRATOR_FEATURES_GLSL
#define PT_INTEGRATOR_FEATURES_GLSL
#include "shared/layout.h"

layout(constant_id = SPEC_HAS_DIFFUSE) const bool HAS_DIFFUSE = true;
layout(constant_id = SPEC_HAS_MIRROR) const bool HAS_MIRROR = true;
layout(constant_id = SPEC_HAS_DIELECTRIC) const bool HAS_DIELECTRIC = true;
layout(constant_id = SPEC_HAS_ABSORPTION) const bool HAS_ABSORPTION = true;
layout(constant_id = SPEC_HAS_SHADING_NORMALS) const bool HAS_SHADING_NORMALS = true;
layout(constant_id = SPEC_HAS_EMITTERS) const bool HAS_EMITTERS = true;
layout(constant_id = SPEC_USE_NEE) const bool USE_NEE = true;
layout(constant_id = SPEC_USE_MIS) const bool USE_MIS = true;
layout(constant_id = SPEC_USE_RR) const bool USE_RR = true;
layout(constant_id = SPEC_COSINE_SAMPLING) const bool COSINE_SAMPLING = true;
layout(constant_id = SPEC_HAS_SPHERES) const bool HAS_SPHERES = true;
layout(constant_id = SPEC_HAS_TRIANGLES) const bool HAS_TRIANGLES = true;
layout(constant_id = SPEC_HAS_CONDUCTOR) const bool HAS_CONDUCTOR = true;
layout(constant_id = SPEC_HAS_PUNCTUAL_LIGHTS) const bool HAS_PUNCTUAL_LIGHTS = true;
layout(constant_id = SPEC_HAS_GLOSSY) const bool HAS_GLOSSY = true;
layout(constant_id = SPEC_HAS_ENVIRONMENT) const bool HAS_ENVIRONMENT = true;
layout(constant_id = SPEC_HAS_TEXTURES) const bool HAS_TEXTURES = true;
layout(constant_id = SPEC_HAS_NORMAL_MAPS) const bool HAS_NORMAL_MAPS = true;
layout(constant_id = SPEC_HAS_ALPHA) const bool HAS_ALPHA = true;
layout(constant_id = SPEC_HAS_PROCEDURAL) const bool HAS_PROCEDURAL = true;
layout(constant_id = SPEC_HAS_UNLIT) const bool HAS_UNLIT = true;
layout(constant_id = SPEC_HAS_MICROFACET) const bool HAS_MICROFACET = true;
layout(constant_id = SPEC_HAS_PBR) const bool HAS_PBR = true;
layout(constant_id = SPEC_DEBUG_VIEW) const uint DEBUG_VIEW = DEBUG_VIEW_NONE;
layout(constant_id = SPEC_CLASSIC) const bool CLASSIC = false;
layout(constant_id = SPEC_HAS_MOTION) const bool HAS_MOTION = true;
layout(constant_id = SPEC_COUNT_RAYS) const bool COUNT_RAYS = false;
// Light tracing lives in its own SPIR-V module (CMakeLists.txt: PT_LIGHT_TRACING); the other
// module has none of its code.
#ifdef PT_LIGHT_TRACING
layout(constant_id = SPEC_LIGHT_TRACING) const bool LIGHT_TRACING = false;
#else
const bool LIGHT_TRACING = false;
#endif

#endif
