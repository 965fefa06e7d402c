#include "accel/huge_page_allocator.h"

#include <sys/mman.h>

#include <algorithm>
#include <cstdlib>

namespace pt {

void* allocateHugePages(size_t bytes) {
    const size_t rounded = std::max<size_t>(1, (bytes + kHugePage - 1) / kHugePage) * kHugePage;
    void* p = std::aligned_alloc(kHugePage, rounded);
    if (!p) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
    madvise(p, rounded, MADV_HUGEPAGE);
#endif
    return p;
}

void freeHugePages(void* p) noexcept { std::free(p); }

} // namespace pt
