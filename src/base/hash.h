#pragma once
// FNV-1a, 64-bit: a stable hash of bytes (the same in every build and process), for cache keys
// and file checksums. Not cryptographic: it guards against accidents, not adversaries.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

namespace pt {

// Continues from `hash`, so several pieces can be hashed as one.
inline uint64_t fnv1a64(const void* data, size_t bytes, uint64_t hash = 0xcbf29ce484222325ull) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; ++i) {
        hash ^= p[i];
        hash *= 0x100000001b3ull;
    }
    return hash;
}

// The 16 lower-case hex digits of `value`, most significant first.
inline std::string hexDigits(uint64_t value) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
    return text;
}

} // namespace pt
