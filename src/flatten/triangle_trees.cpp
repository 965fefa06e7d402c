#include "flatten/triangle_trees.h"

#include <algorithm>
#include <stdexcept>

namespace pt {
namespace {

// Whether any-hit traversal must test this material's alpha (glTF MASK and BLEND).
bool cutsOut(const Material& m) {
    if (m.alphaMode == Material::AlphaMode::Opaque) return false;
    if (m.baseColorTexture) return true;
    return m.alphaMode == Material::AlphaMode::Mask ? m.opacity < m.alphaCutoff : m.opacity < 1.0f;
}

bool needsTangents(const Material& m) { return m.normalTexture.has_value() || m.anisotropy > 0.0f; }

// a[i] = a_before[order[i]] for each array (tangents may be empty), in place: each cycle of the
// permutation is followed once, with one bit per element to mark what is placed, so no second
// copy of the arrays is made.
void applyOrderInPlace(const std::vector<uint32_t>& order, TriangleSet& set) {
    auto& triangles = set.triangles;
    auto& shading = set.shading;
    auto& tangents = set.tangents;
    const bool withTangents = !tangents.empty();
    std::vector<bool> placed(order.size(), false);
    for (size_t start = 0; start < order.size(); ++start) {
        if (placed[start]) continue;
        const gpu::GpuTriangle firstTriangle = triangles[start];
        const gpu::GpuTriangleShading firstShading = shading[start];
        const gpu::GpuTriangleTangents firstTangents = withTangents ? tangents[start] : gpu::GpuTriangleTangents{};
        size_t to = start;
        for (;;) {
            placed[to] = true;
            const size_t from = order[to];
            if (from == start) break;
            triangles[to] = triangles[from];
            shading[to] = shading[from];
            if (withTangents) tangents[to] = tangents[from];
            to = from;
        }
        triangles[to] = firstTriangle;
        shading[to] = firstShading;
        if (withTangents) tangents[to] = firstTangents;
    }
}

template <class T>
void appendAndRelease(std::vector<T>& to, std::vector<T>& from) {
    if (to.empty())
        to = std::move(from);
    else
        to.insert(to.end(), from.begin(), from.end());
    std::vector<T>().swap(from);
}

// A child word moved with its tree: inner children by the nodes before it, leaves by the
// triangles before it.
uint32_t offsetChild(uint32_t child, uint32_t nodeBase, uint32_t triangleBase, const std::string& what) {
    if (child == BVH4_EMPTY) return child;
    if ((child & BVH4_LEAF_BIT) == 0) {
        if (uint64_t(child) + nodeBase >= BVH4_FIRST_MASK)
            throw std::length_error(what + ": the scene's trees hold more than 2^27 nodes");
        return child + nodeBase;
    }
    const uint32_t first = (child & BVH4_FIRST_MASK) + triangleBase;
    const uint32_t count = ((child >> BVH4_COUNT_SHIFT) & 15u) + 1u;
    if (uint64_t(first) + count > uint64_t(BVH4_FIRST_MASK) + 1)
        throw std::length_error(what + ": the scene holds more than 2^27 distinct triangles");
    return (child & ~BVH4_FIRST_MASK) | first;
}

} // namespace

bool isFinite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

uint32_t motionIndex(const glm::vec3& motion, FlatScene& flat) {
    if (motion == glm::vec3(0.0f) || !isFinite(motion)) return NO_MOTION;
    if (flat.motions.size() >= (1u << (32 - TRIANGLE_MOTION_SHIFT)))
        throw std::runtime_error("more moving objects than the motion table holds");
    flat.motions.emplace_back(motion, 0.0f);
    return static_cast<uint32_t>(flat.motions.size() - 1);
}

bool sceneKeepsTangents(const Scene& scene) {
    auto material = [&](uint32_t i) -> const Material* {
        return i < scene.materials.size() ? &scene.materials[i] : nullptr;
    };
    for (const Mesh& m : scene.meshes)
        if (!m.tangents.empty() && material(m.material) && needsTangents(*material(m.material))) return true;
    for (const SharedMesh& shared : scene.sharedMeshes)
        for (const Mesh& m : shared.parts)
            if (!m.tangents.empty()) return true; // an instance may give it any material: keep them
    return false;
}

WideBvh gpuNodes(const Bvh& bvh, const std::string& what) {
    WideBvh wide = collapseToWide(bvh);
    if (wide.stackNeed > TRAVERSAL_STACK_SIZE)
        throw std::runtime_error(what + " needs " + std::to_string(wide.stackNeed) +
                                 " traversal stack entries; the kernel has " + std::to_string(TRAVERSAL_STACK_SIZE));
    return wide;
}

void gatherTriangles(const Scene& scene, const Mesh& mesh, uint32_t materialIndex, const glm::vec3& motionBy,
    bool keepTangents, FlatScene& flat, TriangleSet& set) {
    if (materialIndex >= scene.materials.size())
        throw std::runtime_error(scene.source + ": mesh '" + mesh.name + "' uses a material that does not exist");
    const Material& material = scene.materials[materialIndex];
    const uint32_t motion = motionIndex(motionBy, flat);
    const bool alphaTested = cutsOut(material);
    const bool tangentFrame = !mesh.tangents.empty() && needsTangents(material);
    for (const glm::uvec3& t : mesh.triangles) {
        gpu::GpuTriangle tri{};
        tri.p0 = mesh.positions.at(t.x);
        tri.p1 = mesh.positions.at(t.y);
        tri.p2 = mesh.positions.at(t.z);
        // Zero-area triangles can never be hit and would only cost traversal time (and break
        // light sampling if emissive).
        const glm::vec3 n = glm::cross(tri.p1 - tri.p0, tri.p2 - tri.p0);
        if (!isFinite(n) || glm::dot(n, n) == 0.0f || !isFinite(tri.p0) || !isFinite(tri.p1) || !isFinite(tri.p2)) {
            flat.degenerateTriangles++;
            continue;
        }
        tri.materialIndex = materialIndex;
        tri.lightIndex = NO_LIGHT;
        if (alphaTested) tri.flags |= TRIANGLE_FLAG_ALPHA_TESTED;
        gpu::GpuTriangleShading sh{};
        if (!mesh.normals.empty()) {
            sh.n0 = mesh.normals[t.x];
            sh.n1 = mesh.normals[t.y];
            sh.n2 = mesh.normals[t.z];
            // Zero normals mark invalid input (see the loaders): use the geometric normal.
            if (sh.n0 != glm::vec3(0.0f) && sh.n1 != glm::vec3(0.0f) && sh.n2 != glm::vec3(0.0f))
                tri.flags |= TRIANGLE_FLAG_SHADING_NORMALS;
        }
        if (!mesh.uvs.empty()) {
            sh.u0 = mesh.uvs[t.x].x;
            sh.u1 = mesh.uvs[t.y].x;
            sh.u2 = mesh.uvs[t.z].x;
            sh.v = glm::vec3(mesh.uvs[t.x].y, mesh.uvs[t.y].y, mesh.uvs[t.z].y);
        }
        Aabb box;
        box.grow(tri.p0);
        box.grow(tri.p1);
        box.grow(tri.p2);
        if (motion != NO_MOTION) {
            tri.flags |= TRIANGLE_FLAG_MOVING | (motion << TRIANGLE_MOTION_SHIFT);
            Aabb moved; // swept over the shutter interval
            moved.grow(box.lo + motionBy);
            moved.grow(box.hi + motionBy);
            box.grow(moved);
        }
        if (keepTangents) {
            gpu::GpuTriangleTangents tg{};
            if (!mesh.tangents.empty()) {
                tg = {mesh.tangents[t.x], mesh.tangents[t.y], mesh.tangents[t.z]};
                // Zero tangents mark invalid input: fall back to the triangle's own frame.
                if (tg.t0.w != 0.0f && tg.t1.w != 0.0f && tg.t2.w != 0.0f && tangentFrame)
                    tri.flags |= TRIANGLE_FLAG_TANGENTS;
            }
            set.tangents.push_back(tg);
        }
        set.triangles.push_back(tri);
        set.shading.push_back(sh);
        set.bounds.push_back(box);
    }
}

AppendedTree appendTriangleTree(
    TriangleSet& set, const BvhBuildOptions& options, const std::string& what, FlatScene& flat) {
    AppendedTree tree;
    tree.root = static_cast<uint32_t>(flat.nodes.size());
    tree.firstTriangle = static_cast<uint32_t>(flat.triangles.size());
    tree.triangleCount = static_cast<uint32_t>(set.triangles.size());
    if (set.triangles.empty()) return tree;
    // The peak of a big scene's memory is here (bench/RESULTS.md, "Memory per triangle"): each
    // temporary goes as soon as it has served, and the arrays are put in BVH order in place.
    Bvh bvh = buildBvh(set.bounds, options);
    std::vector<Aabb>().swap(set.bounds);
    tree.buildSeconds = bvh.buildSeconds;
    tree.sahCost = bvh.sahCost;
    tree.binaryDepth = bvh.maxDepth;
    {
        WideBvh wide = gpuNodes(bvh, what);
        tree.wideDepth = wide.depth;
        for (gpu::GpuBvh4Node& node : wide.nodes)
            for (int i = 0; i < 4; ++i) node.child[i] = offsetChild(node.child[i], tree.root, tree.firstTriangle, what);
        appendAndRelease(flat.nodes, wide.nodes);
    }
    std::vector<uint32_t> order = std::move(bvh.primOrder);
    bvh = Bvh{};
    applyOrderInPlace(order, set);
    appendAndRelease(flat.triangles, set.triangles);
    appendAndRelease(flat.shading, set.shading);
    appendAndRelease(flat.tangents, set.tangents);
    return tree;
}

} // namespace pt
