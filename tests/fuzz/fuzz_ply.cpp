// libFuzzer target: the ply loader on arbitrary bytes (see fuzz_main.h and tests/fuzz/README.md).
#include "fuzz/fuzz_main.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    return pt::test::fuzzEntry(pt::test::FuzzTarget::Ply, data, size);
}
