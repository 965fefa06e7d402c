// The accumulation state on the host: sample-range parsing, merging (exact double-float sums,
// overlap refused, gaps found) and the state EXR round trip (bit for bit).
#include "film/accumulation_state.h"
#include "film/state_file.h"
#include "shared/layout.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>

namespace pt {
namespace {

AccumulationState state(SampleRange range, float sumHi, float sumLo, float dropped = 0) {
    AccumulationState s;
    s.width = 2;
    s.height = 1;
    s.samples = range;
    s.spp = range.count();
    s.sums.assign(2 * ACCUMULATION_VEC4S_PER_PIXEL, glm::vec4(0.0f));
    for (size_t p = 0; p < 2; ++p) {
        s.sums[ACCUMULATION_VEC4S_PER_PIXEL * p + ACCUM_SUM] = glm::vec4(sumHi, sumHi, sumHi, dropped);
        s.sums[ACCUMULATION_VEC4S_PER_PIXEL * p + ACCUM_SUM_LO] = glm::vec4(sumLo, sumLo, sumLo, 0.0f);
        s.sums[ACCUMULATION_VEC4S_PER_PIXEL * p + ACCUM_SUM_SQUARES] = glm::vec4(sumHi, sumHi, sumHi, 0.0f);
    }
    return s;
}

TEST(SampleRange, ParsesAndRejects) {
    const SampleRange r = parseSampleRange("5:12");
    EXPECT_EQ(r.begin, 5u);
    EXPECT_EQ(r.end, 12u);
    EXPECT_EQ(r.count(), 7u);
    for (const char* bad : {"5", "5:5", "7:3", "a:4", "1:99999999999", ":4", "3:", "-1:4"})
        EXPECT_THROW(parseSampleRange(bad), std::runtime_error) << bad;
}

TEST(MergeStates, AddsTheDoubleFloatSumsExactly) {
    // hi + lo carries more than a float: 1 + 2^-30 survives the merge of two such parts.
    const float lo = std::ldexp(1.0f, -30);
    const AccumulationState merged = mergeStates({state({4, 8}, 1.0f, lo, 1), state({0, 4}, 1.0f, lo, 2)});
    EXPECT_EQ(merged.samples.begin, 0u);
    EXPECT_EQ(merged.samples.end, 8u);
    EXPECT_EQ(merged.spp, 8u);
    EXPECT_EQ(merged.sum(0).x, 2.0 + 2.0 * double(lo));
    EXPECT_EQ(merged.dropped(1), 3u);
    EXPECT_EQ(resolve(merged).droppedSamples, 6u);
}

TEST(MergeStates, RefusesOverlapAndFindsGaps) {
    EXPECT_THROW(mergeStates({state({0, 5}, 1, 0), state({4, 8}, 1, 0)}), std::runtime_error);
    const auto gaps = findGaps({{10, 12}, {0, 4}, {6, 10}});
    ASSERT_EQ(gaps.size(), 1u);
    EXPECT_EQ(gaps[0].describe(), "4:6");
    const AccumulationState withGap = mergeStates({state({0, 4}, 1, 0), state({6, 10}, 1, 0)});
    EXPECT_EQ(withGap.spp, 8u);
    EXPECT_EQ(withGap.samples.describe(), "0:10");
}

TEST(StateFile, RoundTripsBitForBit) {
    const auto path = std::filesystem::temp_directory_path() / ("pt_state_" + std::to_string(::getpid()) + ".exr");
    AccumulationState s = state({3, 9}, 1.1f, std::ldexp(1.3f, -27), 2);
    s.sums[5].y = -0.0f; // every float, signs and all
    const AccumulatedImage image = resolve(s);
    writeStateExr(path, s, image.mean, {{"seed", "4"}});
    ImageMetadata meta;
    const AccumulationState back = readStateExr(path, meta);
    std::filesystem::remove(path);
    EXPECT_EQ(back.samples.describe(), "3:9");
    EXPECT_EQ(back.spp, 6u);
    EXPECT_EQ(meta["seed"], "4");
    ASSERT_EQ(back.sums.size(), s.sums.size());
    EXPECT_EQ(std::memcmp(back.sums.data(), s.sums.data(), s.sums.size() * sizeof(glm::vec4)), 0);
}

// Light tracing's splat sums: word k of pixel p set to `value` (scaled to fixed point).
void setSplats(AccumulationState& s, double sum, double sumSquares) {
    s.splats.assign(s.pixels() * SPLAT_WORDS_PER_PIXEL, 0);
    for (size_t p = 0; p < s.pixels(); ++p)
        for (uint32_t c = 0; c < 3; ++c) {
            s.splats[SPLAT_WORDS_PER_PIXEL * p + SPLAT_SUM + c] = uint64_t(std::llround(sum * SPLAT_SUM_SCALE));
            s.splats[SPLAT_WORDS_PER_PIXEL * p + SPLAT_SUM_SQUARES + c] =
                uint64_t(std::llround(sumSquares * SPLAT_SQUARE_SCALE));
        }
}

TEST(Splats, ResolveAddsTheLightTracersMeanAndVariance) {
    // 2 pixels, 4 spp: N = 8 light paths. Pixel values X = 2 Y; Y splatted = 0.5 by one path
    // and 0.25 by another: mean sum(Y) / n = 0.75 / 4; variance of that mean
    // sum(Y^2) / n^2 - mean^2 / N = 0.3125 / 16 - 0.1875^2 / 8.
    AccumulationState s = state({0, 4}, 0.0f, 0.0f);
    for (auto& v : s.sums) v = glm::vec4(0.0f); // no camera contribution
    setSplats(s, 0.75, 0.3125);
    const AccumulatedImage image = resolve(s);
    EXPECT_NEAR(image.mean.rgba[0], 0.1875, 1e-7);
    EXPECT_NEAR(image.varianceOfMean.rgba[0], 0.3125 / 16 - 0.1875 * 0.1875 / 8, 1e-8);
    // Brute force: the 8 per-path pixel estimates X (two of them 1.0 and 0.5, the rest 0).
    const double xs[8] = {1.0, 0.5, 0, 0, 0, 0, 0, 0};
    double mean = 0, second = 0;
    for (double x : xs) mean += x / 8, second += x * x / 8;
    EXPECT_NEAR(image.mean.rgba[0], mean, 1e-7);
    EXPECT_NEAR(image.varianceOfMean.rgba[0], (second - mean * mean) / 8, 1e-8);
}

TEST(Splats, MergeAddsThemAndRefusesAMix) {
    AccumulationState a = state({0, 4}, 1.0f, 0.0f), b = state({4, 8}, 1.0f, 0.0f);
    setSplats(a, 0.5, 0.25);
    setSplats(b, 1.0, 2.0);
    const AccumulationState merged = mergeStates({b, a});
    ASSERT_TRUE(merged.hasSplats());
    EXPECT_EQ(merged.splatSum(1).z, 1.5);
    EXPECT_EQ(merged.splatSumSquares(0).x, 2.25);
    EXPECT_THROW(mergeStates({a, state({4, 8}, 1.0f, 0.0f)}), std::runtime_error);
}

TEST(Splats, StateFileRoundTripsThemBitForBit) {
    const auto path = std::filesystem::temp_directory_path() / ("pt_splats_" + std::to_string(::getpid()) + ".exr");
    AccumulationState s = state({0, 6}, 1.0f, 0.0f);
    setSplats(s, 0.0, 0.0);
    // Every bit of the 64-bit words, including the top ones.
    s.splats[0] = ~uint64_t(0);
    s.splats[1] = uint64_t(1) << 63;
    s.splats[5] = 0x0123456789abcdefull;
    writeStateExr(path, s, resolve(s).mean, {});
    ImageMetadata meta;
    const AccumulationState back = readStateExr(path, meta);
    std::filesystem::remove(path);
    EXPECT_EQ(back.splats, s.splats);
}

TEST(Splats, ACorruptSplatChannelIsRefusedByName) {
    const auto path = std::filesystem::temp_directory_path() / ("pt_bad_splats_" + std::to_string(::getpid()) + ".exr");
    AccumulationState s = state({0, 6}, 1.0f, 0.0f);
    setSplats(s, 0.5, 0.25);
    const AccumulatedImage image = resolve(s);
    writeStateExr(path, s, image.mean, {});
    // Rewrite the file with one splat piece that is not a 22-bit integer.
    std::vector<std::string> names = {"state.sum.R", "state.sum.G", "state.sum.B", "state.sum_lo.R", "state.sum_lo.G",
        "state.sum_lo.B", "state.sum_sq.R", "state.sum_sq.G", "state.sum_sq.B", "state.sum_sq_lo.R",
        "state.sum_sq_lo.G", "state.sum_sq_lo.B", "state.dropped"};
    for (int word = 0; word < int(SPLAT_WORDS_PER_PIXEL); ++word)
        for (int piece = 0; piece < 3; ++piece)
            names.push_back("state.splat." + std::to_string(word) + "." + std::to_string(piece));
    ImageMetadata meta;
    ExrChannels channels = readExrChannels(path, names, &meta);
    channels.channels[13 + 4].values[1] = 0.5f; // state.splat.1.1
    writeExr(path, image.mean, meta, channels.channels);
    try {
        readStateExr(path, meta);
        ADD_FAILURE() << "a corrupt splat channel was accepted";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("state.splat.1.1"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
    std::filesystem::remove(path);
}

TEST(StateFile, ReadingAPlainImageNamesTheMissingChannel) {
    const auto path = std::filesystem::temp_directory_path() / ("pt_plain_" + std::to_string(::getpid()) + ".exr");
    Image plain;
    plain.width = plain.height = 1;
    plain.rgba = {1, 2, 3, 1};
    writeExr(path, plain, {});
    ImageMetadata meta;
    try {
        readStateExr(path, meta);
        ADD_FAILURE() << "a plain image read as a state";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("state.sum.R"), std::string::npos) << e.what();
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
    std::filesystem::remove(path);
}

} // namespace
} // namespace pt
