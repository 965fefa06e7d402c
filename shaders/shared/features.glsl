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
// Light tracing lives in its own SPIR-V module (CMakeLists.txt: PT_LIGHT_TRACING); the other
// module has none of its code, and there the constant is a plain false.
#ifdef PT_LIGHT_TRACING
#define PT_DECLARE_module(NAME, id, value) layout(constant_id = id) const bool NAME = value;
#else
#define PT_DECLARE_module(NAME, id, value) const bool NAME = value;
#endif
#define PT_DECLARE_FEATURE(field, kind, NAME, id, unspecialised, all, decide, log, description)                        \
    PT_DECLARE_##kind(NAME, id, unspecialised)
PT_FEATURES(PT_DECLARE_FEATURE)

#endif
