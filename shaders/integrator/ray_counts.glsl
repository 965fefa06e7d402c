// Ray counts: each invocation counts the closest-hit and shadow rays of its own samples in
// private variables and adds them to its pixel's counters once at the end of a pass: for
// `pt bench` (COUNT_RAYS), and for adaptive sampling, which weighs a pixel's samples by their
// cost (render/adaptive_sampling.h). An integer add per ray; unused, it is removed.
#ifndef PT_INTEGRATOR_RAY_COUNTS_GLSL
#define PT_INTEGRATOR_RAY_COUNTS_GLSL
#include "shared/features.glsl"

uint closestRaysTraced = 0u; // camera rays and path continuations
uint shadowRaysTraced = 0u;

void countClosestRay() { ++closestRaysTraced; }

void countShadowRay() { ++shadowRaysTraced; }

#endif
