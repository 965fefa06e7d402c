#pragma once
// The memory a scene will need, checked before it is allocated: a scene too big for the machine
// stops with one line naming the file, the need and the limit (exit 1), instead of a
// std::bad_alloc halfway through expanding it, or the kernel's OOM killer.
#include <cstdint>
#include <string>

namespace pt {

// Peak resident bytes per triangle of `pt render` from loading to rendering on lavapipe, where
// device memory is host memory (the scene model, the flattened arrays, the BVH build and the
// device buffers), rounded up: 259 at 3 M triangles, the process's fixed 180 MB included
// (bench/RESULTS.md, "Peak memory against triangle count"; bench/bench_peak_memory.py).
constexpr uint64_t kPeakBytesPerTriangle = 300;

// The bytes `triangles` triangles are expected to need at the peak.
uint64_t estimatedSceneBytes(uint64_t triangles);

// Throws SceneError(file, "needs about X for N triangles (<what>), more than <the limit>") when
// the estimate exceeds what hostMemoryHeadroom() leaves; `what` says where the triangles come
// from (e.g. "instances copied into world space").
void requireMemoryForTriangles(const std::string& file, uint64_t triangles, const std::string& what);

} // namespace pt
