#include "lights/light_tree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace pt {
namespace {

constexpr double kPi = std::numbers::pi;
// Spots: the tree's emission spread is their falloff band; at least this many radians, so that
// cos(theta_e) stays below 1 in float and a hard-edged spot keeps its importance inside its cone.
constexpr double kMinSpotBand = 0.01;
constexpr int kBuckets = 12; // per axis, as pbrt-v4

void growBox(LightBounds& b, glm::vec3 p) {
    b.lo = glm::min(b.lo, p);
    b.hi = glm::max(b.hi, p);
}

// A moving light's box covers it at both ends of its translation (motion is a translation).
void addMotion(LightBounds& b, const glm::vec3& translation) {
    const glm::vec3 lo = b.lo, hi = b.hi;
    growBox(b, lo + translation);
    growBox(b, hi + translation);
}

glm::dvec3 rotateAbout(glm::dvec3 v, glm::dvec3 k, double angle) { // Rodrigues, k unit
    return v * std::cos(angle) + glm::cross(k, v) * std::sin(angle) + k * glm::dot(k, v) * (1.0 - std::cos(angle));
}

double safeAcos(double c) { return std::acos(std::clamp(c, -1.0, 1.0)); }

LightBounds unite(const LightBounds& a, const LightBounds& b) {
    if (!(a.phi > 0)) return b;
    if (!(b.phi > 0)) return a;
    LightBounds u;
    u.lo = glm::min(a.lo, b.lo);
    u.hi = glm::max(a.hi, b.hi);
    u.phi = a.phi + b.phi;
    coneUnion(a.axis, a.cosThetaO, b.axis, b.cosThetaO, u.axis, u.cosThetaO);
    u.cosThetaE = std::min(a.cosThetaE, b.cosThetaE);
    u.twoSided = a.twoSided || b.twoSided;
    return u;
}

// pbrt-v4's M_Omega: the measure of the directions the lights may emit into, over the cone of
// normals widened by the emission spread.
double orientationMeasure(const LightBounds& b) {
    const double thetaO = safeAcos(b.cosThetaO), thetaE = safeAcos(b.cosThetaE);
    const double thetaW = std::min(thetaO + thetaE, kPi), sinO = std::sin(thetaO);
    return 2 * kPi * (1 - b.cosThetaO) +
           kPi / 2 * (2 * thetaW * sinO - std::cos(thetaO - 2 * thetaW) - 2 * thetaO * sinO + b.cosThetaO);
}

double surfaceArea(const LightBounds& b) {
    const glm::dvec3 d = glm::dvec3(b.hi) - glm::dvec3(b.lo);
    return 2 * (d.x * d.y + d.y * d.z + d.z * d.x);
}

// The cost of a child of a split along `axis` of a node with centroid extent `extent`: power
// times orientation measure times area, with pbrt-v4's factor against thin slabs.
double splitCost(const LightBounds& b, const glm::dvec3& extent, int axis) {
    const double longest = std::max({extent.x, extent.y, extent.z});
    return longest / extent[axis] * b.phi * orientationMeasure(b) * surfaceArea(b);
}

struct Item {
    LightBounds bounds;
    glm::vec3 centroid;
    uint32_t light;
};

class Builder {
public:
    Builder(std::vector<Item>& items, LightTree& tree) : items_(items), tree_(tree) {}

    uint32_t build(size_t begin, size_t end, int depth, uint64_t trail) {
        const uint32_t index = static_cast<uint32_t>(tree_.nodes.size());
        tree_.nodes.emplace_back();
        tree_.depth = std::max(tree_.depth, depth);
        LightBounds bounds;
        for (size_t i = begin; i < end; ++i) bounds = unite(bounds, items_[i].bounds);
        if (end - begin == 1) {
            store(index, bounds, items_[begin].light, LIGHT_NODE_LEAF);
            tree_.trails[items_[begin].light] = trail;
            return index;
        }
        const size_t mid = split(begin, end, depth);
        build(begin, mid, depth + 1, trail);
        const uint32_t second = build(mid, end, depth + 1, trail | (uint64_t{1} << depth));
        store(index, bounds, second, 0u);
        return index;
    }

private:
    void store(uint32_t index, const LightBounds& b, uint32_t child, uint32_t flags) {
        gpu::GpuLightTreeNode& n = tree_.nodes[index];
        n.boundsMin = b.lo;
        n.boundsMax = b.hi;
        n.phi = static_cast<float>(b.phi);
        n.axis = b.axis;
        n.cosThetaO = b.cosThetaO;
        n.sinThetaO = static_cast<float>(std::sqrt(std::max(0.0, 1.0 - double(b.cosThetaO) * b.cosThetaO)));
        n.cosThetaE = b.cosThetaE;
        n.child = child;
        n.flags = flags | (b.twoSided ? LIGHT_NODE_TWO_SIDED : 0u);
    }

    // Where to split [begin, end): the cheapest of kBuckets - 1 planes per axis over the
    // centroids (pbrt-v4's cost), or the median along the longest axis where no plane separates
    // the lights or the trail would run out of bits.
    size_t split(size_t begin, size_t end, int depth) {
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
        for (size_t i = begin; i < end; ++i) {
            lo = glm::min(lo, items_[i].centroid);
            hi = glm::max(hi, items_[i].centroid);
        }
        const glm::dvec3 extent = glm::dvec3(hi) - glm::dvec3(lo);
        int bestAxis = -1, bestBucket = -1;
        if (depth < kLightTreeCountSplitDepth) {
            double bestCost = std::numeric_limits<double>::infinity();
            for (int axis = 0; axis < 3; ++axis) {
                if (!(extent[axis] > 0)) continue;
                std::array<LightBounds, kBuckets> buckets{};
                for (size_t i = begin; i < end; ++i) {
                    const int b = bucketOf(items_[i].centroid[axis], lo[axis], extent[axis]);
                    buckets[b] = unite(buckets[b], items_[i].bounds);
                }
                for (int planeAfter = 0; planeAfter < kBuckets - 1; ++planeAfter) {
                    LightBounds below, above;
                    for (int b = 0; b <= planeAfter; ++b) below = unite(below, buckets[b]);
                    for (int b = planeAfter + 1; b < kBuckets; ++b) above = unite(above, buckets[b]);
                    if (!(below.phi > 0) || !(above.phi > 0)) continue;
                    const double cost = splitCost(below, extent, axis) + splitCost(above, extent, axis);
                    if (cost < bestCost) {
                        bestCost = cost;
                        bestAxis = axis;
                        bestBucket = planeAfter;
                    }
                }
            }
        }
        if (bestAxis >= 0) {
            auto first = items_.begin() + static_cast<std::ptrdiff_t>(begin);
            auto last = items_.begin() + static_cast<std::ptrdiff_t>(end);
            auto middle = std::partition(first, last, [&](const Item& item) {
                return bucketOf(item.centroid[bestAxis], lo[bestAxis], extent[bestAxis]) <= bestBucket;
            });
            const size_t mid = static_cast<size_t>(middle - items_.begin());
            if (mid > begin && mid < end) return mid;
        }
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        const size_t mid = begin + (end - begin) / 2;
        std::nth_element(items_.begin() + static_cast<std::ptrdiff_t>(begin),
            items_.begin() + static_cast<std::ptrdiff_t>(mid), items_.begin() + static_cast<std::ptrdiff_t>(end),
            [axis](const Item& a, const Item& b) { return a.centroid[axis] < b.centroid[axis]; });
        return mid;
    }

    static int bucketOf(float c, float lo, double extent) {
        const int b = static_cast<int>(kBuckets * ((double(c) - lo) / extent));
        return std::clamp(b, 0, kBuckets - 1);
    }

    std::vector<Item>& items_;
    LightTree& tree_;
};

} // namespace

void coneUnion(glm::vec3 axisA, float cosA, glm::vec3 axisB, float cosB, glm::vec3& axis, float& cosTheta) {
    const double thetaA = safeAcos(cosA), thetaB = safeAcos(cosB);
    const glm::dvec3 a = glm::normalize(glm::dvec3(axisA)), b = glm::normalize(glm::dvec3(axisB));
    const double thetaD = safeAcos(glm::dot(a, b));
    if (std::min(thetaD + thetaB, kPi) <= thetaA) {
        axis = axisA;
        cosTheta = cosA;
        return;
    }
    if (std::min(thetaD + thetaA, kPi) <= thetaB) {
        axis = axisB;
        cosTheta = cosB;
        return;
    }
    const double thetaO = (thetaA + thetaD + thetaB) / 2;
    const glm::dvec3 k = glm::cross(a, b);
    axis = glm::vec3(0, 0, 1);
    cosTheta = -1.0f; // the whole sphere
    if (thetaO >= kPi || !(glm::dot(k, k) > 0)) return;
    axis = glm::vec3(glm::normalize(rotateAbout(a, glm::normalize(k), thetaO - thetaA)));
    // Rounded down, so the cone still holds both (float's cos of a wide angle may round up).
    cosTheta = std::nextafter(static_cast<float>(std::cos(thetaO)), -1.0f);
}

std::vector<LightBounds> lightBoundsOf(std::span<const gpu::GpuLight> lights, std::span<const double> power,
    std::span<const gpu::GpuTriangle> triangles, std::span<const gpu::GpuSphere> spheres,
    std::span<const gpu::GpuMaterial> materials, std::span<const glm::vec4> motions) {
    std::vector<LightBounds> out(lights.size());
    for (size_t i = 0; i < lights.size(); ++i) {
        const gpu::GpuLight& light = lights[i];
        LightBounds& b = out[i];
        b.phi = power[i];
        b.cosThetaE = 0.0f; // a hemisphere about the normal (Lambertian emitters, lights without one)
        b.cosThetaO = -1.0f;
        b.lo = b.hi = light.position;
        if (light.type == LIGHT_TRIANGLE) {
            const gpu::GpuTriangle& t = triangles[light.primitive];
            b.lo = b.hi = t.p0;
            growBox(b, t.p1);
            growBox(b, t.p2);
            if ((t.flags & TRIANGLE_FLAG_MOVING) != 0u)
                addMotion(b, glm::vec3(motions[t.flags >> TRIANGLE_MOTION_SHIFT]));
            b.axis = glm::vec3(glm::normalize(glm::cross(glm::dvec3(t.p1 - t.p0), glm::dvec3(t.p2 - t.p0))));
            b.cosThetaO = 1.0f;
            b.twoSided = (materials[t.materialIndex].flags & MATERIAL_FLAG_DOUBLE_SIDED) != 0u;
        } else if (light.type == LIGHT_SPHERE) {
            const gpu::GpuSphere& s = spheres[light.primitive];
            glm::vec3 centre, reach;
            for (int r = 0; r < 3; ++r) {
                const glm::vec4 row = s.objectToWorld[r];
                centre[r] = row.w;
                reach[r] = std::sqrt(row.x * row.x + row.y * row.y + row.z * row.z) * (1.0f + 1e-6f);
            }
            b.lo = centre - reach;
            b.hi = centre + reach;
            if (s.motion != NO_MOTION) addMotion(b, glm::vec3(motions[s.motion]));
        } else if (light.type == LIGHT_SPOT) {
            b.axis = light.direction;
            b.cosThetaO = light.cosFalloff;
            const double band = safeAcos(light.cosCoverage) - safeAcos(light.cosFalloff);
            b.cosThetaE = static_cast<float>(std::cos(std::max(band, kMinSpotBand)));
        } else if (light.type == LIGHT_SQUARE) {
            const glm::vec3 reach(0.7072f * light.radius);
            b.lo = light.position - reach;
            b.hi = light.position + reach;
            b.axis = light.direction;
            b.cosThetaO = 1.0f;
            b.twoSided = true;
        } else if (light.type != LIGHT_POINT) {
            b.phi = 0; // at infinity: not in the tree
        }
        const bool finiteBox = std::isfinite(b.lo.x + b.lo.y + b.lo.z + b.hi.x + b.hi.y + b.hi.z);
        if (!std::isfinite(b.phi) || !finiteBox) b.phi = 0;
    }
    return out;
}

LightTree buildLightTree(std::span<const LightBounds> bounds, float share) {
    LightTree tree;
    tree.trails.assign(bounds.size(), 0);
    tree.share = share;
    std::vector<Item> items;
    double total = 0;
    for (uint32_t i = 0; i < bounds.size(); ++i)
        if (bounds[i].phi > 0) {
            items.push_back({bounds[i], 0.5f * (bounds[i].lo + bounds[i].hi), i});
            total += bounds[i].phi;
        }
    if (items.size() < 2) return LightTree{};
    for (Item& item : items) item.bounds.phi /= total; // in float on the device: keep it near 1
    tree.nodes.reserve(2 * items.size() - 1);
    Builder(items, tree).build(0, items.size(), 0, 0);
    return tree;
}

} // namespace pt
