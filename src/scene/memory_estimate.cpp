#include "scene/memory_estimate.h"

#include "base/memory_usage.h"
#include "scene/scene_error.h"

namespace pt {

uint64_t estimatedSceneBytes(uint64_t triangles) {
    // Saturating: a hostile file's counts must not wrap around to a small need.
    return triangles > UINT64_MAX / kPeakBytesPerTriangle ? UINT64_MAX : triangles * kPeakBytesPerTriangle;
}

void requireMemoryForTriangles(const std::string& file, uint64_t triangles, const std::string& what) {
    const uint64_t need = estimatedSceneBytes(triangles);
    const MemoryHeadroom headroom = hostMemoryHeadroom();
    if (need <= headroom.bytes) return;
    throw SceneError(file, "needs about " + formatBytes(need) + " of memory for " + std::to_string(triangles) +
                               " triangles (" + what + "), more than " + headroom.limit + " allows");
}

} // namespace pt
