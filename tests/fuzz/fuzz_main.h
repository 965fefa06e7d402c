#pragma once
// One libFuzzer entry point per loader (fuzz_gltf.cpp, ...): each input goes through the loader's
// contract check (support/fuzz_inputs.h); a broken contract is reported and aborts, which
// libFuzzer records as a crash and saves the input.
#include "support/fuzz_inputs.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>

namespace pt::test {

inline int fuzzEntry(FuzzTarget target, const uint8_t* data, size_t size) {
    const std::string problem =
        fuzzOneInput(target, std::string_view(reinterpret_cast<const char*>(data), size), PT_FUZZ_DATA_DIR);
    if (!problem.empty()) {
        std::fprintf(stderr, "fuzz_%s: loader contract broken: %s\n", fuzzTargetName(target), problem.c_str());
        std::abort();
    }
    return 0;
}

} // namespace pt::test
