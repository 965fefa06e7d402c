#include "film/accumulation_state.h"

#include "shared/layout.h"

#include <algorithm>
#include <charconv>
#include <stdexcept>

namespace pt {

std::string SampleRange::describe() const { return std::to_string(begin) + ":" + std::to_string(end); }

SampleRange parseSampleRange(const std::string& text) {
    const auto colon = text.find(':');
    auto number = [&](const char* first, const char* last, uint64_t& value) {
        auto [end, ec] = std::from_chars(first, last, value);
        return ec == std::errc() && end == last && first != last;
    };
    uint64_t a = 0, b = 0;
    if (colon == std::string::npos || !number(text.data(), text.data() + colon, a) ||
        !number(text.data() + colon + 1, text.data() + text.size(), b))
        throw std::runtime_error("sample range '" + text + "' is not A:B (first sample index, one past the last)");
    if (a >= b || b > UINT32_MAX)
        throw std::runtime_error("sample range '" + text + "' is empty or beyond 2^32 (need 0 <= A < B <= 4294967295)");
    return {uint32_t(a), uint32_t(b)};
}

glm::dvec3 AccumulationState::sum(size_t pixel) const {
    const size_t base = ACCUMULATION_VEC4S_PER_PIXEL * pixel;
    return glm::dvec3(sums[base + ACCUM_SUM]) + glm::dvec3(sums[base + ACCUM_SUM_LO]);
}

glm::dvec3 AccumulationState::sumSquares(size_t pixel) const {
    const size_t base = ACCUMULATION_VEC4S_PER_PIXEL * pixel;
    return glm::dvec3(sums[base + ACCUM_SUM_SQUARES]) + glm::dvec3(sums[base + ACCUM_SUM_SQUARES_LO]);
}

uint64_t AccumulationState::dropped(size_t pixel) const {
    return static_cast<uint64_t>(sums[ACCUMULATION_VEC4S_PER_PIXEL * pixel + ACCUM_SUM].w);
}

glm::dvec3 AccumulationState::splatSum(size_t pixel) const {
    if (splats.empty()) return glm::dvec3(0.0);
    const uint64_t* w = &splats[SPLAT_WORDS_PER_PIXEL * pixel + SPLAT_SUM];
    return glm::dvec3(double(w[0]), double(w[1]), double(w[2])) / SPLAT_SUM_SCALE;
}

glm::dvec3 AccumulationState::splatSumSquares(size_t pixel) const {
    if (splats.empty()) return glm::dvec3(0.0);
    const uint64_t* w = &splats[SPLAT_WORDS_PER_PIXEL * pixel + SPLAT_SUM_SQUARES];
    return glm::dvec3(double(w[0]), double(w[1]), double(w[2])) / SPLAT_SQUARE_SCALE;
}

double AccumulationState::totalSamples() const {
    if (!adaptive()) return double(spp) * double(pixels());
    double total = 0;
    for (uint32_t n : pixelSamples) total += n;
    return total;
}

AccumulatedImage resolve(const AccumulationState& state) {
    AccumulatedImage r;
    const size_t pixels = state.pixels();
    r.mean.width = r.varianceOfMean.width = state.width;
    r.mean.height = r.varianceOfMean.height = state.height;
    r.mean.rgba.assign(pixels * 4, 0.0f);
    r.varianceOfMean.rgba.assign(pixels * 4, 0.0f);
    // The light paths: one per sample, so N = totalSamples() of them over the image, and a
    // pixel's splat mean is its splat sum / (N / pixels) (with adaptive sampling too, where
    // pixels' own sample counts differ but the light paths land wherever they land).
    const double lightPaths = state.totalSamples();
    const double m = lightPaths / double(pixels);
    for (size_t i = 0; i < pixels; ++i) {
        const double n = state.samplesOf(i);
        const glm::dvec3 s = state.sum(i);
        const glm::dvec3 s2 = state.sumSquares(i);
        const glm::dvec3 splat = state.splatSum(i);
        const glm::dvec3 splat2 = state.splatSumSquares(i);
        r.droppedSamples += state.dropped(i);
        for (int c = 0; c < 3; ++c) {
            const double mean = n > 0 ? s[c] / n : 0.0;
            // Unbiased sample variance, divided by n for the variance of the mean.
            const double var = n > 1 ? std::max(0.0, (s2[c] / n - mean * mean) * n / (n - 1)) / n : 0.0;
            // Each light path contributes X = pixels x Y where Y is what was splatted, so the
            // mean is sum(Y) / m and the variance of that mean (E[X^2] - mean^2) / N =
            // sum(Y^2) / m^2 - mean^2 / N.
            const double splatMean = m > 0 ? splat[c] / m : 0.0;
            const double splatVar =
                m > 0 ? std::max(0.0, splat2[c] / (m * m) - splatMean * splatMean / lightPaths) : 0.0;
            r.mean.rgba[4 * i + c] = static_cast<float>(mean + splatMean);
            r.varianceOfMean.rgba[4 * i + c] = static_cast<float>(var + splatVar);
        }
        r.mean.rgba[4 * i + 3] = 1.0f;
        r.varianceOfMean.rgba[4 * i + 3] = 1.0f;
    }
    return r;
}

namespace {
// A double rounded to the double-float (hi, lo) the kernel would carry.
void split(double value, float& hi, float& lo) {
    hi = static_cast<float>(value);
    lo = static_cast<float>(value - double(hi));
}
} // namespace

AccumulationState mergeStates(std::vector<AccumulationState> parts) {
    if (parts.empty()) throw std::runtime_error("nothing to merge");
    std::sort(parts.begin(), parts.end(),
        [](const AccumulationState& a, const AccumulationState& b) { return a.samples.begin < b.samples.begin; });
    for (size_t k = 1; k < parts.size(); ++k) {
        if (parts[k].width != parts[0].width || parts[k].height != parts[0].height)
            throw std::runtime_error("parts differ in size (" + std::to_string(parts[0].width) + "x" +
                                     std::to_string(parts[0].height) + " and " + std::to_string(parts[k].width) + "x" +
                                     std::to_string(parts[k].height) + ")");
        if (parts[k].samples.begin < parts[k - 1].samples.end)
            throw std::runtime_error("sample ranges " + parts[k - 1].samples.describe() + " and " +
                                     parts[k].samples.describe() + " overlap");
    }
    for (const AccumulationState& p : parts)
        if (p.adaptive())
            throw std::runtime_error("part " + p.samples.describe() +
                                     " was rendered with adaptive sampling, whose pixels' sample counts differ: "
                                     "parts to merge are rendered with --samples, which samples every pixel alike");
    for (const AccumulationState& p : parts)
        if (p.hasSplats() != parts[0].hasSplats())
            throw std::runtime_error("parts differ in light tracing (some have its splat sums, some do not)");
    AccumulationState merged;
    merged.width = parts[0].width;
    merged.height = parts[0].height;
    merged.samples = {parts.front().samples.begin, parts.back().samples.end};
    for (const AccumulationState& p : parts) merged.spp += p.spp;
    const size_t pixels = merged.pixels();
    merged.sums.assign(pixels * ACCUMULATION_VEC4S_PER_PIXEL, glm::vec4(0.0f));
    for (size_t i = 0; i < pixels; ++i) {
        glm::dvec3 s(0.0), s2(0.0);
        double dropped = 0;
        for (const AccumulationState& p : parts) {
            s += p.sum(i);
            s2 += p.sumSquares(i);
            dropped += double(p.dropped(i));
        }
        glm::vec4* out = &merged.sums[ACCUMULATION_VEC4S_PER_PIXEL * i];
        for (int c = 0; c < 3; ++c) {
            split(s[c], out[ACCUM_SUM][c], out[ACCUM_SUM_LO][c]);
            split(s2[c], out[ACCUM_SUM_SQUARES][c], out[ACCUM_SUM_SQUARES_LO][c]);
        }
        out[ACCUM_SUM].w = static_cast<float>(dropped);
    }
    // Integer sums: exact in any order.
    if (parts[0].hasSplats()) {
        merged.splats.assign(pixels * SPLAT_WORDS_PER_PIXEL, 0);
        for (const AccumulationState& p : parts)
            for (size_t k = 0; k < merged.splats.size(); ++k) merged.splats[k] += p.splats[k];
    }
    return merged;
}

std::vector<SampleRange> findGaps(std::vector<SampleRange> ranges) {
    std::sort(ranges.begin(), ranges.end(), [](SampleRange a, SampleRange b) { return a.begin < b.begin; });
    std::vector<SampleRange> gaps;
    for (size_t k = 1; k < ranges.size(); ++k)
        if (ranges[k].begin > ranges[k - 1].end) gaps.push_back({ranges[k - 1].end, ranges[k].begin});
    return gaps;
}

uint64_t totalSamples(const std::vector<SampleRange>& ranges) {
    uint64_t total = 0;
    for (SampleRange r : ranges) total += r.count();
    return total;
}

} // namespace pt
