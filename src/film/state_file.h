#pragma once
// An accumulation state in an OpenEXR file: R, G, B, A hold the mean image as in any pt output,
// and float32 channels `state.sum.{R,G,B}`, `state.sum_lo.*`, `state.sum_sq.*`,
// `state.sum_sq_lo.*` and `state.dropped` hold the raw double-float sums bit for bit, so the
// file can be merged (pt merge) or continued (pt render --resume) exactly. Metadata adds
// `state` (format version), `sample_begin`, `sample_end` and `spp`. A light-traced render adds
// metadata `splats` = 1 and its uint64 splat sums, each as three float channels of 22 bits
// (`state.splat.<word>.<piece>`: floats hold integers below 2^24 exactly). Written atomically.
#include "film/accumulation_state.h"
#include "image/image_io.h"

#include <filesystem>

namespace pt {

constexpr const char* kStateFormat = "pt-accumulation-1";

void writeStateExr(
    const std::filesystem::path& path, const AccumulationState& state, const Image& mean, ImageMetadata metadata);

// Throws "<path>: <problem>" for a file without the state channels or with inconsistent metadata.
AccumulationState readStateExr(const std::filesystem::path& path, ImageMetadata& metadata);

} // namespace pt
