#include "film/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace pt {
namespace {

std::string sizeText(const Image& im) { return std::to_string(im.width) + "x" + std::to_string(im.height); }

// Also validates the buffers themselves, so the loops below may index freely.
void checkSameSize(const Image& a, const Image& b, const char* what) {
    auto valid = [](const Image& im) {
        return im.width > 0 && im.height > 0 && im.rgba.size() == static_cast<std::size_t>(im.width) * im.height * 4;
    };
    if (!valid(a) || !valid(b))
        throw std::invalid_argument(
            std::string(what) + ": empty image or pixel buffer size " + "does not match width x height");
    if (a.width != b.width || a.height != b.height)
        throw std::invalid_argument(
            std::string(what) + ": image size mismatch (" + sizeText(a) + " vs " + sizeText(b) + ")");
}

// Mean over pixels and RGB of f(x, ref); accumulates in double because a
// 4K image has ~25M terms and float sums would lose the small ones.
template <class F>
double meanOverRgb(const Image& x, const Image& ref, F f) {
    double sum = 0;
    for (std::size_t i = 0; i < x.rgba.size(); i += 4)
        for (int c = 0; c < 3; ++c) sum += f(double(x.rgba[i + c]), double(ref.rgba[i + c]));
    return sum / (double(x.rgba.size() / 4) * 3.0);
}

} // namespace

double relMse(const Image& x, const Image& ref) {
    checkSameSize(x, ref, "relMse");
    return meanOverRgb(x, ref, [](double v, double r) {
        const double d = v - r;
        return d * d / (r * r + 0.01);
    });
}

Image referenceAtSize(const Image& ref, int width, int height, const std::string& name) {
    if (ref.width == width && ref.height == height) return ref;
    if (width < 1 || height < 1 || ref.width % width != 0 || ref.height % height != 0)
        throw std::runtime_error(name + ": reference is " + std::to_string(ref.width) + "x" +
                                 std::to_string(ref.height) + " but the render is " + std::to_string(width) + "x" +
                                 std::to_string(height) + " (nor a whole multiple of it, to be box-filtered down)");
    const int fx = ref.width / width, fy = ref.height / height;
    Image out;
    out.width = width;
    out.height = height;
    out.rgba.assign(size_t(width) * height * 4, 0.0f);
    const double norm = 1.0 / (double(fx) * fy);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            double sum[4] = {0, 0, 0, 0};
            for (int j = 0; j < fy; ++j)
                for (int i = 0; i < fx; ++i) {
                    const float* p = ref.at(x * fx + i, y * fy + j);
                    for (int c = 0; c < 4; ++c) sum[c] += p[c];
                }
            float* o = out.at(x, y);
            for (int c = 0; c < 4; ++c) o[c] = float(sum[c] * norm);
        }
    return out;
}

double estimatedRelMse(const Image& mean, const Image& varianceOfMean) {
    checkSameSize(mean, varianceOfMean, "estimatedRelMse");
    // Each pixel's variance of the mean over the square of the mean of its 8 neighbours (those
    // inside the image). The pixel's own mean would be correlated with its variance: a pixel
    // that caught a rare bright path (a caustic) has a huge variance and a huge mean, and
    // their ratio says "fine" where the error is large. Neighbours' samples are independent
    // of the pixel's and, images being smooth, estimate its value nearly as well.
    double total = 0;
    for (int y = 0; y < mean.height; ++y)
        for (int x = 0; x < mean.width; ++x)
            for (int c = 0; c < 3; ++c) {
                double sum = 0;
                int count = 0;
                for (int ny = std::max(0, y - 1); ny <= std::min(mean.height - 1, y + 1); ++ny)
                    for (int nx = std::max(0, x - 1); nx <= std::min(mean.width - 1, x + 1); ++nx)
                        if (nx != x || ny != y) {
                            sum += mean.at(nx, ny)[c];
                            ++count;
                        }
                const double m = count > 0 ? sum / count : mean.at(x, y)[c]; // a 1x1 image has no neighbours
                total += varianceOfMean.at(x, y)[c] / (m * m + 0.01);
            }
    return total / (3.0 * mean.width * mean.height);
}

double mse(const Image& x, const Image& ref) {
    checkSameSize(x, ref, "mse");
    return meanOverRgb(x, ref, [](double v, double r) { return (v - r) * (v - r); });
}

BlockStats blockStats(const Image& mean, const Image* varOfMean, int blockSize) {
    if (varOfMean)
        checkSameSize(mean, *varOfMean, "blockStats");
    else
        checkSameSize(mean, mean, "blockStats");
    if (blockSize < 1 || blockSize > mean.width || blockSize > mean.height)
        throw std::invalid_argument(
            "blockStats: block size " + std::to_string(blockSize) + " invalid for a " + sizeText(mean) + " image");

    BlockStats s;
    s.blockSize = blockSize;
    s.blocksX = mean.width / blockSize;
    s.blocksY = mean.height / blockSize;
    const std::size_t cells = static_cast<std::size_t>(s.blocksX) * s.blocksY * 3;
    s.mean.assign(cells, 0.0);
    if (varOfMean) s.varOfMean.assign(cells, 0.0);

    const double n = double(blockSize) * blockSize;
    for (int by = 0; by < s.blocksY; ++by) {
        for (int bx = 0; bx < s.blocksX; ++bx) {
            double m[3] = {0, 0, 0}, v[3] = {0, 0, 0};
            for (int y = by * blockSize; y < (by + 1) * blockSize; ++y) {
                for (int x = bx * blockSize; x < (bx + 1) * blockSize; ++x) {
                    const float* p = mean.at(x, y);
                    for (int c = 0; c < 3; ++c) m[c] += p[c];
                    if (varOfMean) {
                        const float* q = varOfMean->at(x, y);
                        for (int c = 0; c < 3; ++c) v[c] += q[c];
                    }
                }
            }
            const std::size_t base = (static_cast<std::size_t>(by) * s.blocksX + bx) * 3;
            for (int c = 0; c < 3; ++c) {
                s.mean[base + c] = m[c] / n;
                // Var(mean of n independent pixels) = sum of variances / n^2.
                if (varOfMean) s.varOfMean[base + c] = v[c] / (n * n);
            }
        }
    }
    return s;
}

AgreementResult compareBlocks(const BlockStats& a, const BlockStats& b) {
    if (a.blocksX != b.blocksX || a.blocksY != b.blocksY || a.blockSize != b.blockSize ||
        a.mean.size() != b.mean.size())
        throw std::invalid_argument("compareBlocks: block layouts differ");
    if (a.varOfMean.empty() && b.varOfMean.empty())
        throw std::invalid_argument("compareBlocks: neither side has a variance estimate");
    if ((!a.varOfMean.empty() && a.varOfMean.size() != a.mean.size()) ||
        (!b.varOfMean.empty() && b.varOfMean.size() != b.mean.size()))
        throw std::invalid_argument("compareBlocks: variance and mean sizes differ");

    // Guards against 0/0 where both variances are exactly zero (e.g. a
    // constant region) while staying far below any real block variance.
    constexpr double kTiny = 1e-30;
    constexpr double kZeroMean = 1e-12;
    const double inf = std::numeric_limits<double>::infinity();

    AgreementResult r;
    double sumZ2 = 0, sumZ = 0, sumRel = 0;
    for (std::size_t i = 0; i < a.mean.size(); ++i) {
        const double ma = a.mean[i], mb = b.mean[i];
        if (std::abs(ma) < kZeroMean && std::abs(mb) < kZeroMean) continue;
        const double va = a.varOfMean.empty() ? 0.0 : a.varOfMean[i];
        const double vb = b.varOfMean.empty() ? 0.0 : b.varOfMean[i];
        double z = (ma - mb) / std::sqrt(va + vb + kTiny);
        // NaN would silently pass "chi2 < threshold" checks; make it fail.
        if (!std::isfinite(z)) z = inf;
        sumZ2 += z * z;
        sumZ += z;
        r.maxAbsZ = std::max(r.maxAbsZ, std::abs(z));
        const double denom = 0.5 * (std::abs(ma) + std::abs(mb));
        sumRel += std::isfinite(ma) && std::isfinite(mb) ? std::abs(ma - mb) / denom : inf;
        ++r.dof;
    }
    if (r.dof > 0) {
        r.chi2PerDof = sumZ2 / r.dof;
        r.meanZ = sumZ / r.dof;
        r.meanRelDiff = sumRel / r.dof;
    }
    return r;
}

} // namespace pt
