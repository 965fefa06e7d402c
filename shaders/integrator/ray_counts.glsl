// Ray counts for `pt bench` (COUNT_RAYS): each invocation counts the closest-hit and
// shadow rays of its own samples in private variables and adds them to its pixel's counters
// once at the end of a pass. Without the constant every increment is removed.
#ifndef PT_INTEGRATOR_RAY_COUNTS_GLSL
#define PT_INTEGRATOR_RAY_COUNTS_GLSL
#include "shared/features.glsl"

uint closestRaysTraced = 0u; // camera rays and path continuations
uint shadowRaysTraced = 0u;

void countClosestRay() {
    if (COUNT_RAYS) ++closestRaysTraced;
}

void countShadowRay() {
    if (COUNT_RAYS) ++shadowRaysTraced;
}

#endif
