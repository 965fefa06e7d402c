#include "film/state_file.h"

#include "shared/layout.h"

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace pt {
namespace {

// Channel c (0..2: R, G, B) of vec4 `slot` of each pixel's ACCUM_* block.
struct StateChannel {
    const char* name;
    uint32_t slot;
    int component;
};
constexpr StateChannel kChannels[] = {
    {"state.sum.R", ACCUM_SUM, 0},
    {"state.sum.G", ACCUM_SUM, 1},
    {"state.sum.B", ACCUM_SUM, 2},
    {"state.sum_lo.R", ACCUM_SUM_LO, 0},
    {"state.sum_lo.G", ACCUM_SUM_LO, 1},
    {"state.sum_lo.B", ACCUM_SUM_LO, 2},
    {"state.sum_sq.R", ACCUM_SUM_SQUARES, 0},
    {"state.sum_sq.G", ACCUM_SUM_SQUARES, 1},
    {"state.sum_sq.B", ACCUM_SUM_SQUARES, 2},
    {"state.sum_sq_lo.R", ACCUM_SUM_SQUARES_LO, 0},
    {"state.sum_sq_lo.G", ACCUM_SUM_SQUARES_LO, 1},
    {"state.sum_sq_lo.B", ACCUM_SUM_SQUARES_LO, 2},
    {"state.dropped", ACCUM_SUM, 3},
};

// The splat words' channels: word k of SPLAT_WORDS_PER_PIXEL, piece j (bits 22j and up).
constexpr int kSplatPieces = 3;
constexpr int kSplatPieceBits = 22;
std::string splatChannelName(uint32_t word, int piece) {
    return "state.splat." + std::to_string(word) + "." + std::to_string(piece);
}

// Adaptive sampling's per-pixel counts (samples so far, the epoch's allocation, the epoch's
// rays): 32-bit integers as two 16-bit pieces, each exact in a float channel.
constexpr const char* kAdaptiveChannels[] = {"state.adaptive.samples.0", "state.adaptive.samples.1",
    "state.adaptive.allocation.0", "state.adaptive.allocation.1", "state.adaptive.rays.0", "state.adaptive.rays.1"};
constexpr int kAdaptiveCounts = 3;
template <class State>
auto& adaptiveCounts(State& state, int k) {
    return k < 2 ? state.pixelSamples : k < 4 ? state.allocation : state.epochRays;
}

uint32_t readIndex(const std::filesystem::path& path, const ImageMetadata& metadata, const char* key) {
    const auto it = metadata.find(key);
    uint64_t value = 0;
    if (it == metadata.end()) throw std::runtime_error(path.string() + ": metadata '" + key + "' is missing");
    const std::string& text = it->second;
    auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || value > UINT32_MAX)
        throw std::runtime_error(path.string() + ": metadata '" + key + "' is not a sample index ('" + text + "')");
    return static_cast<uint32_t>(value);
}

} // namespace

void writeStateExr(
    const std::filesystem::path& path, const AccumulationState& state, const Image& mean, ImageMetadata metadata) {
    std::vector<ExrChannel> channels;
    const size_t pixels = state.pixels();
    for (const StateChannel& c : kChannels) {
        ExrChannel out{c.name, std::vector<float>(pixels)};
        for (size_t i = 0; i < pixels; ++i)
            out.values[i] = state.sums[ACCUMULATION_VEC4S_PER_PIXEL * i + c.slot][c.component];
        channels.push_back(std::move(out));
    }
    if (state.hasSplats()) {
        for (uint32_t word = 0; word < SPLAT_WORDS_PER_PIXEL; ++word)
            for (int piece = 0; piece < kSplatPieces; ++piece) {
                ExrChannel out{splatChannelName(word, piece), std::vector<float>(pixels)};
                for (size_t i = 0; i < pixels; ++i) {
                    const uint64_t bits = state.splats[SPLAT_WORDS_PER_PIXEL * i + word] >> (kSplatPieceBits * piece);
                    out.values[i] = static_cast<float>(bits & ((uint64_t(1) << kSplatPieceBits) - 1));
                }
                channels.push_back(std::move(out));
            }
        metadata["splats"] = "1";
    }
    if (state.adaptive()) {
        for (int k = 0; k < 2 * kAdaptiveCounts; ++k) {
            const std::vector<uint32_t>& counts = adaptiveCounts(state, k);
            ExrChannel out{kAdaptiveChannels[k], std::vector<float>(pixels)};
            for (size_t i = 0; i < pixels; ++i)
                out.values[i] = static_cast<float>((counts[i] >> (16 * (k % 2))) & 0xffffu);
            channels.push_back(std::move(out));
        }
        metadata["adaptive"] = "1";
        metadata["epoch_rounds"] = std::to_string(state.epochRounds);
        metadata["epoch_rounds_done"] = std::to_string(state.epochRoundsDone);
    }
    metadata["state"] = kStateFormat;
    metadata["sample_begin"] = std::to_string(state.samples.begin);
    metadata["sample_end"] = std::to_string(state.samples.end);
    metadata["spp"] = std::to_string(state.spp);
    writeExr(path, mean, metadata, channels);
}

AccumulationState readStateExr(const std::filesystem::path& path, ImageMetadata& metadata) {
    std::vector<std::string> names;
    for (const StateChannel& c : kChannels) names.push_back(c.name);
    ExrChannels file = readExrChannels(path, names, &metadata);
    if (metadata["state"] != kStateFormat)
        throw std::runtime_error(path.string() + ": not a pt accumulation state (metadata 'state' is '" +
                                 metadata["state"] + "', expected " + kStateFormat + ")");
    AccumulationState state;
    state.width = file.width;
    state.height = file.height;
    state.samples = {readIndex(path, metadata, "sample_begin"), readIndex(path, metadata, "sample_end")};
    state.spp = readIndex(path, metadata, "spp");
    if (state.samples.end < state.samples.begin || state.spp == 0 || state.spp > state.samples.count())
        throw std::runtime_error(path.string() + ": inconsistent sample range " + state.samples.describe() + " for " +
                                 std::to_string(state.spp) + " spp");
    const size_t pixels = state.pixels();
    state.sums.assign(pixels * ACCUMULATION_VEC4S_PER_PIXEL, glm::vec4(0.0f));
    for (size_t k = 0; k < std::size(kChannels); ++k)
        for (size_t i = 0; i < pixels; ++i)
            state.sums[ACCUMULATION_VEC4S_PER_PIXEL * i + kChannels[k].slot][kChannels[k].component] =
                file.channels[k].values[i];
    if (metadata.count("splats") && metadata["splats"] == "1") {
        std::vector<std::string> splatNames;
        for (uint32_t word = 0; word < SPLAT_WORDS_PER_PIXEL; ++word)
            for (int piece = 0; piece < kSplatPieces; ++piece) splatNames.push_back(splatChannelName(word, piece));
        ExrChannels splatFile = readExrChannels(path, splatNames);
        state.splats.assign(pixels * SPLAT_WORDS_PER_PIXEL, 0);
        for (uint32_t word = 0; word < SPLAT_WORDS_PER_PIXEL; ++word)
            for (int piece = 0; piece < kSplatPieces; ++piece) {
                const std::vector<float>& values = splatFile.channels[word * kSplatPieces + piece].values;
                for (size_t i = 0; i < pixels; ++i) {
                    const float v = values[i];
                    if (!(v >= 0.0f && v < float(uint64_t(1) << kSplatPieceBits)) || v != std::floor(v))
                        throw std::runtime_error(path.string() + ": channel " + splatChannelName(word, piece) +
                                                 " holds a value that is not a 22-bit integer");
                    state.splats[SPLAT_WORDS_PER_PIXEL * i + word] |= uint64_t(v) << (kSplatPieceBits * piece);
                }
            }
    }
    if (metadata.count("adaptive") && metadata["adaptive"] == "1") {
        ExrChannels adaptiveFile =
            readExrChannels(path, std::vector<std::string>(std::begin(kAdaptiveChannels), std::end(kAdaptiveChannels)));
        for (int k = 0; k < 2 * kAdaptiveCounts; k += 2) adaptiveCounts(state, k).assign(pixels, 0);
        for (int k = 0; k < 2 * kAdaptiveCounts; ++k) {
            std::vector<uint32_t>& counts = adaptiveCounts(state, k);
            const std::vector<float>& values = adaptiveFile.channels[k].values;
            for (size_t i = 0; i < pixels; ++i) {
                const float v = values[i];
                if (!(v >= 0.0f && v <= 65535.0f) || v != std::floor(v))
                    throw std::runtime_error(path.string() + ": channel " + kAdaptiveChannels[k] +
                                             " holds a value that is not a 16-bit integer");
                counts[i] |= uint32_t(v) << (16 * (k % 2));
            }
        }
        state.epochRounds = readIndex(path, metadata, "epoch_rounds");
        state.epochRoundsDone = readIndex(path, metadata, "epoch_rounds_done");
        if (state.epochRoundsDone > state.epochRounds || state.samples.begin != 0)
            throw std::runtime_error(path.string() + ": inconsistent adaptive sampling epoch (" +
                                     std::to_string(state.epochRoundsDone) + " of " +
                                     std::to_string(state.epochRounds) + " rounds done)");
    }
    return state;
}

} // namespace pt
