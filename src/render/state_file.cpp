#include "render/state_file.h"

#include "shared/layout.h"

#include <charconv>
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
    {"state.sum.R", ACCUM_SUM, 0}, {"state.sum.G", ACCUM_SUM, 1}, {"state.sum.B", ACCUM_SUM, 2},
    {"state.sum_lo.R", ACCUM_SUM_LO, 0}, {"state.sum_lo.G", ACCUM_SUM_LO, 1}, {"state.sum_lo.B", ACCUM_SUM_LO, 2},
    {"state.sum_sq.R", ACCUM_SUM_SQUARES, 0}, {"state.sum_sq.G", ACCUM_SUM_SQUARES, 1},
    {"state.sum_sq.B", ACCUM_SUM_SQUARES, 2}, {"state.sum_sq_lo.R", ACCUM_SUM_SQUARES_LO, 0},
    {"state.sum_sq_lo.G", ACCUM_SUM_SQUARES_LO, 1}, {"state.sum_sq_lo.B", ACCUM_SUM_SQUARES_LO, 2},
    {"state.dropped", ACCUM_SUM, 3},
};

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

void writeStateExr(const std::filesystem::path& path, const AccumulationState& state, const Image& mean,
    ImageMetadata metadata) {
    std::vector<ExrChannel> channels;
    const size_t pixels = state.pixels();
    for (const StateChannel& c : kChannels) {
        ExrChannel out{c.name, std::vector<float>(pixels)};
        for (size_t i = 0; i < pixels; ++i) out.values[i] = state.sums[ACCUMULATION_VEC4S_PER_PIXEL * i + c.slot][c.component];
        channels.push_back(std::move(out));
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
            state.sums[ACCUMULATION_VEC4S_PER_PIXEL * i + kChannels[k].slot][kChannels[k].component] = file.channels[k].values[i];
    return state;
}

} // namespace pt
