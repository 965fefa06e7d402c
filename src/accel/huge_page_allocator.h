// Memory for the BVH build's big arrays on transparent huge pages: the builder's primitive
// buffers and the finished node array are first written by the build itself, and on huge pages
// that costs one page fault per 2 MiB instead of one per 4 KiB.
#pragma once
#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>

namespace pt {

constexpr size_t kHugePage = size_t(2) << 20;

// Memory for `bytes` bytes, 2 MiB aligned and rounded up to whole 2 MiB pages, on transparent
// huge pages where the system gives them on request (Debian's default "madvise" mode). Throws
// std::bad_alloc; released with freeHugePages.
void* allocateHugePages(size_t bytes);
void freeHugePages(void* p) noexcept;

struct HugeFree {
    void operator()(void* p) const { freeHugePages(p); }
};

// An uninitialised array of `count` T on huge pages. Trivial types only (the memory is not
// constructed).
template <class T>
using HugeArray = std::unique_ptr<T[], HugeFree>;
template <class T>
HugeArray<T> allocateHuge(size_t count) {
    static_assert(std::is_trivially_default_constructible_v<T> && std::is_trivially_destructible_v<T>);
    return HugeArray<T>(static_cast<T*>(allocateHugePages(count * sizeof(T))));
}

// A std::allocator whose value-less construct() default-initialises, so that resize() leaves
// trivial elements unwritten: the builder fills its fresh node array on all threads instead of
// first zero-filling it on one (about 50 MB for a million triangles). Arrays of 2 MiB and more go
// on huge pages (fewer page faults when the build first writes them).
template <class T>
struct DefaultInitAllocator : std::allocator<T> {
    template <class U>
    struct rebind {
        using other = DefaultInitAllocator<U>;
    };
    DefaultInitAllocator() = default;
    template <class U>
    DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}
    template <class U>
    void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
        ::new (static_cast<void*>(p)) U;
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
    T* allocate(size_t count) {
        if (count * sizeof(T) < kHugePage) return std::allocator<T>::allocate(count);
        return static_cast<T*>(allocateHugePages(count * sizeof(T)));
    }
    void deallocate(T* p, size_t count) noexcept {
        if (count * sizeof(T) < kHugePage)
            std::allocator<T>::deallocate(p, count);
        else
            freeHugePages(p);
    }
};

} // namespace pt
