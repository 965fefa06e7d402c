// The BVH builder's thread fan-out: a parallel loop over indices and a fixed chunking of ranges
// (fixed so that results never depend on the thread count).
#pragma once
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

namespace pt::bvh_detail {

// Runs fn(i) for every i in [0, count) on up to `threads` threads (the caller included), handing
// indices out dynamically. Callers must make results independent of which thread ran what.
template <class Fn>
void parallelFor(int threads, size_t count, Fn&& fn) {
    const size_t workers = std::min<size_t>(size_t(std::max(threads, 1)), count);
    if (workers <= 1) {
        for (size_t i = 0; i < count; ++i) fn(i);
        return;
    }
    std::atomic<size_t> next{0};
    std::mutex errorMutex;
    std::exception_ptr error;
    auto loop = [&] {
        try {
            for (size_t i; (i = next.fetch_add(1, std::memory_order_relaxed)) < count;) fn(i);
        } catch (...) {
            std::lock_guard lock(errorMutex);
            if (!error) error = std::current_exception();
            next.store(count);
        }
    };
    std::vector<std::thread> pool;
    pool.reserve(workers - 1);
    for (size_t w = 1; w < workers; ++w) {
        try {
            pool.emplace_back(loop);
        } catch (...) {
            break; // could not start a thread: the caller's loop below does the remaining work
        }
    }
    loop();
    for (auto& t : pool) t.join();
    if (error) std::rethrow_exception(error);
}

// Fixed chunking for flat parallel loops (independent of the thread count on purpose).
inline size_t chunkCount(size_t n) { return std::max<size_t>(1, std::min<size_t>(64, n / 16384)); }

inline std::pair<uint32_t, uint32_t> chunkRange(uint32_t begin, uint32_t end, size_t chunks, size_t c) {
    const uint64_t n = end - begin;
    return {uint32_t(begin + n * c / chunks), uint32_t(begin + n * (c + 1) / chunks)};
}

} // namespace pt::bvh_detail
