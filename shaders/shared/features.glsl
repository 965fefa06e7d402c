// What this pipeline was specialised for: one specialization constant per row of
// shared/features.h. The host sets them from the scene and the switches
// (src/flatten/feature_set.cpp); code behind a false constant is removed when the pipeline is
// created, so a scene pays nothing for features it does not use.
#ifndef PT_SHARED_FEATURES_GLSL
#define PT_SHARED_FEATURES_GLSL
#include "shared/layout.h"
#include "shared/features.h"

#define PT_DECLARE_flag(NAME, id, value) layout(constant_id = id) const bool NAME = value;
#define PT_DECLARE_choice(NAME, id, value) layout(constant_id = id) const uint NAME = value;
// Light tracing and bidirectional path tracing live in SPIR-V modules of their own
// (CMakeLists.txt: PT_LIGHT_TRACING, PT_BDPT); the other modules have none of their code, and
// there the constant is a plain false.
#ifdef PT_LIGHT_TRACING
#define PT_MODULE_LIGHT_TRACING(id, value) layout(constant_id = id) const bool LIGHT_TRACING = value;
#else
#define PT_MODULE_LIGHT_TRACING(id, value) const bool LIGHT_TRACING = value;
#endif
#ifdef PT_BDPT
#define PT_MODULE_BDPT(id, value) layout(constant_id = id) const bool BDPT = value;
#else
#define PT_MODULE_BDPT(id, value) const bool BDPT = value;
#endif
#define PT_DECLARE_module(NAME, id, value) PT_MODULE_##NAME(id, value)
#define PT_DECLARE_FEATURE(field, kind, NAME, id, unspecialised, all, decide, log, description)                        \
    PT_DECLARE_##kind(NAME, id, unspecialised)
PT_FEATURES(PT_DECLARE_FEATURE)

#endif
