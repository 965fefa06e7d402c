// BVH build benchmark: builds the binned SAH BVH over procedurally generated triangles several
// times per thread count and prints the median build time, M triangles/s, SAH cost, node count
// and depth (one Markdown table row each). Built when PT_BUILD_BENCH is on (the default).
//
//   pt_bvh_bench [--triangles N] [--repeats R] [--threads 1,2] [--mesh soup|surface] [--bins B]
//
// soup:    N small random triangles with centres uniform in the unit cube (as the host test).
// surface: a closed, bumpy sphere tessellated into about N triangles: the shape of a scanned
//          mesh (connected, locally flat, very uneven density along the view of any axis).
#include "accel/bvh.h"
#include "accel/wide_bvh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

struct Tri {
    glm::vec3 v0, v1, v2;
};

std::vector<Tri> soup(size_t n) {
    std::mt19937 rng(71);
    std::uniform_real_distribution<float> u(0.0f, 1.0f), o(-0.01f, 0.01f);
    std::vector<Tri> tris(n);
    for (Tri& t : tris) {
        const glm::vec3 c(u(rng), u(rng), u(rng));
        t.v0 = c + glm::vec3(o(rng), o(rng), o(rng));
        t.v1 = c + glm::vec3(o(rng), o(rng), o(rng));
        t.v2 = c + glm::vec3(o(rng), o(rng), o(rng));
    }
    return tris;
}

// A latitude-longitude sphere of radius 1 displaced by a few sine octaves (2 * rings * segments
// triangles, segments = 2 * rings).
std::vector<Tri> surface(size_t n) {
    const int rings = std::max(4, int(std::sqrt(double(n) / 4.0)));
    const int segments = 2 * rings;
    const auto point = [&](int r, int s) {
        const float theta = float(M_PI) * float(r) / float(rings);
        const float phi = 2.0f * float(M_PI) * float(s % segments) / float(segments);
        const glm::vec3 d(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
        const float bump = 0.15f * std::sin(7.0f * d.x) * std::sin(5.0f * d.y + 1.0f) +
                           0.05f * std::sin(23.0f * d.z + 11.0f * d.x) + 0.01f * std::sin(97.0f * d.y);
        return d * (1.0f + bump);
    };
    std::vector<Tri> tris;
    tris.reserve(size_t(2) * rings * segments);
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const glm::vec3 a = point(r, s), b = point(r + 1, s), c = point(r + 1, s + 1), d = point(r, s + 1);
            tris.push_back({a, b, c});
            tris.push_back({a, c, d});
        }
    return tris;
}

// CPU seconds of the whole process (all threads): on a shared machine the single-thread figure
// tracks the work done much more steadily than the wall clock does.
double processCpuSeconds() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

std::vector<int> parseList(const std::string& s) {
    std::vector<int> out;
    std::stringstream ss(s);
    for (std::string item; std::getline(ss, item, ',');) out.push_back(std::stoi(item));
    return out;
}

// How full the four-wide tree the kernel traverses is: slots used per node, primitives per leaf.
// How full the four-wide tree the kernel traverses is: slots used per node, primitives per leaf;
// and its SAH cost under the collapse's cost model (relative to the root's area).
void printWideTree(const pt::WideBvh& wide, const pt::WideCollapseOptions& costs) {
    size_t slots = 0, leaves = 0, primitives = 0;
    double cost = 0.0;
    const double rootArea = std::max(double(pt::wideNodeBounds(wide.nodes.at(0)).surfaceArea()), 1e-30);
    cost += costs.nodeCost;
    for (const auto& node : wide.nodes)
        for (int i = 0; i < 4; ++i) {
            const uint32_t word = node.child[i];
            if (word == BVH4_EMPTY) continue;
            ++slots;
            pt::Aabb box;
            box.grow(glm::vec3(node.loX[i], node.loY[i], node.loZ[i]));
            box.grow(glm::vec3(node.hiX[i], node.hiY[i], node.hiZ[i]));
            const double area = double(box.surfaceArea()) / rootArea;
            if ((word & BVH4_LEAF_BIT) != 0u) {
                ++leaves;
                const uint32_t count = ((word >> BVH4_COUNT_SHIFT) & 15u) + 1u;
                primitives += count;
                cost += area * (costs.leafCost + costs.primitiveCost * double(count));
            } else
                cost += area * costs.nodeCost;
        }
    const double nodes = double(std::max<size_t>(wide.nodes.size(), 1));
    std::printf(
        "\nfour-wide: %zu nodes, depth %d, %.2f children a node, %zu leaves of %.2f primitives, SAH cost %.2f\n",
        wide.nodes.size(), wide.depth, double(slots) / nodes, leaves,
        double(primitives) / double(std::max<size_t>(leaves, 1)), cost);
}

int run(int argc, char** argv) {
    size_t triangles = 1000000;
    int repeats = 5;
    std::vector<int> threads{1, 2};
    std::string mesh = "soup";
    int bins = pt::BvhBuildOptions{}.bins;
    int leaf = pt::BvhBuildOptions{}.maxLeafSize;
    pt::WideCollapseOptions collapse;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (i + 1 >= argc) throw std::runtime_error(a + ": missing value");
        const std::string v = argv[++i];
        if (a == "--triangles")
            triangles = std::stoul(v);
        else if (a == "--repeats")
            repeats = std::max(1, std::stoi(v));
        else if (a == "--threads")
            threads = parseList(v);
        else if (a == "--mesh")
            mesh = v;
        else if (a == "--bins")
            bins = std::stoi(v);
        else if (a == "--leaf")
            leaf = std::stoi(v);
        else if (a == "--wide-leaf")
            collapse.maxLeafSize = std::stoi(v);
        else if (a == "--leaf-cost")
            collapse.leafCost = std::stof(v);
        else if (a == "--primitive-cost")
            collapse.primitiveCost = std::stof(v);
        else
            throw std::runtime_error(a + ": unknown option");
    }
    if (mesh != "soup" && mesh != "surface") throw std::runtime_error(mesh + ": --mesh is soup or surface");
    const std::vector<Tri> tris = mesh == "soup" ? soup(triangles) : surface(triangles);
    std::vector<pt::Aabb> bounds(tris.size());
    for (size_t i = 0; i < tris.size(); ++i) {
        bounds[i].grow(tris[i].v0);
        bounds[i].grow(tris[i].v1);
        bounds[i].grow(tris[i].v2);
    }
    std::printf("| mesh | triangles | threads | median s (min-max of %d) | M triangles/s | CPU s | SAH cost | nodes | "
                "depth |\n",
        repeats);
    std::printf("|---|---|---|---|---|---|---|---|---|\n");
    for (int t : threads) {
        pt::BvhBuildOptions opt;
        opt.threads = t;
        opt.bins = bins;
        opt.maxLeafSize = leaf;
        std::vector<double> seconds, cpu;
        pt::Bvh bvh;
        for (int r = 0; r < repeats; ++r) {
            bvh = pt::Bvh{}; // free the previous tree outside the timed region
            const double cpuStart = processCpuSeconds();
            bvh = pt::buildBvh(bounds, opt);
            cpu.push_back(processCpuSeconds() - cpuStart);
            seconds.push_back(bvh.buildSeconds);
        }
        std::sort(seconds.begin(), seconds.end());
        std::sort(cpu.begin(), cpu.end());
        const double median = seconds[seconds.size() / 2];
        std::printf("| %s | %zu | %d | %.3f (%.3f-%.3f) | %.2f | %.3f | %.2f | %zu | %d |\n", mesh.c_str(), tris.size(),
            t, median, seconds.front(), seconds.back(), 1e-6 * double(tris.size()) / median, cpu[cpu.size() / 2],
            bvh.sahCost, bvh.nodes.size(), bvh.maxDepth);
        if (t == threads.back()) printWideTree(pt::collapseToWide(bvh, collapse), collapse);
    }
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "pt_bvh_bench: %s\n", e.what());
        return 2;
    }
}
