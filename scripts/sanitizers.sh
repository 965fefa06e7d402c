#!/usr/bin/env bash
# The sanitizer step of CI (called by .ci/run after the README's test command): builds pt, the host
# and command-line tests and the loaders' libFuzzer targets with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer in their own build directory, then runs
#   - pt_host_tests and pt_cli_tests (every finding aborts the test: -fno-sanitize-recover=all),
#   - a sample of the GPU tests that covers the host side of rendering (scene flattening, BVH
#     upload, textures, environment tables, the accumulation state, partitions and checkpoints,
#     degenerate input): lavapipe itself is not instrumented, and the whole GPU suite would take
#     longer than this step may (10 minutes on 2 cores, build included); this sample takes ~70 s,
#   - a short fuzz run of each loader (its seed corpus, then PT_FUZZ_SECONDS of mutation).
# Usage: bash scripts/sanitizers.sh   (env: PT_ASAN_BUILD_DIR, default build-asan; PT_FUZZ_SECONDS, default 20)
set -euo pipefail
cd "$(dirname "$0")/.."

build=${PT_ASAN_BUILD_DIR:-build-asan}
fuzz_seconds=${PT_FUZZ_SECONDS:-20}
jobs=$(nproc)

command -v clang++ >/dev/null || { echo "sanitizers: clang++ not found (scripts/setup.sh installs clang)"; exit 1; }

# -O1: a third of -O2's compile time, and sanitizer reports keep usable stacks.
cmake -S . -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS=-O1 \
  -DPT_SANITIZE=ON -DPT_FUZZ=ON -DPT_FUZZ_SHORT_SECONDS="$fuzz_seconds" >/dev/null
cmake --build "$build" -j "$jobs" --target pt pt_host_tests pt_cli_tests pt_gpu_tests \
  fuzz_gltf fuzz_ceng795 fuzz_ply fuzz_texture_image

# Leaks in the Vulkan loader and Mesa's lavapipe are theirs, not ours: suppressed with a reason
# per line in tests/sanitizers/lsan.supp. pt_cli_tests runs the instrumented pt, which inherits these.
export ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1:check_initialization_order=1:detect_stack_use_after_return=1
export LSAN_OPTIONS=suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

# Speed tests measure the uninstrumented code's speed (the ordinary build runs them); ASan makes
# everything 2-3x slower, so they are left out here.
"$build/tests/pt_host_tests" --gtest_brief=1 \
  --gtest_filter='-Bvh.BuildSpeedMillionRandomTriangles:PlyReader.MillionTriangleBinaryIsFast'
# The command line on every malformed input and the basic commands; the long renders of pt bench,
# partitions and checkpoints run in the ordinary build only (under ASan they alone take minutes);
# so do the tests under `ulimit -v` (ASan's shadow memory needs terabytes of address space).
"$build/tests/pt_cli_tests" --gtest_brief=1 \
  --gtest_filter='*Corpus*:CliTest.*:-CliTest.Bench*:CliTest.*Refused*:CliTest.*UnderTheSameLimit'
"$build/tests/pt_gpu_tests" --gtest_brief=1 --gtest_filter='MitsubaReference.CornellBoxDiffuse:OwnScenes.Textured*:*TraversalTest.*:HardCases.Degenerate*:EnvironmentLight.*:Partition*:Checkpoint*:Accumulation*'
ctest --test-dir "$build" -L fuzz -j "$jobs" --output-on-failure
echo "sanitizers: host tests, CLI tests, GPU test sample and fuzz runs clean under ASan + UBSan"
