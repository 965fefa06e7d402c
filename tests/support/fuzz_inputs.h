#pragma once
// The loaders as the fuzz targets (tests/fuzz/) see them: bytes in, and "" back when the loader
// kept its contract (support/load_contract.h), else what it broke. The corpus replay test
// (tests/scene/fuzz_corpus_test.cpp) runs every checked-in fuzz input through the same functions
// in the ordinary build, so a crash once found stays fixed without clang.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace pt::test {

enum class FuzzTarget { Gltf, Ceng795, Ply, TextureImage };

// Lower-case names: the fuzzer binaries are fuzz_<name>, the corpora tests/fuzz/corpus/<name>/.
const char* fuzzTargetName(FuzzTarget target);
std::vector<FuzzTarget> allFuzzTargets();

// `dataDir` is where relative references (buffers, PLY files, images) resolve: tests/fuzz/data,
// so that inputs can reach the external-file code paths without touching anything else.
std::string fuzzOneInput(FuzzTarget target, std::string_view bytes, const std::filesystem::path& dataDir);

} // namespace pt::test
